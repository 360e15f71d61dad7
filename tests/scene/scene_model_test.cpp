// The scene model. Annulus motion (seed 5.2.2): a flat annular membrane whose closed-state
// annulus is the open one contracted by 10 % about the centre. After the zero-pressure solve
// every annulus node sits on its target (0.9 × its open position, to the ring's chord error)
// and the membrane, now slack, has followed inward without folding. Condensed chordae runs:
// the same equilibrium as every chord point a node.
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>

#include "valve/scene/scene_config.hpp"
#include "valve/mesh/closest_point.hpp"
#include "valve/mesh/generators.hpp"
#include "valve/mesh/quality.hpp"
#include "valve/scene/scene_model.hpp"
#include "valve/scene/simulation.hpp"
#include "support/annulus_scene.hpp"

using namespace valve;
namespace fs = std::filesystem;

TEST_CASE("annulus motion moves the annulus to the closed ring before any pressure", "[scene]") {
  const test::AnnulusScene scene;
  const TriMesh& open = scene.open;
  const SceneConfig& sc = scene.config;
  const SceneModel& model = scene.model;
  REQUIRE(model.annulus);
  CHECK(model.annulus->nodes.size() == 48);
  CHECK(model.annulus->mean_motion_mm == Approx(1.2).margin(0.02));  // 10 % of 12 mm
  auto sys = build_system(sc, model);
  const SimulationResult res = simulate(sc, model.mesh, *sys);
  INFO(res.summary.one_line());
  REQUIRE(res.summary.status == SolverStatus::ok);
  REQUIRE(res.increments.size() == 1);  // no pressure declared: the zero-pressure step is all
  CHECK(res.increments[0].load == 0);
  const MatX3 x = unflatten(res.x);
  for (int i = 0; i < 48; ++i) CHECK((x.row(i) - 0.9 * open.points.row(i)).norm() < 0.05);
  // The inner rings were carried inward by the spread displacement and stay unfolded.
  for (int i = 48; i < 3 * 48; ++i) CHECK(x.row(i).norm() < open.points.row(i).norm());
  CHECK(summarize_quality(triangle_qualities(x, open.triangles)).min > 0.3);
}

TEST_CASE("chordae.chains condensed: the leaflets close where they close with every chord point a node", "[scene][chordae][quasistatic]") {
  // A clamped disk (20 mm, normals +z) pushed up by 2 kPa and held by a papillary tip 20 mm
  // below: a trunk to a hub, and from the hub three runs of three segments each through kinked
  // unbranched points to nodes 3 mm from the centre. Both models solve to a relative residual of
  // 1e-9; the runs' points carry no load, so the equilibria coincide.
  DiskOptions o;
  o.mesh.target_triangles = 400;
  const TriMesh disk = generate_clamped_disk(o);
  nlohmann::json points = nlohmann::json::array(), segments = nlohmann::json::array();
  points.push_back({{"kind", "papillary_tip"}, {"position", {0.0, 0.0, -20.0}}});
  points.push_back({{"kind", "branch"}, {"position", {0.0, 0.0, -12.0}}});
  segments.push_back({{"from", 0}, {"to", 1}, {"type", "primary"}});
  for (int k = 0; k < 3; ++k) {
    const double angle = 2 * M_PI * k / 3;
    const int node = nearest_point_index(disk.points, Vec3(3 * std::cos(angle), 3 * std::sin(angle), 0));
    const Vec3 end = disk.points.row(node).transpose(), kink(0.4 * std::sin(angle), 0.4 * std::cos(angle), 0);
    const int first = static_cast<int>(points.size());
    for (double f : {0.3, 0.65}) {
      const Vec3 p = Vec3(0, 0, -12) + f * (end - Vec3(0, 0, -12)) + kink;
      points.push_back({{"kind", "branch"}, {"position", {p.x(), p.y(), p.z()}}});
    }
    points.push_back({{"kind", "insertion"}, {"position", {end.x(), end.y(), end.z()}}, {"mesh_node", node}});
    segments.push_back({{"from", 1}, {"to", first}, {"type", "primary"}});
    segments.push_back({{"from", first}, {"to", first + 1}, {"type", "primary"}});
    segments.push_back({{"from", first + 1}, {"to", first + 2}, {"type", "primary"}});
  }
  const fs::path file = fs::temp_directory_path() / "valve_condensed_chains.chordae.json";
  std::ofstream(file) << nlohmann::json{{"diameter_mm", 0.5}, {"points", points}, {"segments", segments}}.dump();

  auto close = [&](const std::string& chains, SceneModel& model) {
    const SceneConfig sc = parse_scene({{"mesh", "disk.vtp"},
                                        {"model", "membrane_fe"},
                                        {"material", "aortic_leaflet"},
                                        {"pressure", {{"value", "2 kPa"}, {"direction", "along_normal"}}},
                                        {"chordae", {{"file", file.string()}, {"chains", chains}}},
                                        {"solver", {{"type", "quasistatic"}, {"quasistatic", {{"relative_residual_tolerance", 1e-9}}}}}},
                                       "scene.json", ".");
    model = prepare_scene_model(sc, disk);
    auto sys = build_system(sc, model);
    SimulationResult res = simulate(sc, model.mesh, *sys);
    INFO(chains << ": " << res.summary.reason);
    REQUIRE(res.summary.status == SolverStatus::ok);
    return res.x;
  };
  SceneModel full_model, condensed_model;
  const VecX full = close("nodes", full_model), condensed = close("condensed", condensed_model);
  REQUIRE(condensed_model.attachment.rods.size() == 4);  // the trunk and one rod per run
  double lift = 0, apart = 0;
  for (int i = 0; i < disk.num_nodes(); ++i) {
    lift = std::max(lift, full[3 * i + 2]);
    apart = std::max(apart, (node3(full, i) - node3(condensed, i)).norm());
  }
  // The chordae hold the centre: it rises less than the rim-free bulge around it.
  const int centre = nearest_point_index(disk.points, Vec3::Zero());
  CHECK(full[3 * centre + 2] < lift);
  CHECK(apart < 1e-6 * lift);
  // Every run ends straight: the full model's points lie where the condensed rods draw them.
  const MatX3 drawn = condensed_model.attachment.point_positions(condensed);
  const MatX3 free_points = full_model.attachment.point_positions(full);
  CHECK((drawn - free_points).cwiseAbs().maxCoeff() < 1e-4);
  // By default condensed for the quasi-static solver only.
  for (const auto& [solver, rods] : {std::pair<std::string, size_t>{"quasistatic", 4}, {"bdf2", 10}, {"static", 10}}) {
    const SceneConfig sc = parse_scene({{"mesh", "disk.vtp"},
                                        {"model", "membrane_fe"},
                                        {"material", "aortic_leaflet"},
                                        {"pressure", {{"value", "2 kPa"}}},
                                        {"chordae", {{"file", file.string()}}},
                                        {"solver", {{"type", solver}}}},
                                       "scene.json", ".");
    CHECK(prepare_scene_model(sc, disk).attachment.rods.size() == rods);
  }
}
