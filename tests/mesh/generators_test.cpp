// Analytic meshes of seed 3.2.2.1: triangle counts, quality, node roles, reproducibility.
#include <catch2/catch.hpp>
#include <cmath>

#include "valve/analysis/leaflet_metrics.hpp"
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
