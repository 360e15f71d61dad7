// Annulus motion (seed 5.2.2): a flat annular membrane whose closed-state annulus is the
// open one contracted by 10 % about the centre. After the zero-pressure solve every annulus
// node sits on its target (0.9 × its open position, to the ring's chord error) and the
// membrane, now slack, has followed inward without folding.
#include <catch2/catch.hpp>

#include "valve/scene/scene_config.hpp"
#include "valve/mesh/quality.hpp"
#include "valve/scene/scene_model.hpp"
#include "valve/scene/simulation.hpp"
#include "support/annulus_scene.hpp"

using namespace valve;

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
