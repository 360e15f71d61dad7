// The k-d tree's nearest neighbours against the brute-force scan.
#include <catch2/catch.hpp>

#include <random>

#include "valve/mesh/closest_point.hpp"
#include "valve/mesh/nearest_points.hpp"

using namespace valve;

TEST_CASE("NearestPoints finds the same nearest distance as the scan of every point", "[nearest_points]") {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-20, 20);
  MatX3 points(2000, 3);
  for (int i = 0; i < points.rows(); ++i) points.row(i) << u(rng), u(rng), 0.2 * u(rng);
  const NearestPoints index(points);
  for (int q = 0; q < 500; ++q) {
    const Vec3 p(u(rng), u(rng), u(rng));
    double d_tree = -1, d_scan = -1;
    const int i_tree = index.nearest(p, &d_tree);
    nearest_point_index(points, p, &d_scan);
    // Ties aside the indices agree; the distances always do.
    REQUIRE(d_tree == Approx(d_scan).margin(1e-12));
    REQUIRE((points.row(i_tree).transpose() - p).norm() == Approx(d_tree).margin(1e-12));
  }
}

TEST_CASE("NearestPoints returns the point itself at distance zero and -1 for an empty set", "[nearest_points]") {
  MatX3 points(3, 3);
  points << 0, 0, 0, 1, 0, 0, 0, 2, 0;
  const NearestPoints index(points);
  double d = -1;
  CHECK(index.nearest(Vec3(0, 2, 0), &d) == 2);
  CHECK(d == 0);
  const MatX3 none(0, 3);
  const NearestPoints empty(none);
  CHECK(empty.nearest(Vec3::Zero(), &d) == -1);
}
