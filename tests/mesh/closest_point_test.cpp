// Closest-point helpers against hand-computed distances.
#include <catch2/catch.hpp>
#include <cmath>

#include "valve/mesh/closest_point.hpp"

using namespace valve;

TEST_CASE("point_segment_distance: perpendicular inside, nearest end outside, a point for no length", "[mesh]") {
  const Vec3 a(0, 0, 0), b(4, 0, 0);
  CHECK(point_segment_distance(Vec3(1, 3, 0), a, b) == Approx(3.0));        // foot at (1, 0, 0)
  CHECK(point_segment_distance(Vec3(7, 4, 0), a, b) == Approx(5.0));        // beyond b: |(3, 4)|
  CHECK(point_segment_distance(Vec3(-1, 0, 0), a, b) == Approx(1.0));       // before a
  CHECK(point_segment_distance(Vec3(2, 0, 0), a, b) == Approx(0.0).margin(1e-15));
  CHECK(point_segment_distance(Vec3(0, 2, 2), a, a) == Approx(std::sqrt(8.0)));  // degenerate segment
}
