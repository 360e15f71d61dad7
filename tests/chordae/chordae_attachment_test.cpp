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

namespace {
// A tip, a hub, and from the hub a run of three segments through two unbranched points to
// insertion A2 (node 4), besides a direct chord to P1 (node 8). The run's middle segment is
// shortened, as a repair would.
ChordaeNetwork network_with_run() {
  ChordaeNetwork n;
  n.points = {{ChordPointKind::papillary_tip, Vec3(1, 1, -20), -1, "tip"},
              {ChordPointKind::branch, Vec3(1, 1, -10), -1, "hub"},
              {ChordPointKind::branch, Vec3(1.5, 1, -7), -1, ""},
              {ChordPointKind::branch, Vec3(1, 1.5, -3), -1, ""},
              {ChordPointKind::insertion, Vec3(1, 1, 0), -1, "A2"},
              {ChordPointKind::insertion, Vec3(2, 2, 0), -1, "P1"}};
  n.segments = {{0, 1, ChordType::primary}, {1, 2, ChordType::primary}, {2, 3, ChordType::primary},
                {3, 4, ChordType::primary}, {1, 5, ChordType::secondary}};
  n.segments[2].scale = 0.9;
  return n;
}
}  // namespace

TEST_CASE("condensed chains: a run through unbranched points is one rod, its points held and drawn on its line", "[chordae]") {
  const TriMesh grid = test::grid_mesh(2.0);
  ChordaeNetwork n = network_with_run();
  snap_insertions(n, grid.points, 0.5, "c.json");
  ChordMaterial material{std::make_shared<LinearRodLaw>(40.0), {}, 0.0, 1e-3};
  const ChordaeAttachment full = attach_chordae(n, grid.num_nodes(), material);
  REQUIRE(full.rods.size() == 5);  // one per segment, in order
  CHECK(full.segment_rod == std::vector<int>{0, 1, 2, 3, 4});
  material.condense_chains = true;
  const ChordaeAttachment a = attach_chordae(n, grid.num_nodes(), material);
  CHECK(a.point_node == full.point_node);  // every point keeps its node
  REQUIRE(a.rods.size() == 3);
  CHECK(a.segment_rod == std::vector<int>{0, 1, 1, 1, 2});
  const Rod& run = a.rods[1];
  CHECK(run.a == a.point_node[1]);
  CHECK(run.b == 4);
  const double l1 = std::sqrt(0.25 + 9), l2 = 0.9 * std::sqrt(0.25 + 0.25 + 16), l3 = std::sqrt(0.25 + 9);
  CHECK(run.rest_length == Approx(l1 + l2 + l3));
  // The hub free, the run's points held and massless; the hub keeps its mass: half of each
  // segment at it, the run's first included.
  CHECK(a.extra_roles == std::vector<NodeRole>{NodeRole::fixed, NodeRole::free, NodeRole::fixed, NodeRole::fixed});
  const double area = M_PI * 0.25 / 4;
  CHECK(a.extra_mass[1] == Approx(0.5 * 1e-3 * area * (10.0 + std::sqrt(0.25 + 9) + std::sqrt(1 + 1 + 100.0))));
  CHECK(a.extra_mass == std::vector<double>{full.extra_mass[0], full.extra_mass[1], 0.0, 0.0});
  CHECK(a.extra_mass[2] == 0);
  CHECK(a.extra_mass[3] == 0);
  // Drawn on the rod's line at their share of its rest length; tensions per segment from the rods.
  VecX x = flatten(with_chordae_nodes(grid, a).points);
  const MatX3 p = a.point_positions(x);
  const Vec3 hub = p.row(1).transpose(), insertion = p.row(4).transpose();
  CHECK((p.row(2).transpose() - (hub + l1 / run.rest_length * (insertion - hub))).norm() < 1e-12);
  CHECK((p.row(3).transpose() - (hub + (l1 + l2) / run.rest_length * (insertion - hub))).norm() < 1e-12);
  CHECK(a.segment_tensions({1.0, 2.0, 3.0}) == std::vector<double>{1.0, 2.0, 2.0, 2.0, 3.0});
  // A point between two sections ends a run: hub to point 3, then point 3 to A2.
  n.segments[3].area = 0.3;
  const ChordaeAttachment split = attach_chordae(n, grid.num_nodes(), material);
  CHECK(split.segment_rod == std::vector<int>{0, 1, 1, 2, 3});
  CHECK(split.extra_roles[3] == NodeRole::free);
}

TEST_CASE("a condensed run stores the least energy its segments can hold between the same ends", "[chordae]") {
  // Jensen: Σ A L_i W(λ_i) with Σ L_i λ_i = ℓ is least at λ_i = ℓ / Σ L_i when W is convex,
  // which is the condensed rod's A (Σ L_i) W(ℓ / Σ L_i). Checked with the Texas TriValve
  // deck's anterior chordae law (Ogden, α ≈ 98), the steepest in our files.
  const TriMesh grid = test::grid_mesh(2.0);
  ChordaeNetwork n = network_with_run();
  snap_insertions(n, grid.points, 0.5, "c.json");
  OgdenParameters law;
  law.mu = {18.88, 22.68, 19.50};
  law.alpha = {98.25, 98.25, 98.25};
  ChordMaterial material;
  material.default_law = std::make_shared<OgdenRodLaw>(law);
  const ChordaeAttachment full = attach_chordae(n, grid.num_nodes(), material);
  material.condense_chains = true;
  const ChordaeAttachment condensed = attach_chordae(n, grid.num_nodes(), material);
  // The run alone: its three segments against its one rod.
  const ChordaeTerm full_term({full.rods[1], full.rods[2], full.rods[3]}), condensed_term({condensed.rods[1]});
  // The hub pulled 0.3 % past the run's rest length from A2, straight below it.
  VecX x = flatten(with_chordae_nodes(grid, full).points);
  const Vec3 a2 = node3(x, 4);
  const double ell = 1.003 * condensed.rods[1].rest_length;
  x.segment<3>(3 * full.point_node[1]) = a2 - Vec3(0, 0, ell);
  auto energy = [](const ChordaeTerm& term, const VecX& y) {
    double e = 0;
    term.energy(State{y, VecX::Zero(y.size()), 1.0, 0.0}, e);
    return e;
  };
  const double least = energy(condensed_term, x);
  REQUIRE(least > 0);
  // The run's points where the condensed rod draws them: the same energy.
  const MatX3 drawn = condensed.point_positions(x);
  for (int p : {2, 3}) x.segment<3>(3 * full.point_node[p]) = drawn.row(p).transpose();
  CHECK(energy(full_term, x) == Approx(least).epsilon(1e-9));
  // Anywhere else on the line or off it: more.
  for (double shift : {-0.01, 0.01, 0.05})
    for (const Vec3& dir : {Vec3(0, 0, 1), Vec3(1, 0, 0)}) {
      VecX y = x;
      y.segment<3>(3 * full.point_node[2]) += shift * dir;
      CHECK(energy(full_term, y) > least);
    }
}
