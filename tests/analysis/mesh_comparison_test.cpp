// valve-compare's distances on flat grids whose distances are known in closed form.
#include <catch2/catch.hpp>

#include "valve/analysis/mesh_comparison.hpp"
#include "valve/core/error.hpp"

using namespace valve;

namespace {
// Unit-spaced grid in z = height: columns x = 0..nx, rows y = 0..ny, two triangles a cell.
TriMesh grid(int nx, int ny, double height = 0) {
  TriMesh m;
  m.points.resize((nx + 1) * (ny + 1), 3);
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) m.points.row(j * (nx + 1) + i) << i, j, height;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const int a = j * (nx + 1) + i, b = a + 1, c = a + nx + 1, d = c + 1;
      m.triangles.emplace_back(a, b, d);
      m.triangles.emplace_back(a, d, c);
    }
  m.fill_defaults();
  return m;
}
}  // namespace

TEST_CASE("A simulated sheet too short to cover the reference shows in the other direction and the Hausdorff distance",
          "[mesh_comparison]") {
  const TriMesh reference = grid(10, 10), simulated = grid(10, 5);  // the simulated half of the sheet
  ComparisonOptions o;
  o.registration = Registration::none;
  const MeshComparison c = compare_meshes(simulated, reference, o);
  // Every simulated node lies on the reference: one direction alone sees a perfect match.
  CHECK(c.error.max == Approx(0).margin(1e-12));
  CHECK(c.node_error.max == Approx(0).margin(1e-12));
  // Reference node (x, y) is max(0, y − 5) from the half sheet: 11 nodes each at 1..5 mm.
  CHECK(c.reference_error.max == Approx(5));
  CHECK(c.reference_error.mean == Approx(11.0 * 15 / 121));
  CHECK(c.hausdorff_mm == Approx(5));
  // ASSD = (0 · 66 + 165) / (66 + 121).
  CHECK(c.symmetric_mean_mm == Approx(165.0 / 187));
  const auto m = c.metrics();
  CHECK(m["symmetric_surface_distance"]["hausdorff_mm"].get<double>() == Approx(5));
  CHECK(m["reference_to_simulated"]["count"].get<int>() == 121);
  CHECK_FALSE(m.contains("registration"));
}

TEST_CASE("A sheet lifted by 2 mm is 2 mm away both ways and node by node", "[mesh_comparison]") {
  const TriMesh reference = grid(6, 4), simulated = grid(6, 4, 2.0);
  ComparisonOptions o;
  o.registration = Registration::none;
  const MeshComparison nearest = compare_meshes(simulated, reference, o);
  CHECK(nearest.error.mean == Approx(2));
  CHECK(nearest.reference_error.mean == Approx(2));
  CHECK(nearest.symmetric_mean_mm == Approx(2));
  CHECK(nearest.hausdorff_mm == Approx(2));
  o.correspondence = Correspondence::nodes;
  const MeshComparison nodes = compare_meshes(simulated, reference, o);
  CHECK(nodes.error.max == Approx(2));
  CHECK(nodes.metrics().contains("node_distance"));
  CHECK_FALSE(nodes.metrics().contains("symmetric_surface_distance"));
  // Registration on all nodes takes the lift out.
  o.registration = Registration::all;
  const MeshComparison registered = compare_meshes(simulated, reference, o);
  CHECK(registered.registered);
  CHECK(registered.error.max == Approx(0).margin(1e-6));
  CHECK(registered.icp.transform.translation.norm() == Approx(2).margin(1e-6));
}

TEST_CASE("compare_meshes refuses node correspondence across node counts and an annulus registration without a ring",
          "[mesh_comparison]") {
  const TriMesh reference = grid(4, 4), simulated = grid(4, 2);
  ComparisonOptions o;
  o.correspondence = Correspondence::nodes;
  o.registration = Registration::none;
  o.reference_name = "ref.vtp";
  CHECK_THROWS_WITH(compare_meshes(simulated, reference, o), Catch::Contains("ref.vtp: points"));
  o.correspondence = Correspondence::nearest;
  o.registration = Registration::annulus;
  o.simulated_name = "sim.vtp";
  CHECK_THROWS_AS(compare_meshes(simulated, reference, o), InputError);
  CHECK_THROWS_WITH(compare_meshes(simulated, reference, o), Catch::Contains("sim.vtp: NodeRole"));
}
