// Projected orifice (analysis/orifice.hpp) of flat sheets with a known gap between them.
#include <catch2/catch.hpp>
#include <Eigen/Geometry>
#include <cmath>

#include "valve/analysis/orifice.hpp"
#include "valve/core/error.hpp"

using namespace valve;

namespace {

// Structured sheet [x0, x1] x [-5, 5] in z = 0 (cells of about 0.5 mm), leaflet `leaflet`;
// the side x = free_x is its free edge, the rest of its border attached.
void add_sheet(TriMesh& m, double x0, double x1, double free_x, int leaflet) {
  const int nx = std::max(1, static_cast<int>(std::lround((x1 - x0) / 0.5))), ny = 20;
  const int base = m.num_nodes();
  m.points.conservativeResize(base + (nx + 1) * (ny + 1), 3);
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) {
      const double x = x0 + (x1 - x0) * i / nx, y = -5 + 10.0 * j / ny;
      m.points.row(base + j * (nx + 1) + i) << x, y, 0;
      const bool border = i == 0 || i == nx || j == 0 || j == ny;
      const bool free = std::abs(x - free_x) < 1e-12 && j > 0 && j < ny;
      m.boundary.push_back(free ? BoundaryType::free_edge : border ? BoundaryType::attached : BoundaryType::interior);
    }
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const int a = base + j * (nx + 1) + i, b = a + 1, c = a + nx + 2, d = a + nx + 1;
      m.triangles.emplace_back(a, b, c);
      m.triangles.emplace_back(a, c, d);
      m.leaflet.push_back(leaflet);
      m.leaflet.push_back(leaflet);
    }
}

// Two sheets over [-5, -g/2] and [g/2, 5]: a gap of width g along y between their free edges.
TriMesh split_square(double gap) {
  TriMesh m;
  add_sheet(m, -5, -gap / 2, -gap / 2, 0);
  add_sheet(m, gap / 2, 5, gap / 2, 1);
  m.fill_defaults();
  return m;
}

}  // namespace

TEST_CASE("orifice: the gap between two sheets, narrowed by their thickness", "[analysis][orifice]") {
  // Cross-section: the 10 x 10 square (the attached borders, the chord across the gap's ends
  // included). Opening: the strip between the free edges, (g - 2 r) x 10 mm. Pixel-centre
  // counting errs by at most a pixel along the strip's two long sides: 2 x 10 x 0.02 mm².
  const ValveAxis axis{Vec3(0, 0, 0), Vec3(0, 0, 1)};
  const TriMesh m = split_square(1.0);
  const VecX x = flatten(m.points);
  const OrificeResult thin = projected_orifice(m, x, axis, 0.0);
  CHECK(thin.cross_section_mm2 == Approx(100).epsilon(1e-12));
  CHECK(thin.area_mm2 == Approx(1.0 * 10).margin(0.4));
  CHECK(projected_orifice(m, x, axis, 0.25).area_mm2 == Approx(0.5 * 10).margin(0.4));
  CHECK(projected_orifice(m, x, axis, 0.5).area_mm2 == 0);  // thick enough to touch
  // Sheets 0.25 mm apart (the contact's separation) with half the 0.5 mm threshold: sealed.
  const TriMesh touching = split_square(0.25);
  CHECK(projected_orifice(touching, flatten(touching.points), axis, 0.25).area_mm2 == 0);
  // Seen along the sheets' plane the ring collapses onto a line through the axis, and from
  // an axis beside the sheets it is seen from outside: neither has a cross-section.
  CHECK(projected_orifice(m, x, ValveAxis{Vec3(0, 0, 0), Vec3(1, 0, 0)}, 0.25).area_mm2 == -1);
  const OrificeResult beside = projected_orifice(m, x, ValveAxis{Vec3(7, 0, 0), Vec3(0, 0, 1)}, 0.25);
  CHECK(beside.area_mm2 == -1);
  CHECK(beside.cross_section_mm2 == -1);
  // An axis anywhere inside the ring gives the same opening.
  CHECK(projected_orifice(m, x, ValveAxis{Vec3(-3, 2, 5), Vec3(0, 0, -1)}, 0.25).area_mm2 == Approx(0.5 * 10).margin(0.4));
}

