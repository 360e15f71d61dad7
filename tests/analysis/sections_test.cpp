// Cut-plane sections (analysis/sections.hpp): the frame of an elliptic ring and the cut of
// a flat square, checked against hand-computed geometry.
#include <Eigen/Geometry>
#include <catch2/catch.hpp>
#include <cmath>

#include "valve/analysis/sections.hpp"

using namespace valve;

TEST_CASE("section frame: planes across the ring's long axis at evenly spaced stations", "[analysis]") {
  // Ellipse 15 x 10 mm in z = 2, centred at (1, 0, 2): long axis x.
  MatX3 ring(72, 3);
  for (int i = 0; i < 72; ++i) ring.row(i) << 1 + 15 * std::cos(2 * M_PI * i / 72), 10 * std::sin(2 * M_PI * i / 72), 2;
  const SectionFrame f = section_frame(ring, 3, Vec3(0, 0, 1));
  CHECK((f.origin - Vec3(1, 0, 2)).norm() < 1e-9);
  CHECK(std::abs(f.axis.x()) == Approx(1).epsilon(1e-9));
  CHECK(f.v.z() == Approx(1).epsilon(1e-9));  // oriented by `up`
  CHECK(f.axis.cross(f.u).dot(f.v) == Approx(1).epsilon(1e-9));
  REQUIRE(f.offsets.size() == 3);
  // Quarter points of [-15, 15].
  const double sign = f.axis.x() > 0 ? 1 : -1;
  CHECK(sign * f.offsets[0] == Approx(-7.5).epsilon(1e-3));
  CHECK(f.offsets[1] == Approx(0).margin(1e-9));
  CHECK(sign * f.offsets[2] == Approx(7.5).epsilon(1e-3));
}

TEST_CASE("cut sections of a flat square give one straight line per plane", "[analysis]") {
  // A 10 x 10 mm square in z = 0 of 8 triangles, cut by x = -2.5, 0, 2.5 (frame given).
  TriMesh m;
  m.points.resize(9, 3);
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i) m.points.row(3 * j + i) << -5 + 5 * i, -5 + 5 * j, 0;
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 2; ++i) {
      const int a = 3 * j + i;
      m.triangles.emplace_back(a, a + 1, a + 4);
      m.triangles.emplace_back(a, a + 4, a + 3);
    }
  SectionFrame f;
  f.offsets = {-2.5, 0.0, 2.5};
  const auto segs = cut_sections(m, m.points, f);
  for (int p = 0; p < 3; ++p) {
    double length = 0, vmax = 0, umin = 1e9, umax = -1e9;
    for (const auto& g : segs) {
      if (g.plane != p) continue;
      length += std::hypot(g.u1 - g.u0, g.v1 - g.v0);
      vmax = std::max({vmax, std::abs(g.v0), std::abs(g.v1)});
      umin = std::min({umin, g.u0, g.u1}), umax = std::max({umax, g.u0, g.u1});
    }
    INFO("plane " << p);
    CHECK(length == Approx(10).epsilon(1e-9));  // across the whole square, no segment twice
    CHECK(vmax < 1e-12);                        // in the sheet's plane
    CHECK(umin == Approx(-5));
    CHECK(umax == Approx(5));
  }
}
