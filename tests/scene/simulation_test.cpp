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

namespace {
// Sheet A: a square patch in z = 0, normals +z; sheet B: its mirror image in z = 2 with the
// winding flipped, normals −z. Boundaries fixed. Pressure along the normals presses them
// together.
TriMesh facing_sheets() {
  SquarePatchOptions o;
  o.side = 10;
  o.mesh.target_triangles = 120;
  const TriMesh a = generate_square_patch(o);
  TriMesh m;
  const int n = a.num_nodes();
  m.points.resize(2 * n, 3);
  m.points.topRows(n) = a.points;
  m.points.bottomRows(n) = a.points;
  m.points.bottomRows(n).col(2).setConstant(2.0);
  m.fiber.resize(2 * a.num_triangles(), 3);
  m.fiber.topRows(a.num_triangles()) = a.fiber;
  m.fiber.bottomRows(a.num_triangles()) = a.fiber;
  for (const Tri& t : a.triangles) m.triangles.push_back(t), m.leaflet.push_back(0);
  for (const Tri& t : a.triangles) m.triangles.emplace_back(t[0] + n, t[2] + n, t[1] + n), m.leaflet.push_back(1);
  m.roles.assign(2 * n, NodeRole::free);
  m.boundary.assign(2 * n, BoundaryType::interior);
  for (int i = 0; i < n; ++i)
    if (a.boundary[i] != BoundaryType::interior) m.roles[i] = m.roles[i + n] = NodeRole::fixed;
  return m;
}

int nearest_node(const TriMesh& m, const Vec3& p, int first, int count) {
  int best = first;
  for (int i = first; i < first + count; ++i)
    if ((m.points.row(i).transpose() - p).norm() < (m.points.row(best).transpose() - p).norm()) best = i;
  return best;
}
}  // namespace

TEST_CASE("two sheets pressed together stop at the contact separation, symmetrically", "[scene][contact]") {
  const TriMesh mesh = facing_sheets();
  const int n = mesh.num_nodes() / 2;
  const int ca = nearest_node(mesh, Vec3(0, 0, 0), 0, n), cb = nearest_node(mesh, Vec3(0, 0, 2), n, n);
  json j = {{"mesh", "unused.vtp"},
            {"model", "membrane_fe"},
            {"material", "aortic_leaflet"},
            {"pressure", {{"value", "80 mmHg"}, {"direction", "along_normal"}}},
            {"damping", {{"type", "critical"}}},
            {"solver", {{"type", "bdf2"}, {"bdf2", {{"max_wall_seconds", 100}}}}}};
  // Without contact each sheet bulges past the mid-plane z = 1 (so contact has work to do).
  {
    const SceneConfig sc = parse_scene(j, "free.json", ".");
    auto sys = build_system(sc, mesh);
    const auto res = simulate(sc, mesh, *sys);
    REQUIRE(res.summary.status == SolverStatus::ok);
    CHECK(node3(res.x, ca).z() > 1.3);
  }
  // With contact BDF2 does not settle to the seed's 1e-5 mm per step (known gap, README):
  // judge the state after 40 ms of simulated time, long after the sheets have met.
  j["contact"] = json::object();  // penalty: δ = 0.25 mm, k = 1 N/mm
  j["solver"]["bdf2"]["max_time"] = "40 ms";
  const SceneConfig sc = parse_scene(j, "contact.json", ".");
  auto sys = build_system(sc, mesh);
  const auto res = simulate(sc, mesh, *sys);
  INFO(res.summary.reason << ", " << res.summary.steps << " steps, residual " << res.summary.relative_residual
                          << ", last monitor step " << res.summary.last_monitor_displacement_mm << " mm");
  REQUIRE(res.summary.reason == "max_time reached");
  CHECK(res.summary.relative_residual < 0.05);
  const double za = node3(res.x, ca).z(), zb = node3(res.x, cb).z();
  // The pressure on a node (~0.0107 MPa × ~0.4 mm²) compresses the 0.25 mm separation by
  // √(0.005 N · δ / k) ≈ 0.035 mm; allow for the node not lying exactly over the other's face.
  CHECK(zb - za > 0.15);
  CHECK(zb - za < 0.25);
  // Mirror symmetry of mesh and load: the sheets meet near the mid-plane (not settled yet).
  CHECK(za + zb == Approx(2.0).margin(0.05));
  // Nothing crossed: every node of A stays below its mirror node of B.
  for (int i = 0; i < n; ++i) CHECK(node3(res.x, i).z() < node3(res.x, i + n).z());
}
