// chordae.json: the phantom's network survives a round trip, and the network checks
// (zero-length chord, tree without a papillary tip) reject bad files.
#include <catch2/catch.hpp>
#include <cmath>

#include "valve/chordae/chordae_network.hpp"
#include "valve/core/error.hpp"
#include "valve/phantom/mitral_phantom.hpp"

using namespace valve;

namespace {
nlohmann::json small_tree() {
  return nlohmann::json::parse(R"({
    "diameter_mm": 0.5,
    "points": [{"kind": "papillary_tip", "position": [0, 0, -20]},
               {"kind": "branch", "position": [0, 0, -10]},
               {"kind": "insertion", "position": [1, 0, 0], "mesh_node": 4, "name": "A1"},
               {"kind": "insertion", "position": [-1, 0, 0], "mesh_node": 7}],
    "segments": [{"from": 0, "to": 1, "type": "primary"},
                 {"from": 1, "to": 2, "type": "primary"},
                 {"from": 1, "to": 3, "type": "secondary"}]})");
}
}  // namespace

TEST_CASE("the phantom's chordae survive a JSON round trip", "[chordae]") {
  const MitralPhantom ph = make_mitral_phantom(MitralPhantomOptions{});
  const ChordaeNetwork back = read_chordae_json(to_json(ph.chordae), "phantom.chordae.json");
  REQUIRE(back.points.size() == ph.chordae.points.size());
  REQUIRE(back.segments.size() == ph.chordae.segments.size());
  CHECK(back.diameter == ph.chordae.diameter);
  for (std::size_t i = 0; i < back.points.size(); ++i) {
    CHECK(back.points[i].kind == ph.chordae.points[i].kind);
    CHECK(back.points[i].mesh_node == ph.chordae.points[i].mesh_node);
    CHECK((back.points[i].position - ph.chordae.points[i].position).norm() < 1e-12);
  }
  CHECK(back.count(ChordType::strut) == ph.chordae.count(ChordType::strut));
}

TEST_CASE("chordae.json checks", "[chordae]") {
  const ChordaeNetwork ok = read_chordae_json(small_tree(), "c.json");
  CHECK(ok.count(ChordType::secondary) == 1);
  CHECK(ok.points[2].name == "A1");

  auto doc = small_tree();
  doc["points"][3]["position"] = {0, 0, -10};  // on top of the branch point
  CHECK_THROWS_WITH(read_chordae_json(doc, "c.json"), Catch::Contains("segments[2]") && Catch::Contains("zero length"));

  doc = small_tree();
  doc["points"][0]["kind"] = "branch";  // no papillary tip anywhere
  CHECK_THROWS_WITH(read_chordae_json(doc, "c.json"), Catch::Contains("papillary tip"));

  doc = small_tree();
  doc["points"].push_back({{"kind", "insertion"}, {"position", {5, 5, 0}}});
  CHECK_THROWS_WITH(read_chordae_json(doc, "c.json"), Catch::Contains("points[4]") && Catch::Contains("unconnected"));

  doc = small_tree();
  doc["segments"][1]["to"] = 9;
  CHECK_THROWS_WITH(read_chordae_json(doc, "c.json"), Catch::Contains("segments[1].to"));

  doc = small_tree();
  doc["segments"][0]["type"] = "tertiary";
  CHECK_THROWS_WITH(read_chordae_json(doc, "c.json"), Catch::Contains("segments[0].type"));
}

