// valve-remesh's report: the subdivision levels with their quality and distance to a
// reference, the summary's figures, and its messages.
#include <catch2/catch.hpp>

#include "valve/remesh/remesh_report.hpp"

using namespace valve;

namespace {
// A 2 x 2 mm square of two triangles in z = 0; the edge y = 0 is the annulus.
TriMesh square() {
  TriMesh m;
  m.points.resize(4, 3);
  m.points << 0, 0, 0, 2, 0, 0, 2, 2, 0, 0, 2, 0;
  m.triangles = {Tri(0, 1, 2), Tri(0, 2, 3)};
  m.fill_defaults();
  m.boundary[0] = m.boundary[1] = BoundaryType::attached;
  return m;
}
}  // namespace

TEST_CASE("remesh levels: each subdivision splits every triangle in four, measured against a reference", "[remesh]") {
  TriMesh reference = square();
  reference.points.col(2).setConstant(0.5);  // the same square 0.5 mm above
  const auto levels = remesh_levels(square(), 2, "leaflets", &reference);
  REQUIRE(levels.size() == 3);
  const std::vector<std::string> files{"leaflets.vtp", "leaflets_x4.vtp", "leaflets_x16.vtp"};
  const std::vector<int> triangles{2, 8, 32};
  const std::vector<int> nodes{4, 9, 25};  // (2^k + 1)^2 on the square's grid
  for (int k = 0; k < 3; ++k) {
    const RemeshLevel& level = levels[k];
    CHECK(level.file == files[k]);
    CHECK(level.entry["file"] == files[k]);
    CHECK(level.entry["triangles"] == triangles[k]);
    CHECK(level.entry["nodes"] == nodes[k]);
    REQUIRE(level.arrays.size() == 2);
    CHECK(level.arrays[0].name == "Quality");
    CHECK(level.arrays[0].per_cell);
    CHECK(level.arrays[0].values.rows() == triangles[k]);
    CHECK(level.arrays[1].name == "Error_mm");
    CHECK(level.arrays[1].values.rows() == nodes[k]);
    CHECK(level.arrays[1].values.minCoeff() == Approx(0.5));
    const auto& distance = level.entry["distance_to_reference"];
    CHECK(distance["mean_mm"].get<double>() == Approx(0.5));
    CHECK(distance["count"] == nodes[k]);
    // 2^k + 1 nodes along the annulus edge y = 0.
    CHECK(distance["boundary_nodes"]["count"] == (1 << k) + 1);
    CHECK(distance["interior_nodes"]["count"] == nodes[k] - (1 << k) - 1);
  }
  // Right isosceles triangles: quality below 1, the same at every level.
  CHECK(levels[0].entry["quality_mean"].get<double>() == Approx(levels[2].entry["quality_mean"].get<double>()));

  const auto plain = remesh_levels(square(), 0, "m");
  REQUIRE(plain.size() == 1);
  CHECK(plain[0].arrays.size() == 1);
  CHECK_FALSE(plain[0].entry.contains("distance_to_reference"));
}

TEST_CASE("remesh report: the summary's figures and messages", "[remesh]") {
  MeshShapeReport shape;
  shape.nodes = 10, shape.triangles = 12, shape.boundary_loops = 2, shape.non_manifold_edges = 1;
  const nlohmann::json j = mesh_shape_json(shape);
  CHECK(j["nodes"] == 10);
  CHECK(j["boundary_loops"] == 2);
  CHECK(j["manifold"] == false);

  MembraneSummary ms;
  ms.atrial_direction = Vec3(0, 1, 0);
  ms.faces_in = 100, ms.faces_kept = 40;
  RemeshSummary rs;
  rs.attempts = 3;
  const nlohmann::json m = remesh_metrics(ms, rs, square(), 1);
  CHECK(m["atrial_direction"] == nlohmann::json{0.0, 1.0, 0.0});
  CHECK(m["extraction"]["faces_kept"] == 40);
  CHECK(m["remesh"]["attempts"] == 3);
  CHECK(m["annulus_nodes"] == 2);
  CHECK(m["free_edge_nodes"] == 0);

  RemeshOptions ro;
  ro.target_triangles = 650;
  ro.tolerance = 0.05;
  rs.attempts = 8;
  CHECK(remesh_not_converged_reason(ro, rs, 700) ==
        "no edge length gave a count within 5 % of 650 triangles in 8 attempts; the closest (700) is written");

  RemeshLevel first;
  first.entry = {{"triangles", 650}, {"quality_mean", 0.91234}, {"quality_min", 0.3}, {"mean_interior_valence", 5.996}};
  CHECK(remesh_report_line(first, 2) == "650 triangles, quality mean 0.912 min 0.300, valence 6.00, 2 boundary loop(s)");
  first.entry["distance_to_reference"]["mean_mm"] = 0.123456;
  CHECK(remesh_report_line(first, 2) ==
        "650 triangles, quality mean 0.912 min 0.300, valence 6.00, 2 boundary loop(s), mean distance to reference 0.123 mm");
}
