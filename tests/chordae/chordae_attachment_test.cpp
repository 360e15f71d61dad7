// Chordae on a mesh: snapping (and its error naming the chord), extra nodes for tips and
// branch points, rest lengths with a per-chord scale, the chords' mass at branch points.
#include <catch2/catch.hpp>

#include "support/test_meshes.hpp"
#include "valve/chordae/chordae_attachment.hpp"
#include "valve/core/error.hpp"

using namespace valve;

namespace {
// Tip below the 2 mm grid (z = 0), a branch, two insertions just off nodes 4 and 8.
ChordaeNetwork small_network() {
  ChordaeNetwork n;
  n.points = {{ChordPointKind::papillary_tip, Vec3(1, 1, -20), -1, "tip"},
              {ChordPointKind::branch, Vec3(1, 1, -10), -1, ""},
              {ChordPointKind::insertion, Vec3(1.1, 0.9, 0.05), -1, "A2"},
              {ChordPointKind::insertion, Vec3(1.95, 2.05, 0), -1, "P1"}};
  n.segments = {{0, 1, ChordType::primary}, {1, 2, ChordType::primary}, {1, 3, ChordType::secondary}};
  return n;
}
}  // namespace

TEST_CASE("insertions snap to the nearest node; one too far is an error naming the chord", "[chordae]") {
  const TriMesh grid = test::grid_mesh(2.0);
  ChordaeNetwork n = small_network();
  snap_insertions(n, grid.points, 0.5, "c.json");
  CHECK(n.points[2].mesh_node == 4);
  CHECK(n.points[3].mesh_node == 8);
  CHECK((n.points[2].position - Vec3(1, 1, 0)).norm() < 1e-12);

  ChordaeNetwork far = small_network();
  far.points[3].position = Vec3(5, 5, 0);  // 4.24 mm from node 8
  CHECK_THROWS_WITH(snap_insertions(far, grid.points, 1.0, "c.json"),
                    Catch::Contains("points[3] (chord P1)") && Catch::Contains("4.24 mm"));
}

TEST_CASE("attachment appends tips and branch points, scales rest lengths, lumps chord mass", "[chordae]") {
  const TriMesh grid = test::grid_mesh(2.0);
  ChordaeNetwork n = small_network();
  snap_insertions(n, grid.points, 0.5, "c.json");
  n.segments[1].scale = 0.9;  // a shortened chord
  const ChordaeAttachment a = attach_chordae(n, grid.num_nodes(), ChordMaterial{std::make_shared<LinearRodLaw>(40.0), {}, 0.0, 1e-3});
  REQUIRE(a.extra_points.rows() == 2);
  CHECK(a.point_node == std::vector<int>{9, 10, 4, 8});
  CHECK(a.extra_roles[0] == NodeRole::fixed);
  CHECK(a.extra_roles[1] == NodeRole::free);
  REQUIRE(a.rods.size() == 3);
  CHECK(a.rods[0].rest_length == Approx(10.0));
  CHECK(a.rods[1].rest_length == Approx(0.9 * 10.0));
  CHECK(a.rods[2].rest_length == Approx(std::sqrt(1 + 1 + 100.0)));
  CHECK(a.rods[0].area == Approx(M_PI * 0.25 / 4));
  CHECK(a.rods[0].law->name() == "linear");
  // Branch point: half of each of its three chords' mass, ρ A L / 2.
  const double area = M_PI * 0.25 / 4;
  CHECK(a.extra_mass[1] == Approx(0.5 * 1e-3 * area * (10.0 + 10.0 + std::sqrt(102.0))));
  const TriMesh m = with_chordae_nodes(grid, a);
  CHECK(m.num_nodes() == 11);
  CHECK(m.num_triangles() == grid.num_triangles());
  CHECK(m.roles[9] == NodeRole::fixed);
}

TEST_CASE("a segment naming a chord law takes it and its own section; the rest take the default", "[chordae]") {
  const TriMesh grid = test::grid_mesh(2.0);
  ChordaeNetwork n = small_network();
  snap_insertions(n, grid.points, 0.5, "c.json");
  n.segments[1].material = "Anterior_Chordae";
  n.segments[1].area = 0.356;
  n.segments[2].area = 0.3;  // its own section, with the default law
  OgdenParameters p;
  p.mu = {18.9, 0, 0};
  p.alpha = {98.3, 1, 1};
  ChordMaterial material;
  material.named_laws["Anterior_Chordae"] = std::make_shared<OgdenRodLaw>(p);
  const ChordaeAttachment a = attach_chordae(n, grid.num_nodes(), material);
  CHECK(a.rods[0].law->name() == "linear");
  CHECK(a.rods[0].area == Approx(M_PI * 0.25 / 4));  // the network's 0.5 mm diameter
  CHECK(a.rods[1].law->name() == "ogden");
  CHECK(a.rods[1].area == Approx(0.356));
  CHECK(a.rods[2].law->name() == "linear");
  CHECK(a.rods[2].area == Approx(0.3));
  material.diameter = 0.6;  // the scene's diameter sets every section
  const ChordaeAttachment b = attach_chordae(n, grid.num_nodes(), material);
  for (const Rod& r : b.rods) CHECK(r.area == Approx(M_PI * 0.36 / 4));
}
