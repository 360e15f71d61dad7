// Analytic meshes of seed 3.2.2.1: triangle counts, quality, node roles, reproducibility.
#include <catch2/catch.hpp>
#include <cmath>

#include "valve/analysis/leaflet_metrics.hpp"
#include "valve/core/error.hpp"
#include "valve/mechanics/aortic_root.hpp"
#include "valve/mesh/generators.hpp"
#include "valve/mesh/quality.hpp"
#include "valve/mesh/topology.hpp"
#include "valve/mesh/validate.hpp"

using namespace valve;

TEST_CASE("square patches: 229 ± 1 triangles, mean quality >= 0.95 over 10 seeds", "[mesh][seed]") {
  for (std::uint64_t seed = 1; seed <= 10; ++seed) {
    SquarePatchOptions o;
    o.mesh.seed = seed;
    const TriMesh m = generate_square_patch(o);
    validate_mesh(m, "square");
    const auto q = summarize_quality(triangle_qualities(m.points, m.triangles));
    INFO("seed " << seed);
    CHECK(std::abs(m.num_triangles() - 229) <= 1);
    CHECK(q.mean >= 0.95);
    CHECK(q.min > 0.6);
    // The patch covers the square: total area 15².
    double area = 0;
    for (const auto& t : m.triangles) area += triangle_area(m.points, t);
    CHECK(area == Approx(225.0).epsilon(1e-12));
  }
}

TEST_CASE("clamped disk: flat, its rim fixed on the circle, its area that of the inscribed polygon", "[mesh]") {
  DiskOptions o;
  o.diameter = 20;
  o.mesh.target_triangles = 600;
  const TriMesh m = generate_clamped_disk(o);
  CHECK(std::abs(m.num_triangles() - 600) <= 10);
  double area = 0;
  for (const Tri& t : m.triangles) {
    area += triangle_area(m.points, t);
    CHECK(triangle_normal(m.points, t).z() > 0.999);
  }
  int rim = 0;
  for (int i = 0; i < m.num_nodes(); ++i) {
    CHECK(m.points(i, 2) == 0);
    const double r = m.points.row(i).norm();
    if (m.roles[i] == NodeRole::fixed) {
      ++rim;
      CHECK(r == Approx(10.0).epsilon(1e-12));
      CHECK(m.boundary[i] == BoundaryType::attached);
    } else {
      CHECK(r < 10.0 - 1e-9);
    }
  }
  // The regular rim polygon of n sides inscribed in the circle: n/2 r² sin(2π/n).
  CHECK(area == Approx(0.5 * rim * 100 * std::sin(2 * M_PI / rim)).epsilon(1e-9));
  CHECK(summarize_quality(triangle_qualities(m.points, m.triangles)).mean > 0.95);
}

TEST_CASE("aortic leaflet: semicircle wrapped on the cylinder, fixed along its arc", "[mesh][seed]") {
  LeafletOptions o;
  const TriMesh m = generate_aortic_leaflet(o);
  validate_mesh(m, "leaflet");
  CHECK(std::abs(m.num_triangles() - 221) <= 2);
  CHECK(summarize_quality(triangle_qualities(m.points, m.triangles)).mean >= 0.95);
  const double R = 60.0 / (2 * 3.14159265358979323846);
  for (int i = 0; i < m.num_nodes(); ++i) {
    CHECK(std::hypot(m.points(i, 0), m.points(i, 1)) == Approx(R).epsilon(1e-12));  // on the cylinder
    if (m.boundary[i] == BoundaryType::attached) CHECK(m.roles[i] == NodeRole::fixed);
    if (m.boundary[i] == BoundaryType::free_edge) CHECK(std::abs(m.points(i, 2)) < 1e-12);
  }
  // Normals point toward the axis (the side the aortic pressure pushes to).
  for (const auto& t : m.triangles) {
    const Vec3 c = (m.points.row(t[0]) + m.points.row(t[1]) + m.points.row(t[2])).transpose() / 3.0;
    CHECK(triangle_normal(m.points, t).dot(Vec3(-c.x(), -c.y(), 0).normalized()) > 0.9);
  }
  // Rest dimensions of Table 3.2: free edge 20 mm (an arc, measured by chords), midline 10 mm
  // (measured on the faceted surface, which lies inside the cylinder by up to ~0.01 mm).
  const VecX X = flatten(m.points);
  CHECK(polyline_length(free_edge_polyline(m), X) == Approx(20.0).margin(0.05));
  CHECK(leaflet_midline(m).length(m, X) == Approx(10.0).margin(0.005));
}

