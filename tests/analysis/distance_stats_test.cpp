#include <catch2/catch.hpp>

#include "valve/analysis/distance_stats.hpp"
#include "valve/core/error.hpp"

using namespace valve;

TEST_CASE("distance statistics: mean, max, RMS and 95th percentile", "[analysis]") {
  std::vector<double> d;
  for (int i = 0; i <= 100; ++i) d.push_back(i / 100.0);  // 0, 0.01, ..., 1
  const auto s = summarize_distances(d);
  CHECK(s.count == 101);
  CHECK(s.mean == Approx(0.5));
  CHECK(s.max == Approx(1.0));
  CHECK(s.p95 == Approx(0.95));
  // RMS, computed independently of the library:
  double sum2 = 0;
  for (double x : d) sum2 += x * x;
  CHECK(s.rms == Approx(std::sqrt(sum2 / 101)));
}

TEST_CASE("corresponding node distances of a translated mesh equal the translation", "[analysis]") {
  MatX3 a(3, 3), b(3, 3);
  a << 0, 0, 0, 1, 0, 0, 0, 1, 0;
  b = a;
  b.col(2).array() += 2.0;
  for (double x : corresponding_node_distances(a, b)) CHECK(x == Approx(2.0));
  MatX3 c(2, 3);
  c.setZero();
  CHECK_THROWS_AS(corresponding_node_distances(a, c), InputError);
}
