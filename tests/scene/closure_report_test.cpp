// What valve-simulate reports of a closure, against closed forms: a homogeneous stretch of a
// flat patch, and the counts of a real closure.
#include <catch2/catch.hpp>

#include "valve/scene/scene_config.hpp"
#include "valve/core/error.hpp"
#include "valve/mesh/generators.hpp"
#include "valve/scene/closure_report.hpp"
#include "valve/scene/scene_model.hpp"
#include "valve/scene/simulation.hpp"

using namespace valve;
using json = nlohmann::json;

namespace {
const NamedArray& array_named(const ClosedValveAnalysis& a, const std::string& name) {
  for (const auto& n : a.arrays)
    if (n.name == name) return n;
  FAIL("no array " << name);
  throw;
}
}  // namespace

TEST_CASE("A patch stretched by 1.2 along its fibers reports the strains of that stretch", "[closure_report]") {
  // x = diag(1.2, 1, 1) X with the fibers along x: F = diag(1.2, 1), so E11 = (1.2² − 1)/2 = 0.22,
  // E22 = E12 = 0, the fiber stretch 1.2, the cross stretch 1, the area ratio 1.2, and the
  // displacement 0.2 X₁ along x.
  SquarePatchOptions o;
  TriMesh patch = generate_square_patch(o);
  for (int t = 0; t < patch.num_triangles(); ++t) patch.fiber.row(t) << 1, 0, 0;
  VecX x = flatten(patch.points);
  for (int i = 0; i < patch.num_nodes(); ++i) x[3 * i] *= 1.2;
  const SceneConfig scene = parse_scene(json{{"mesh", "unused.vtp"}, {"model", "membrane_fe"}, {"material", "aortic_leaflet"},
                                             {"pressure", {{"value", "1 kPa"}}}},
                                        "patch.json", ".");
  const ClosedValveAnalysis a = analyze_closed_valve(scene, patch, x);
  const auto& green = array_named(a, "GreenStrain").values;
  for (int t = 0; t < patch.num_triangles(); ++t) {
    CHECK(green(t, 0) == Approx(0.22).margin(1e-12));
    CHECK(green(t, 1) == Approx(0).margin(1e-12));
    CHECK(green(t, 2) == Approx(0).margin(1e-12));
  }
  CHECK(array_named(a, "StretchFiber").values.minCoeff() == Approx(1.2));
  CHECK(array_named(a, "StretchFiber").values.maxCoeff() == Approx(1.2));
  CHECK(array_named(a, "StretchCross").values.maxCoeff() == Approx(1.0));
  CHECK(array_named(a, "AreaRatio").values.minCoeff() == Approx(1.2));
  const auto& d = array_named(a, "Displacement").values;
  for (int i = 0; i < patch.num_nodes(); ++i) CHECK(d(i, 0) == Approx(0.2 * patch.points(i, 0)).margin(1e-12));
  CHECK(a.max_displacement_mm == Approx(0.2 * patch.points.col(0).cwiseAbs().maxCoeff()));
  CHECK(array_named(a, "PK2Stress").per_cell);
  CHECK_FALSE(a.coaptation);  // one leaflet: nothing to coapt with
  // A non-finite state is refused, not analysed.
  x[0] = std::nan("");
  CHECK_THROWS_AS(analyze_closed_valve(scene, patch, x), NumericalError);
}

TEST_CASE("A three-leaflet closure (static, no contact) reports its run, each leaflet's free edge and its coaptation", "[closure_report]") {
  LeafletOptions o;
  const TriMesh mesh = generate_three_leaflet_valve(o);
  const SceneConfig scene = parse_scene(json{{"mesh", "unused.vtp"},
                                             {"model", "membrane_fe"},
                                             {"material", "aortic_leaflet"},
                                             {"pressure", {{"value", "80 mmHg"}, {"direction", "along_normal"}}},
                                             {"solver", {{"type", "static"}}}},
                                        "three.json", ".");
  const SceneModel model = prepare_scene_model(scene, mesh);
  auto system = build_system(scene, model);
  const SimulationResult res = simulate(scene, model.mesh, *system);
  INFO(res.summary.reason << ", " << res.summary.steps << " steps, " << res.summary.wall_seconds << " s");
  REQUIRE(res.summary.status == SolverStatus::ok);
  const ClosureRunReport run = closure_run_metrics(scene, mesh, model, *system, res, res.x);
  CHECK(run.metrics["nodes"] == mesh.num_nodes());
  CHECK(run.metrics["triangles"] == mesh.num_triangles());
  CHECK(run.metrics["solver"]["status"] == "ok");
  CHECK(run.metrics["increments"].size() == res.increments.size());
  CHECK_FALSE(run.metrics.contains("contact"));  // no contact term in this scene
  CHECK_FALSE(run.chordae);
  const ClosedValveAnalysis a = analyze_closed_valve(scene, mesh, res.x);
  REQUIRE(a.coaptation);
  REQUIRE(a.leaflets.size() == 3);
  // The seed's leaflets: a free edge of 20 mm at rest (the semicircle's diameter), stretched
  // by the pressure.
  double mesh_area = 0, leaflet_areas = 0;
  for (const auto& t : mesh.triangles) mesh_area += triangle_area(mesh.points, t);
  for (const auto& l : a.leaflets) {
    CHECK(l["free_edge_rest_mm"].get<double>() == Approx(20).epsilon(0.02));
    CHECK(l["free_edge_mm"].get<double>() > l["free_edge_rest_mm"].get<double>());
    // Three copies of one leaflet: a third of the mesh's rest area each, up to the mesher's
    // random triangulation of the same outline.
    CHECK(l["rest_area_mm2"].get<double>() == Approx(mesh_area / 3).epsilon(0.01));
    leaflet_areas += l["rest_area_mm2"].get<double>();
  }
  CHECK(leaflet_areas == Approx(mesh_area).epsilon(1e-12));
}