TEST_CASE("three-leaflet valve shares the commissure nodes", "[mesh][seed]") {
  LeafletOptions o;
  o.mesh.target_triangles = 221;
  const TriMesh one = generate_aortic_leaflet(o);
  const TriMesh m = generate_three_leaflet_valve(o);
  validate_mesh(m, "valve");
  CHECK(m.num_triangles() == 3 * one.num_triangles());
  CHECK(m.num_nodes() == 3 * one.num_nodes() - 3);
  for (int l = 0; l < 3; ++l) CHECK(free_edge_polyline(m, l).size() == free_edge_polyline(one, 0).size());
}

TEST_CASE("generation is seeded and reproducible, and scales to 20,000 triangles", "[mesh]") {
  SquarePatchOptions o;
  o.mesh.seed = 42;
  const TriMesh a = generate_square_patch(o), b = generate_square_patch(o);
  CHECK(a.points == b.points);
  o.mesh.seed = 43;
  CHECK(!(generate_square_patch(o).points == a.points));
  for (int n : {50, 2000, 20000}) {
    o.mesh.target_triangles = n;
    const TriMesh m = generate_square_patch(o);
    INFO(n);
    CHECK(std::abs(m.num_triangles() - n) <= std::max(2, n / 100));
    CHECK(summarize_quality(triangle_qualities(m.points, m.triangles)).mean >= 0.9);
  }
}

TEST_CASE("mesh validation rejects broken meshes", "[mesh]") {
  TriMesh m = generate_square_patch({});
  TriMesh bad = m;
  bad.triangles.push_back(bad.triangles[3]);
  CHECK_THROWS_WITH(validate_mesh(bad, "x.vtp"), Catch::Contains("duplicate"));
  bad = m;
  bad.triangles[0][1] = 100000;
  CHECK_THROWS_WITH(validate_mesh(bad, "x.vtp"), Catch::Contains("triangle 0"));
  bad = m;
  bad.points(5, 1) = std::nan("");
  CHECK_THROWS_WITH(validate_mesh(bad, "x.vtp"), Catch::Contains("point 5"));
}

TEST_CASE("aortic valve of seed 4.2.1: cusp outline, cylinder, commissures, quality", "[mesh][seed]") {
  const double pi = 3.14159265358979, d = 20, gamma = 22 * pi / 180;
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    AorticValveOptions o;
    o.mesh.seed = seed;
    const TriMesh m = generate_aortic_valve(o);
    validate_mesh(m, "aortic valve");
    const auto q = summarize_quality(triangle_qualities(m.points, m.triangles));
    INFO("seed " << seed);
    CHECK(std::abs(m.num_triangles() - 660) <= 15);
    CHECK(q.mean >= 0.95);
    CHECK(m.initial.rows() == 0);  // native leaflets start unstressed
    // Every node lies on the cylinder of diameter d; the attachment spans from the nadir
    // (z = −(curve depth + commissure height)) to the commissure tops at z = 0.
    const double depth = d * std::pow(std::sin(1.047 / 2), 2) / std::tan(gamma);
    double zmin = 1e9, zmax = -1e9;
    for (int i = 0; i < m.num_nodes(); ++i) {
      CHECK(std::hypot(m.points(i, 0), m.points(i, 1)) == Approx(d / 2).epsilon(1e-9));
      if (m.boundary[i] == BoundaryType::attached) {
        CHECK(m.roles[i] == NodeRole::fixed);
        zmin = std::min(zmin, m.points(i, 2)), zmax = std::max(zmax, m.points(i, 2));
      }
    }
    CHECK(zmin == Approx(-(depth + 5)).margin(1e-9));
    CHECK(zmax == Approx(0).margin(1e-9));
    // Flat area of one cusp: w (depth + h_c) − ∫ d sin²(x/d)/tan γ dx over |x| <= w/2.
    const double w = 1.047 * d, a = w / (2 * d);
    const double expected = w * (depth + 5) - d * d / std::tan(gamma) * (a - std::sin(2 * a) / 2);
    for (int l = 0; l < 3; ++l) {
      double area = 0;
      for (int t = 0; t < m.num_triangles(); ++t)
        if (m.leaflet[t] == l) area += triangle_area(m.points, m.triangles[t]);
      // Chords of the cylinder cut a little area off the curved cusp.
      CHECK(area == Approx(expected).epsilon(0.01));
      const auto edge = free_edge_polyline(m, l);
      CHECK(polyline_length(edge, flatten(m.points)) == Approx(w).epsilon(0.01));
    }
    // Fibers at ±25° to the free edge, mirror-symmetric about each leaflet's midline.
    for (int t = 0; t < m.num_triangles(); ++t) CHECK(std::abs(m.fiber(t, 2)) == Approx(std::sin(25 * pi / 180)).epsilon(1e-9));
  }
}

