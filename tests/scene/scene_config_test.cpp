#include <catch2/catch.hpp>
#include <set>

#include "valve/core/units.hpp"
#include "valve/scene/scene_config.hpp"

using namespace valve;

namespace {
const SceneKeyRow* find_row(const std::vector<SceneKeyRow>& rows, const std::string& path, const std::string& when = "") {
  for (const auto& r : rows)
    if (r.key.path == path && r.applies_when == when) return &r;
  return nullptr;
}
}  // namespace

TEST_CASE("the scene key table lists every block's keys with the defaults the parser applies", "[scene][config]") {
  const auto rows = scene_key_table();
  std::set<std::string> blocks;
  for (const auto& r : rows) blocks.insert(r.key.path.substr(0, r.key.path.find_first_of(".[")));
  for (const char* block : {"mesh", "model", "material", "thickness", "pressure", "edge_loads", "damping", "fixed",
                            "contact", "aortic_root", "bending", "coaptation", "chordae", "annulus_motion",
                            "leaflet_materials", "load", "solver", "monitor", "strain_markers", "output"})
    CHECK(blocks.count(block) == 1);

  // Defaults as the option structs hold them, in the internal units.
  const auto* max_step = find_row(rows, "solver.bdf2.max_step");
  REQUIRE(max_step);
  CHECK(parse_quantity(max_step->key.default_value, Dimension::time, "") == Bdf2Options().max_step);
  CHECK(find_row(rows, "output.every")->key.default_value == std::to_string(SceneConfig().time_series_every));
  CHECK(find_row(rows, "pressure.value")->key.default_value == "required");

  // A choice that brings its own keys or defaults gets rows of its own.
  const auto* penalty = find_row(rows, "contact.stiffness");
  const auto* barrier = find_row(rows, "contact.stiffness", "contact.model=barrier");
  const auto* seed = find_row(rows, "contact.stiffness", "contact.model=seed");
  REQUIRE(penalty);
  REQUIRE(barrier);
  REQUIRE(seed);
  CHECK(parse_quantity(penalty->key.default_value, Dimension::stiffness, "") == PenaltyContactOptions().stiffness);
  CHECK(parse_quantity(barrier->key.default_value, Dimension::stiffness, "") == kDefaultBarrierStiffness);
  CHECK(parse_quantity(seed->key.default_value, Dimension::stiffness, "") == ContactOptions().stiffness);
  CHECK(find_row(rows, "material.C10", "material.law=hgo"));
  CHECK_FALSE(find_row(rows, "material.C10"));
  CHECK(find_row(rows, "damping.rate", "damping.type=mass_proportional"));
  CHECK(find_row(rows, "leaflet_materials[].leaflets"));

  // Each path appears once per setting.
  std::set<std::string> seen;
  for (const auto& r : rows) CHECK(seen.insert(r.key.path + " | " + r.applies_when).second);
}

TEST_CASE("scene defaults taken from other keys are recorded in the internal unit, not rounded", "[scene][config]") {
  const json j = {{"mesh", "m.vtp"},
                  {"model", "membrane_fe"},
                  {"material", {{"c", "1 kPa"}, {"A1", 1.0}, {"A2", 1.0}, {"thickness", "0.123456789 mm"}}},
                  {"bending", {{"modulus", "1 MPa"}}}};
  const SceneConfig sc = parse_scene(j, "s.json", ".");
  CHECK(sc.thickness == 0.123456789);
  CHECK(sc.bending->thickness == 0.123456789);
  CHECK(sc.used["thickness"] == "0.123456789 mm");
  CHECK(sc.used["bending"]["thickness"] == "0.123456789 mm");
}

TEST_CASE("aortic_root.stiffening_pressure: the preset's 80 mmHg, a value of its own, or none", "[scene][config]") {
  auto root = [](const json& block) {
    const json j = {{"mesh", "m.vtp"}, {"model", "membrane_fe"}, {"material", "aortic_leaflet"},
                    {"pressure", {{"value", "80 mmHg"}}}, {"aortic_root", block}};
    return *parse_scene(j, "s.json", ".").aortic_root;
  };
  // configs/materials/aortic_root.json sets 80 mmHg (the seed's calibration point of the tube).
  REQUIRE(root(json::object()).stiffening_pressure);
  CHECK(*root(json::object()).stiffening_pressure == Approx(80 * units::mmHg).epsilon(1e-12));
  CHECK(*root({{"stiffening_pressure", "120 mmHg"}}).stiffening_pressure == Approx(120 * units::mmHg).epsilon(1e-12));
  CHECK_FALSE(root({{"stiffening_pressure", "none"}}).stiffening_pressure);
  CHECK_THROWS_WITH(root({{"stiffening_pressure", "never"}}), Catch::Contains("aortic_root.stiffening_pressure"));
  CHECK_THROWS_WITH(root({{"stiffening_pressure", 80}}), Catch::Contains("aortic_root.stiffening_pressure"));
  CHECK(*root({{"stiffness_index", 12.5}}).stiffness_index == 12.5);
  CHECK_FALSE(root(json::object()).stiffness_index);  // aortic_root.json gives none: continuous
  CHECK_FALSE(root({{"preset", "aortic_root_taut"}, {"stiffness_index", "continuous"}}).stiffness_index);
  CHECK(*root({{"preset", "aortic_root_taut"}}).stiffness_index == 20);
  CHECK_THROWS_WITH(root({{"stiffness_index", -3}}), Catch::Contains("aortic_root.stiffness_index"));
  CHECK_THROWS_WITH(root({{"stiffness_index", "stiff"}}), Catch::Contains("aortic_root.stiffness_index"));
}

