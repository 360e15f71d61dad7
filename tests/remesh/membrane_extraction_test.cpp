// Atrial-face extraction from a closed thick sheet, and the atrial direction estimate.
#include <catch2/catch.hpp>
#include <Eigen/Geometry>
#include <cmath>

#include "valve/core/error.hpp"
#include "valve/mesh/quality.hpp"
#include "valve/remesh/membrane_extraction.hpp"

using namespace valve;

namespace {
// The closed surface of a w × w × t slab centred at the origin, faces split into n × n
// squares on the large faces (outward normals), and the rim in n × 1 strips.
TriMesh slab(double w, double t, int n) {
  TriMesh m;
  std::vector<Vec3> pts;
  auto quad = [&](const Vec3& o, const Vec3& u, const Vec3& v, int nu, int nv) {
    const int base = static_cast<int>(pts.size());
    for (int j = 0; j <= nv; ++j)
      for (int i = 0; i <= nu; ++i) pts.push_back(o + u * (double(i) / nu) + v * (double(j) / nv));
    for (int j = 0; j < nv; ++j)
      for (int i = 0; i < nu; ++i) {
        const int a = base + j * (nu + 1) + i, b = a + 1, c = a + nu + 2, d = a + nu + 1;
        m.triangles.push_back({a, b, c});
        m.triangles.push_back({a, c, d});
      }
  };
  const double h = w / 2, z = t / 2;
  quad(Vec3(-h, -h, z), Vec3(w, 0, 0), Vec3(0, w, 0), n, n);     // top, normal +z
  quad(Vec3(-h, h, -z), Vec3(w, 0, 0), Vec3(0, -w, 0), n, n);    // bottom, normal -z
  quad(Vec3(-h, -h, -z), Vec3(w, 0, 0), Vec3(0, 0, t), n, 1);    // y = -h, normal -y
  quad(Vec3(h, h, -z), Vec3(-w, 0, 0), Vec3(0, 0, t), n, 1);     // y = +h, normal +y
  quad(Vec3(h, -h, -z), Vec3(0, w, 0), Vec3(0, 0, t), n, 1);     // x = +h, normal +x
  quad(Vec3(-h, h, -z), Vec3(0, -w, 0), Vec3(0, 0, t), n, 1);    // x = -h, normal -x
  m.points.resize(static_cast<Eigen::Index>(pts.size()), 3);
  for (std::size_t i = 0; i < pts.size(); ++i) m.points.row(static_cast<Eigen::Index>(i)) = pts[i].transpose();
  m.fill_defaults();
  return m;  // not welded: the extraction only needs each face's own normal and neighbours
}
}  // namespace

TEST_CASE("the atrial face of a slab is its top face", "[remesh][membrane]") {
  const TriMesh s = slab(20, 1, 40);
  MembraneOptions o;
  o.atrial_direction = Vec3::UnitZ();
  MembraneSummary summary;
  const TriMesh top = extract_atrial_membrane(s, o, &summary);
  // The top face is one piece of 2 × 40 × 40 triangles at z = t/2 (the rim faces look
  // sideways and the viewpoint is far above: they are split by the smoothing).
  CHECK(summary.pieces_kept == 1);
  CHECK(summary.area_mm2 == Approx(400).epsilon(0.02));
  for (int i = 0; i < top.num_nodes(); ++i) CHECK(top.points(i, 2) == Approx(0.5).margin(1e-9));
  o.atrial_direction = -Vec3::UnitZ();
  const TriMesh bottom = extract_atrial_membrane(s, o, &summary);
  for (int i = 0; i < bottom.num_nodes(); ++i) CHECK(bottom.points(i, 2) == Approx(-0.5).margin(1e-9));
}

TEST_CASE("the atrial direction of a funnel points to its wide end", "[remesh][membrane]") {
  // A funnel along the axis a: radius 15 mm at the top (annulus), 8 mm 10 mm below.
  const Vec3 axis = Vec3(0.2, -0.3, 1).normalized();
  const Vec3 u = axis.unitOrthogonal(), v = axis.cross(u);
  MatX3 pts(36 * 11, 3);
  int k = 0;
  for (int j = 0; j <= 10; ++j)
    for (int i = 0; i < 36; ++i, ++k) {
      const double a = 2 * 3.14159265358979 * i / 36, r = 15 - 0.7 * j;
      pts.row(k) = (r * std::cos(a) * u + r * std::sin(a) * v - double(j) * axis).transpose();
    }
  CHECK(estimate_atrial_direction(pts).dot(axis) > 0.999);
}

