// Annulus motion (seed 5.2.2): a flat annular membrane whose closed-state annulus is the
// open one contracted by 10 % about the centre. After the zero-pressure solve every annulus
// node sits on its target (0.9 × its open position, to the ring's chord error) and the
// membrane, now slack, has followed inward without folding.
#include <catch2/catch.hpp>

#include "valve/scene/scene_config.hpp"
#include "valve/mesh/quality.hpp"
#include "valve/scene/scene_model.hpp"
#include "valve/scene/simulation.hpp"

using namespace valve;

namespace {
// Two rings of n nodes (radii 12 and 6 mm) in z = 0 joined by triangles; outer ring fixed.
TriMesh annulus_membrane(int n, double scale) {
  TriMesh m;
  m.points.resize(3 * n, 3);
  for (int r = 0; r < 3; ++r)
    for (int i = 0; i < n; ++i) {
      const double t = 2 * M_PI * (i + 0.5 * r) / n, radius = scale * (12.0 - 3.0 * r);
      m.points.row(r * n + i) << radius * std::cos(t), radius * std::sin(t), 0;
    }
  for (int r = 0; r < 2; ++r)
    for (int i = 0; i < n; ++i) {
      const int j = (i + 1) % n, a = r * n + i, b = r * n + j, c = (r + 1) * n + i, d = (r + 1) * n + j;
      m.triangles.emplace_back(a, b, c);
      m.triangles.emplace_back(b, d, c);
    }
  m.fill_defaults();
  for (int i = 0; i < n; ++i) m.roles[i] = NodeRole::fixed;
  return m;
}
}  // namespace

TEST_CASE("annulus motion moves the annulus to the closed ring before any pressure", "[scene]") {
  const TriMesh open = annulus_membrane(48, 1.0), closed = annulus_membrane(48, 0.9);
  const json j = {{"mesh", "open.vtp"},
                  {"model", "mass_spring"},
                  {"material", "mitral_leaflet_table51"},
                  {"annulus_motion", {{"closed_mesh", "closed.vtp"}, {"register", false}}},
                  {"solver", {{"type", "static"}}}};
  const SceneConfig sc = parse_scene(j, "scene.json", ".");
  const SceneModel model = prepare_scene_model(sc, open, &closed);
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