TEST_CASE("solver.quasistatic.approach: newton by default, dynamic with its settle tolerance, anything else refused", "[scene][config]") {
  auto approach = [](const json& block) {
    const json j = {{"mesh", "m.vtp"}, {"model", "membrane_fe"}, {"material", "aortic_leaflet"},
                    {"pressure", {{"value", "80 mmHg"}}}, {"solver", {{"type", "quasistatic"}, {"quasistatic", block}}}};
    return parse_scene(j, "s.json", ".").quasistatic_approach;
  };
  CHECK_FALSE(approach(json::object()).dynamic);
  CHECK(approach(json::object()).settle_tolerance == 0.05);
  const auto dynamic = approach({{"approach", "dynamic"}, {"approach_settle_tolerance", "0.2 mm"}});
  CHECK(dynamic.dynamic);
  CHECK(dynamic.settle_tolerance == Approx(0.2).epsilon(1e-12));
  CHECK_THROWS_WITH(approach({{"approach", "bdf2"}}), Catch::Contains("solver.quasistatic.approach"));
  CHECK_THROWS_WITH(approach({{"approach_settle_tolerance", "0 mm"}}),
                    Catch::Contains("solver.quasistatic.approach_settle_tolerance"));
}

TEST_CASE("solver.quasistatic.forcing: fixed by default, adaptive on request, anything else refused", "[scene][config]") {
  auto forcing = [](const json& block) {
    const json j = {{"mesh", "m.vtp"}, {"model", "membrane_fe"}, {"material", "aortic_leaflet"},
                    {"pressure", {{"value", "80 mmHg"}}}, {"solver", {{"type", "quasistatic"}, {"quasistatic", block}}}};
    return parse_scene(j, "s.json", ".").quasistatic.forcing;
  };
  CHECK(forcing(json::object()) == NewtonForcing::fixed);
  CHECK(forcing({{"forcing", "adaptive"}}) == NewtonForcing::adaptive);
  CHECK_THROWS_WITH(forcing({{"forcing", "exact"}}), Catch::Contains("solver.quasistatic.forcing"));
}

TEST_CASE("the quasi-static solver with penalty contact runs with a warning that sheets may end crossed", "[scene][config]") {
  auto warnings = [](const std::string& solver, const std::string& contact) {
    const json j = {{"mesh", "m.vtp"},          {"model", "membrane_fe"},
                    {"material", "aortic_leaflet"}, {"pressure", {{"value", "80 mmHg"}}},
                    {"contact", {{"model", contact}}}, {"solver", {{"type", solver}}}};
    return parse_scene(j, "s.json", ".").warnings;
  };
  const auto penalty = warnings("quasistatic", "penalty");
  REQUIRE(penalty.size() == 1);
  CHECK_THAT(penalty[0], Catch::Contains("s.json") && Catch::Contains("contact.model penalty") &&
                             Catch::Contains("crossed") && Catch::Contains("contact.model barrier"));
  CHECK(warnings("quasistatic", "barrier").empty());
  CHECK(warnings("bdf2", "penalty").empty());
  CHECK(warnings("auto", "penalty").empty());
}

TEST_CASE("contact.max_detection caps the automatic detection distance and is refused beside a given distance", "[scene][config]") {
  auto contact = [](const json& block) {
    const json j = {{"mesh", "m.vtp"}, {"model", "membrane_fe"}, {"material", "aortic_leaflet"},
                    {"pressure", {{"value", "80 mmHg"}}}, {"contact", block}};
    return parse_scene(j, "s.json", ".");
  };
  const auto capped = contact({{"max_detection", "2.5 mm"}});
  REQUIRE(capped.penalty_contact);
  CHECK(capped.penalty_contact->detection == 0);
  CHECK(capped.penalty_contact->max_detection == Approx(2.5));
  CHECK(contact({{"model", "seed"}, {"max_detection", "2 mm"}}).contact->max_detection == Approx(2.0));
  CHECK_THROWS_WITH(contact({{"detection", "3 mm"}, {"max_detection", "2.5 mm"}}),
                    Catch::Contains("contact.max_detection") && Catch::Contains("detection is given"));
  CHECK_THROWS_WITH(contact({{"model", "barrier"}, {"offset", "0.5 mm"}, {"max_detection", "0.6 mm"}}),
                    Catch::Contains("contact.max_detection") && Catch::Contains("separation plus offset"));
  CHECK_THROWS_WITH(contact({{"model", "seed"}, {"max_detection", "0.05 mm"}}),
                    Catch::Contains("contact.max_detection") && Catch::Contains("zone"));
}