namespace {
// A funnel-shaped ring membrane: nodes on `rings` circles of 24, radius 20 mm at z = 1
// (the outer loop, the annulus) down to 10 mm at z = 0 (the inner loop, the free edge).
TriMesh ring_membrane(int rings = 3) {
  TriMesh m;
  const int n = 24;
  m.points.resize(n * rings, 3);
  for (int j = 0; j < rings; ++j)
    for (int i = 0; i < n; ++i) {
      const double a = 2 * 3.14159265358979 * i / n, s = double(j) / (rings - 1), r = 20 - 10 * s;
      m.points.row(j * n + i) << r * std::cos(a), r * std::sin(a), 1 - s;
    }
  for (int j = 0; j + 1 < rings; ++j)
    for (int i = 0; i < n; ++i) {
      const int a = j * n + i, b = j * n + (i + 1) % n, c = a + n, d = b + n;
      m.triangles.push_back({a, b, d});
      m.triangles.push_back({a, d, c});
    }
  m.fill_defaults();
  return m;
}
}  // namespace

TEST_CASE("the annulus can be taken from a landmark instead of the outer loop", "[remesh][membrane]") {
  TriMesh reference = ring_membrane();
  REQUIRE(mark_annulus_and_free_edge(reference, Vec3::UnitZ()) == 2);
  // The reference's annulus is its outer loop: 24 edges on the 20 mm circle.
  const auto all = annulus_segments(reference, "reference.vtp");
  CHECK(all.size() == 24);
  for (const auto& [a, b] : all) {
    CHECK(std::hypot(a.x(), a.y()) == Approx(20));
    CHECK(a.z() == Approx(1));
  }
  // Half of that ring as the landmark (angles 0..180°): the outer-loop nodes on that half
  // (0°, 15°, ..., 180°: 13) are annulus; the other 11 and the inner loop's 24 free edge.
  std::vector<std::pair<Vec3, Vec3>> half;
  for (const auto& s : all)
    if (s.first.y() >= -1e-9 && s.second.y() >= -1e-9) half.push_back(s);
  REQUIRE(half.size() == 12);
  TriMesh mesh = ring_membrane();
  CHECK(mark_annulus_near(mesh, half, 0.5, Vec3::UnitZ()) == 2);
  int annulus = 0, free_edge = 0;
  for (int v = 0; v < mesh.num_nodes(); ++v) {
    const bool on_half = v < 24 && mesh.points(v, 1) >= -1e-9;
    CHECK((mesh.boundary[v] == BoundaryType::attached) == on_half);
    CHECK((mesh.roles[v] == NodeRole::fixed) == on_half);
    annulus += mesh.boundary[v] == BoundaryType::attached;
    free_edge += mesh.boundary[v] == BoundaryType::free_edge;
  }
  CHECK(annulus == 13);
  CHECK(free_edge == 11 + 24);
  // Fibers along the annulus: perpendicular to the radius, up to the projection onto each
  // flat facet, whose normal leans a little out of the centroid's radial plane (< 0.01).
  for (int t = 0; t < mesh.num_triangles(); ++t) {
    const Vec3 f = mesh.fiber.row(t).transpose();
    const Tri& tri = mesh.triangles[t];
    const Vec3 c = (mesh.points.row(tri[0]) + mesh.points.row(tri[1]) + mesh.points.row(tri[2])).transpose() / 3;
    CHECK(std::abs(f.dot(Vec3(c.x(), c.y(), 0).normalized())) < 0.01);
  }
  // A landmark 5 mm above the valve marks nothing within 2 mm: an error, not a valve
  // without an annulus.
  std::vector<std::pair<Vec3, Vec3>> lifted = half;
  for (auto& [a, b] : lifted) a.z() += 5, b.z() += 5;
  CHECK_THROWS_AS(mark_annulus_near(mesh, lifted, 2.0, Vec3::UnitZ()), InputError);
  // A reference without a marked annulus is refused.
  CHECK_THROWS_AS(annulus_segments(ring_membrane(), "plain.vtp"), InputError);
}

TEST_CASE("a given membrane keeps every face and the atrial direction given or estimated", "[remesh][membrane]") {
  const TriMesh m = ring_membrane();
  const MembraneSummary given = describe_given_membrane(m, Vec3(0, 0, 2));
  CHECK(given.atrial_direction == Vec3::UnitZ());
  CHECK_FALSE(given.direction_estimated);
  CHECK(given.faces_in == 2 * 24 * 2);
  CHECK(given.faces_kept == given.faces_in);
  // Without one: the funnel's wide end is up, so the estimate is +z.
  const MembraneSummary estimated = describe_given_membrane(m, std::nullopt);
  CHECK(estimated.direction_estimated);
  CHECK(estimated.atrial_direction.z() > 0.999);
}
