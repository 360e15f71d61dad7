// A network put on a small mesh: snapped, typed by where it lands, scaled, rest lengths fixed.
#include <catch2/catch.hpp>

#include "support/test_meshes.hpp"
#include "valve/chordae/chordae_placement.hpp"
#include "valve/core/error.hpp"

using namespace valve;

namespace {
// 3 x 3 grid of 2 mm (nodes 3 j + i at (i, j, 0)); node 1 on the free edge. One tip 4 mm
// below node 4 feeds two chords: to (1.1, 0, 0) near node 1 and to (1, 1.9, 0) near node 7.
struct Fixture {
  TriMesh mesh = test::grid_mesh(2.0);
  ChordaeNetwork net;
  Fixture() {
    mesh.boundary[1] = BoundaryType::free_edge;
    net.points = {{ChordPointKind::papillary_tip, Vec3(1, 1, -4)},
                  {ChordPointKind::insertion, Vec3(1.1, 0, 0)},
                  {ChordPointKind::insertion, Vec3(1, 1.9, 0)}};
    ChordSegment a, b;
    a.from = 0, a.to = 1, b.from = 0, b.to = 2;
    net.segments = {a, b};
  }
};
}  // namespace

TEST_CASE("chordae placement: snapped to nodes, typed by landing, scaled, rest lengths fixed", "[chordae]") {
  Fixture f;
  ChordaePlacementOptions o;
  o.segment_scales = {"1=0.9"};
  const ChordaeNetwork net = place_chordae(f.net, f.mesh, o, "curves.mrk.json");
  CHECK(net.points[1].mesh_node == 1);
  CHECK(net.points[2].mesh_node == 7);
  CHECK(net.points[1].position == Vec3(1, 0, 0));
  CHECK(net.segments[0].type == ChordType::primary);  // lands on the free edge
  CHECK(net.segments[1].type == ChordType::secondary);
  // |(1, 1, -4) - (1, 0, 0)| = sqrt(17), the same to node 7.
  CHECK(net.segments[0].rest_length == Approx(std::sqrt(17.0)));
  CHECK(net.segments[1].rest_length == Approx(std::sqrt(17.0)));
  CHECK(net.rest_length(1) == Approx(0.9 * std::sqrt(17.0)));

  const nlohmann::json m = chordae_metrics(net);
  CHECK(m["segments"] == 2);
  CHECK(m["primary"] == 1);
  CHECK(m["insertions"] == 2);
  CHECK(m["papillary_tips"] == 1);
  CHECK(m["total_rest_length_mm"].get<double>() == Approx(1.9 * std::sqrt(17.0)));
  CHECK(m["longest_segment_mm"].get<double>() == Approx(std::sqrt(17.0)));

  // A chordae.json keeps its types.
  o.type_by_insertion = false;
  o.segment_scales.clear();
  f.net.segments[0].type = ChordType::strut;
  CHECK(place_chordae(f.net, f.mesh, o, "chordae.json").segments[0].type == ChordType::strut);
}

TEST_CASE("chordae placement: scales naming no segment and far insertions are refused", "[chordae]") {
  Fixture f;
  ChordaePlacementOptions o;
  for (const char* bad : {"2=0.9", "0=6", "0", "-1=1"}) {
    o.segment_scales = {bad};
    CHECK_THROWS_WITH(place_chordae(f.net, f.mesh, o, "c.json"),
                      std::string("valve-chordae: --scale: expected SEGMENT=FACTOR with SEGMENT in [0, 1] and FACTOR in [0.2, 5], found \"") +
                          bad + "\"");
  }
  o.segment_scales.clear();
  o.snap_tolerance_mm = 0.05;  // the first insertion is 0.1 mm from its node
  CHECK_THROWS_AS(place_chordae(f.net, f.mesh, o, "c.json"), InputError);
}

TEST_CASE("chordae extraction summary as the stage reports it", "[chordae]") {
  ChordaeExtractionSummary s;
  s.chordae_voxels = 1200, s.skeleton_voxels = 300, s.spurs_removed = 4, s.tips_on_other_tissue = 1, s.convergence_tips = 2;
  const nlohmann::json j = to_json(s);
  CHECK(j["chordae_voxels"] == 1200);
  CHECK(j["skeleton_voxels"] == 300);
  CHECK(j["spurs_removed"] == 4);
  CHECK(j["tips_on_other_tissue"] == 1);
  CHECK(j["convergence_tips"] == 2);
  CHECK(j.size() == 8);
}