TEST_CASE("aortic valve fibers descend toward each midline; a negative angle mirrors them", "[mesh][seed]") {
  const double pi = 3.14159265358979;
  for (const double angle : {25.0, -25.0}) {
    AorticValveOptions o;
    o.fiber_angle_deg = angle;
    const TriMesh m = generate_aortic_valve(o);
    int descending = 0, rising = 0, flat = 0;
    for (int t = 0; t < m.num_triangles(); ++t) {
      const auto& tri = m.triangles[t];
      const Vec3 c = (m.points.row(tri[0]) + m.points.row(tri[1]) + m.points.row(tri[2])).transpose() / 3;
      // Angle from the leaflet's midline (leaflet k is centred at 2πk/3), wrapped to (−π, π].
      const double off = std::remainder(std::atan2(c.y(), c.x()) - 2 * pi * m.leaflet[t] / 3, 2 * pi);
      const double phi = std::atan2(c.y(), c.x());
      const Vec3 toward_midline = (off < 0 ? 1.0 : -1.0) * Vec3(-std::sin(phi), std::cos(phi), 0);
      Vec3 f = m.fiber.row(t).transpose();
      if (f.dot(toward_midline) < 0) f = -f;
      (f.z() < -1e-9 ? descending : (f.z() > 1e-9 ? rising : flat)) += 1;
    }
    INFO("fiber angle " << angle);
    // Triangles straddling the midline take their centroid's side; none lies exactly on it.
    CHECK(flat == 0);
    if (angle > 0) CHECK(rising == 0);
    else CHECK(descending == 0);
  }
}

TEST_CASE("aortic valve graft: larger rest shape, sewn in at the root's radius", "[mesh][seed]") {
  AorticValveOptions o;
  o.width_scale[0] = 1.21;
  o.height_scale[0] = 1.27;
  const TriMesh m = generate_aortic_valve(o);
  validate_mesh(m, "graft valve");
  REQUIRE(m.initial.rows() == m.num_nodes());
  double graft_area = 0, native_area = 0, top = -1e9;
  for (int t = 0; t < m.num_triangles(); ++t) (m.leaflet[t] == 0 ? graft_area : native_area) += triangle_area(m.points, m.triangles[t]);
  // Scaling the flat shape by 1.21 x 1.27 scales its area by their product.
  CHECK(graft_area == Approx(1.21 * 1.27 * native_area / 2).epsilon(0.015));
  for (int i = 0; i < m.num_nodes(); ++i) {
    const double r_rest = std::hypot(m.points(i, 0), m.points(i, 1));
    const double r_start = std::hypot(m.initial(i, 0), m.initial(i, 1));
    CHECK(r_start == Approx(10).epsilon(1e-9));                          // all start on the root
    CHECK((r_rest == Approx(12.1).epsilon(1e-9) || r_rest == Approx(10).epsilon(1e-9)));
    CHECK(m.initial(i, 2) == m.points(i, 2));                            // only radial moves
    top = std::max(top, m.points(i, 2));
  }
  // The taller graft reaches 27 % higher above the shared nadir than the native leaflets.
  const double pi = 3.14159265358979, depth = 20 * std::pow(std::sin(1.047 / 2), 2) / std::tan(22 * pi / 180);
  CHECK(top == Approx(0.27 * (depth + 5)).epsilon(1e-6));
  CHECK_THROWS_AS([] { AorticValveOptions b; b.width_scale[1] = 0.9; return generate_aortic_valve(b); }(), InputError);
}