TEST_CASE("orifice: a triangle inside a frame covers its own area widened by the dilation", "[analysis][orifice]") {
  // A square frame [-5, 5]² minus [-4, 4]² (its outer corners attached: the cross-section is
  // the 10 x 10 square) and one slanted triangle inside it. Dilated by r the frame leaves the
  // square (8 - 2r)² open, less the triangle's own dilation: its area, its perimeter times r
  // and a disc of radius r (Steiner's formula for a convex set). Pixel centres err by at
  // most a pixel along every border: (4 x 6 + 12) mm x 0.01 mm, under 0.4 mm².
  TriMesh m;
  m.points.resize(11, 3);
  m.points << -5, -5, 0, 5, -5, 0, 5, 5, 0, -5, 5, 0, -4, -4, 0, 4, -4, 0, 4, 4, 0, -4, 4, 0,  //
      -1, -1, 0, 1.5, -0.5, 0, 0, 1.2, 0;
  for (int k = 0; k < 4; ++k) {
    const int a = k, b = (k + 1) % 4;
    m.triangles.emplace_back(a, b, 4 + b);
    m.triangles.emplace_back(a, 4 + b, 4 + a);
  }
  m.triangles.emplace_back(8, 9, 10);
  m.leaflet.assign(8, 0);
  m.leaflet.push_back(1);
  m.boundary.assign(4, BoundaryType::attached);
  m.boundary.resize(8, BoundaryType::interior);
  m.boundary.resize(11, BoundaryType::free_edge);
  m.fill_defaults();
  const VecX x = flatten(m.points);
  const Vec3 a = m.points.row(8), b = m.points.row(9), c = m.points.row(10);
  const double area = 0.5 * (b - a).cross(c - a).norm(), perimeter = (b - a).norm() + (c - b).norm() + (a - c).norm();
  const ValveAxis axis{Vec3(0, 0, 0), Vec3(0, 0, 1)};
  for (const double r : {0.0, 0.5, 1.0}) {
    const double open = (8 - 2 * r) * (8 - 2 * r) - (area + perimeter * r + M_PI * r * r);
    CHECK(projected_orifice(m, x, axis, r, 0.01).area_mm2 == Approx(open).margin(0.4));
  }
}

TEST_CASE("orifice: the same after a rigid motion of valve and axis", "[analysis][orifice]") {
  const TriMesh m = split_square(2.0);
  const Mat3 R = Eigen::AngleAxisd(0.9, Vec3(1, -2, 0.5).normalized()).toRotationMatrix();
  const Vec3 t(3, -7, 11);
  VecX x = flatten(m.points);
  for (int i = 0; i < m.num_nodes(); ++i) x.segment<3>(3 * i) = R * x.segment<3>(3 * i) + t;
  const OrificeResult r = projected_orifice(m, x, ValveAxis{t, R * Vec3(0, 0, 2)}, 0.25);
  CHECK(r.cross_section_mm2 == Approx(100).epsilon(1e-9));
  CHECK(r.area_mm2 == Approx(1.5 * 10).margin(0.4));
}

TEST_CASE("orifice: without attached nodes there is no cross-section; bad arguments throw", "[analysis][orifice]") {
  TriMesh m = split_square(1.0);
  const VecX x = flatten(m.points);
  const ValveAxis axis{Vec3(0, 0, 0), Vec3(0, 0, 1)};
  CHECK_THROWS_AS(projected_orifice(m, x, axis, -0.1), InputError);
  CHECK_THROWS_AS(projected_orifice(m, x, axis, 0.25, 0.0), InputError);
  CHECK_THROWS_AS(projected_orifice(m, x, ValveAxis{Vec3(0, 0, 0), Vec3(0, 0, 0)}, 0.25), InputError);
  CHECK_THROWS_AS(projected_orifice(m, VecX::Zero(6), axis, 0.25), InputError);
  VecX bad = x;
  bad[4] = std::nan("");
  CHECK_THROWS_AS(projected_orifice(m, bad, axis, 0.25), InputError);
  for (auto& b : m.boundary) b = BoundaryType::free_edge;
  const OrificeResult none = projected_orifice(m, x, axis, 0.25);
  CHECK(none.area_mm2 == -1);
  CHECK(none.cross_section_mm2 == -1);
}
