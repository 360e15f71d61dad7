// valve-bench's closure is the scene's whole model, as valve-simulate runs it: here the annulus
// motion of a flat annular membrane (its closed ring 10 % smaller) must move the annulus.
#include <catch2/catch.hpp>

#include "support/annulus_scene.hpp"
#include "valve/scene/benchmark.hpp"

using namespace valve;

TEST_CASE("the benchmarked closure runs the scene's annulus motion and reports leaflet positions", "[scene]") {
  const test::AnnulusScene scene;
  const TriMesh& open = scene.open;
  const ClosureCost cost = measure_closure(scene.config, scene.model, ModelKind::mass_spring, 1);
  INFO(cost.solver.dump());
  REQUIRE(cost.solver["status"] == "ok");
  REQUIRE(cost.x.size() == 3 * open.num_nodes());
  // Without the model the annulus, fixed and unloaded, would not move at all.
  const MatX3 x = unflatten(cost.x);
  for (int i = 0; i < 48; ++i) CHECK((x.row(i) - 0.9 * open.points.row(i)).norm() < 0.05);
  CHECK(cost.one_factorization_seconds > 0);
  CHECK(cost.one_factorization_shift >= 0);  // some diagonal shift factorized, and was timed
  CHECK(cost.ratio_to_factorization > 0);
}