TEST_CASE("a graft starts a gap along the wall from its neighbours' commissures, sharing no node", "[mesh][seed]") {
  for (const auto& [width_scale, height_scale] : {std::pair{1.07, 1.0}, std::pair{1.07, 1.13}, std::pair{1.0, 1.13}}) {
    AorticValveOptions o;
    o.width_scale[0] = width_scale;
    o.height_scale[0] = height_scale;
    const TriMesh m = generate_aortic_valve(o);
    INFO("width scale " << width_scale << ", height scale " << height_scale);
    std::vector<char> on_graft(m.num_nodes(), 0), on_native(m.num_nodes(), 0);
    for (int t = 0; t < m.num_triangles(); ++t)
      for (int c = 0; c < 3; ++c) (m.leaflet[t] == 0 ? on_graft : on_native)[m.triangles[t][c]] = 1;
    double closest = 1e9, widest_angle = 0;
    int shared = 0;
    for (int i = 0; i < m.num_nodes(); ++i) {
      shared += on_graft[i] && on_native[i];
      if (!on_graft[i]) continue;
      widest_angle = std::max(widest_angle, std::abs(std::atan2(m.initial(i, 1), m.initial(i, 0))));
      for (int j = 0; j < m.num_nodes(); ++j)
        if (on_native[j]) closest = std::min(closest, (m.initial.row(i) - m.initial.row(j)).norm());
    }
    // The graft (leaflet 0, centred on angle 0) spans ±(60° less 0.3 mm of the 10 mm root) where
    // it starts; its nearest native node is at least the chord of 0.3 mm away.
    CHECK(shared == 0);
    const double gap_angle = 0.3 / 10;
    CHECK(widest_angle == Approx(1.047 - gap_angle).epsilon(1e-9));
    CHECK(closest >= 2 * 10 * std::sin(gap_angle / 2) - 1e-9);
    CHECK(closest < 1.0);  // still beside them: within a mesh edge (about 0.8 mm)
  }
  AorticValveOptions bad;
  bad.width_scale[0] = 1.07;
  bad.graft_commissure_gap = -0.1;
  CHECK_THROWS_AS(generate_aortic_valve(bad), InputError);
  // Without a graft the gap has nothing to act on and is not checked.
  AorticValveOptions native_only;
  native_only.graft_commissure_gap = -0.1;
  CHECK_NOTHROW(generate_aortic_valve(native_only));
}

TEST_CASE("the root of a valve with a wider graft is the one its leaflets are sewn into", "[mechanics][root]") {
  // A graft's rest shape lies on a cylinder width_scale times the root's; the root is where the
  // leaflets start (radius 10 mm for the 20 mm valve), whatever the graft's width.
  AorticValveOptions native_options;
  const RootGeometry native = root_geometry(generate_aortic_valve(native_options), Vec3::Zero(), Vec3::UnitZ());
  AorticValveOptions graft_options;
  graft_options.width_scale[0] = 1.27;
  const TriMesh graft_valve = generate_aortic_valve(graft_options);
  const RootGeometry graft = root_geometry(graft_valve, Vec3::Zero(), Vec3::UnitZ());
  CHECK(native.mesh_radius == Approx(10).epsilon(1e-9));
  CHECK(graft.mesh_radius == Approx(10).epsilon(1e-9));
  // The wall is shared by attachment length along the root, which the gathered graft does not grow:
  // its nodes' share is about a third, as a native leaflet's.
  std::vector<char> on_graft(graft_valve.num_nodes(), 0);
  for (int t = 0; t < graft_valve.num_triangles(); ++t)
    if (graft_valve.leaflet[t] == 0)
      for (int c = 0; c < 3; ++c) on_graft[graft_valve.triangles[t][c]] = 1;
  double graft_share = 0, total = 0;
  for (size_t k = 0; k < graft.nodes.size(); ++k) {
    total += graft.wall_area[k];
    if (on_graft[graft.nodes[k]]) graft_share += graft.wall_area[k];
  }
  CHECK(graft_share / total == Approx(1.0 / 3).margin(0.03));
}