TEST_CASE("a scale multiplies an explicit rest length too", "[chordae]") {
  // valve-chordae writes every segment's length at scale 1; a later scale (a repair, the
  // scene's chordae.rest_length_scale) must still shorten the chord.
  nlohmann::json doc = small_tree();
  doc["segments"][0]["rest_length_mm"] = 10.0;
  doc["segments"][0]["scale"] = 0.9;
  const ChordaeNetwork net = read_chordae_json(doc, "c.json");
  CHECK(net.unscaled_rest_length(0) == Approx(10.0));
  CHECK(net.rest_length(0) == Approx(9.0));
  const ChordaeNetwork again = read_chordae_json(to_json(net), "c.json");
  CHECK(again.rest_length(0) == Approx(9.0));
  // Without an explicit length: the distance between the ends, times the scale.
  const ChordaeNetwork plain = read_chordae_json(small_tree(), "c.json");
  const double open = (plain.points[plain.segments[0].from].position - plain.points[plain.segments[0].to].position).norm();
  CHECK(plain.rest_length(0) == Approx(open));
}

TEST_CASE("chords of a type keep the trunks that carry them", "[chordae]") {
  // Two tips; a secondary trunk from tip 0 to a branch with a primary and a secondary chord;
  // a second route to the branch from tip 5, longer (14 mm against 10 mm); a secondary chord
  // straight from tip 5 to the leaflet.
  const ChordaeNetwork net = read_chordae_json(nlohmann::json::parse(R"({
    "points": [{"kind": "papillary_tip", "position": [0, 0, -20]},
               {"kind": "branch", "position": [0, 0, -10]},
               {"kind": "insertion", "position": [1, 0, 0], "mesh_node": 4},
               {"kind": "insertion", "position": [-1, 0, 0], "mesh_node": 7},
               {"kind": "branch", "position": [0, 10, -10]},
               {"kind": "papillary_tip", "position": [0, 14, -10]},
               {"kind": "insertion", "position": [0, 14, 0], "mesh_node": 9}],
    "segments": [{"from": 0, "to": 1, "type": "secondary"},
                 {"from": 1, "to": 2, "type": "primary"},
                 {"from": 1, "to": 3, "type": "secondary"},
                 {"from": 1, "to": 4, "type": "secondary"},
                 {"from": 4, "to": 5, "type": "secondary"},
                 {"from": 5, "to": 6, "type": "secondary"}]})"), "c.json");
  const ChordaeNetwork primary = chords_of_types(net, {"primary"});
  REQUIRE(primary.segments.size() == 2);  // the primary chord and the 10 mm trunk, not the 14 mm route
  CHECK(primary.count(ChordType::primary) == 1);
  CHECK(primary.count(ChordPointKind::papillary_tip) == 1);
  CHECK(primary.count(ChordPointKind::insertion) == 1);
  double length = 0;
  for (int s = 0; s < 2; ++s) length += primary.rest_length(s);
  CHECK(length == Approx(10 + std::sqrt(101.0)));
  // Every type: the whole network; secondary only: everything but the primary chord.
  CHECK(chords_of_types(net, {"primary", "secondary", "strut"}).segments.size() == net.segments.size());
  CHECK(chords_of_types(net, {"secondary"}).segments.size() == net.segments.size() - 1);
  CHECK(chords_of_types(net, {"strut"}).segments.empty());
}

TEST_CASE("chords of a type keep their points in the file's order", "[chordae]") {
  // Tip 3 is listed after tip 0 but its chord comes first: the kept tips stay 0 then 3, so a
  // list of closed-state tip positions in file order still matches them.
  const ChordaeNetwork net = read_chordae_json(nlohmann::json::parse(R"({
    "points": [{"kind": "papillary_tip", "position": [0, 0, -20], "name": "first"},
               {"kind": "insertion", "position": [1, 0, 0], "mesh_node": 4},
               {"kind": "insertion", "position": [-1, 0, 0], "mesh_node": 7},
               {"kind": "papillary_tip", "position": [0, 5, -20], "name": "second"}],
    "segments": [{"from": 3, "to": 2, "type": "primary"},
                 {"from": 0, "to": 1, "type": "primary"}]})"), "c.json");
  const ChordaeNetwork kept = chords_of_types(net, {"primary"});
  REQUIRE(kept.points.size() == 4);
  CHECK(kept.points[0].name == "first");
  CHECK(kept.points[3].name == "second");
  CHECK(kept.segments[0].from == 3);
}
