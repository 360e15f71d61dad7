// Whole scenes on generated meshes: the biaxial protocol against the Fung law (an
// independent inversion of Eq. 3.1-3.3), and agreement of the static and dynamic solvers.
#include <catch2/catch.hpp>

#include "valve/analysis/leaflet_metrics.hpp"
#include "valve/config/scene_config.hpp"
#include "valve/mesh/generators.hpp"
#include "valve/scene/biaxial_protocol.hpp"
#include "valve/scene/simulation.hpp"

using namespace valve;

namespace {
SceneConfig biaxial_scene(const std::string& model, const std::string& sx, const std::string& sy, const std::string& rule) {
  const json j = {{"mesh", "unused.vtp"},
                  {"model", model},
                  {"material", "aortic_leaflet"},
                  {"edge_loads", {{"stress_x", sx}, {"stress_y", sy}}},
                  {"fixed", {{"node_roles", false}, {"planar", true}, {"pin_centre", true}}},
                  {"damping", {{"type", "critical"}}},
                  {"strain_markers", {{"convergence", rule}}},
                  {"load", {{"increments", {0.025, 0.05, 0.1, 0.2, 0.4, 0.7, 1.0}}}}};
  return parse_scene(j, "test.json", ".");
}

json run_biaxial(const SceneConfig& sc, const TriMesh& mesh) {
  auto sys = build_system(sc, mesh);
  BiaxialProtocol protocol(sc, mesh);
  SimulationHooks hooks;
  protocol.install(hooks);
  const auto res = simulate(sc, mesh, *sys, hooks);
  REQUIRE(res.summary.status == SolverStatus::ok);
  return protocol.report();
}
}  // namespace

TEST_CASE("FE biaxial patch reproduces the Fung law exactly when converged", "[scene][seed]") {
  // Linear triangles represent a homogeneous state exactly, so the only error left is the
  // solver's: with the residual criterion the marker strains equal the law's to 1e-6.
  for (double angle : {0.0, 45.0}) {
    SquarePatchOptions o;
    o.fiber_angle_deg = angle;
    o.mesh.seed = 3;
    const TriMesh mesh = generate_square_patch(o);
    const json rep = run_biaxial(biaxial_scene("membrane_fe", "20 kPa", "60 kPa", "solver"), mesh);
    for (const auto& c : rep["components"]) {
      INFO("angle " << angle << " " << c["component"]);
      CHECK(std::abs(c["simulated"].get<double>() - c["law"].get<double>()) < 1e-6);
    }
  }
}

TEST_CASE("FE biaxial with the seed's 2% rule meets the issue's error bounds", "[scene][seed]") {
  // Seed 3.3: FE 0.004 % (equibiaxial normal), 0.9 % (non-equibiaxial normal), 3.1 % (shear);
  // required here: <= 0.05 %, <= 1.5 %, <= 5 % (shear judged where it is not tiny: 20:60 at 45°).
  SquarePatchOptions o;
  o.fiber_angle_deg = 45;
  const TriMesh m45 = generate_square_patch(o);
  o.fiber_angle_deg = 0;
  const TriMesh m0 = generate_square_patch(o);
  for (const auto& c : run_biaxial(biaxial_scene("membrane_fe", "60 kPa", "60 kPa", "seed"), m0)["components"])
    if (c["component"] != "E12") CHECK(c["error_pct"].get<double>() <= 0.05);
  for (const auto& c : run_biaxial(biaxial_scene("membrane_fe", "20 kPa", "60 kPa", "seed"), m45)["components"])
    CHECK(c["error_pct"].get<double>() <= (c["component"] == "E12" ? 5.0 : 1.5));
}

TEST_CASE("static and dynamic solvers agree on the loaded aortic leaflet", "[scene][solver]") {
  const TriMesh mesh = generate_aortic_leaflet({});
  for (const std::string model : {"mass_spring", "membrane_fe"}) {
    json j = {{"mesh", "unused.vtp"},
              {"model", model},
              {"material", "aortic_leaflet"},
              {"pressure", {{"value", "80 mmHg"}}},
              {"damping", {{"type", "critical"}}},
              {"monitor", "free_edge_middle"},
              {"solver", {{"type", "bdf2"}}}};
    const SceneConfig dyn = parse_scene(j, "dyn.json", ".");
    j["solver"] = {{"type", "static"}};
    const SceneConfig stat = parse_scene(j, "static.json", ".");
    auto s1 = build_system(dyn, mesh);
    auto s2 = build_system(stat, mesh);
    const auto a = simulate(dyn, mesh, *s1);
    const auto b = simulate(stat, mesh, *s2);
    INFO(model);
    REQUIRE(a.summary.status == SolverStatus::ok);
    REQUIRE(b.summary.status == SolverStatus::ok);
    double max_diff = 0;
    for (int i = 0; i < mesh.num_nodes(); ++i) max_diff = std::max(max_diff, (node3(a.x, i) - node3(b.x, i)).norm());
    CHECK(max_diff < 0.01);  // mm; the dynamic run stops at a residual of 1e-3 of the load
    CHECK(b.summary.relative_residual < 1e-9);
    CHECK(b.summary.linear.factorizations < 300);
  }
}

TEST_CASE("leaflet_materials: one material group per triangle, clear errors otherwise", "[scene]") {
  AorticValveOptions o;
  o.mesh.target_triangles = 60;
  const TriMesh mesh = generate_aortic_valve(o);
  auto scene = [](const json& groups) {
    return parse_scene({{"mesh", "unused.vtp"}, {"model", "mass_spring"}, {"material", "aortic_leaflet"}, {"leaflet_materials", groups}},
                       "s.json", ".");
  };
  const SceneConfig sc = scene(json::array({{{"leaflets", {2}}, {"material", "pericardium_surrogate"}}}));
  const std::vector<int> group = material_groups(sc, mesh);
  for (int t = 0; t < mesh.num_triangles(); ++t) CHECK(group[t] == (mesh.leaflet[t] == 2 ? 1 : 0));
  // Two membrane terms: the scene's material and the graft group.
  const auto sys = build_system(sc, mesh);
  int membrane_terms = 0;
  for (const auto& t : sys->terms()) membrane_terms += t->name() == "mass_spring";
  CHECK(membrane_terms == 2);
  const SceneConfig twice = scene(json::array({{{"leaflets", {1}}, {"material", "pericardium_surrogate"}},
                                               {{"leaflets", {1}}, {"material", "mitral_leaflet"}}}));
  CHECK_THROWS_WITH(material_groups(twice, mesh), Catch::Contains("leaflet_materials[1].leaflets") && Catch::Contains("listed twice"));
  const SceneConfig absent = scene(json::array({{{"leaflets", {7}}, {"material", "pericardium_surrogate"}}}));
  CHECK_THROWS_WITH(build_system(absent, mesh), Catch::Contains("leaflet_materials[0].leaflets"));
}
