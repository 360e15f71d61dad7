#include "valve/remesh/remesh_report.hpp"

#include <cstdio>

#include "valve/analysis/distance_stats.hpp"
#include "valve/analysis/surface_distance.hpp"
#include "valve/mesh/subdivide.hpp"

namespace valve {

nlohmann::json mesh_shape_json(const MeshShapeReport& r) {
  return {{"nodes", r.nodes},
          {"triangles", r.triangles},
          {"quality_mean", r.quality.mean},
          {"quality_min", r.quality.min},
          {"quality_min_away_from_boundary", r.quality_min_away_from_boundary},
          {"quality_below_0_6", r.quality.below_0_6},
          {"mean_interior_valence", r.mean_interior_valence},
          {"boundary_loops", r.boundary_loops},
          {"manifold", r.manifold()}};
}

std::vector<RemeshLevel> remesh_levels(const TriMesh& mesh, int subdivisions, const std::string& name,
                                       const TriMesh* reference) {
  std::vector<RemeshLevel> levels;
  for (int s = 0; s <= subdivisions; ++s) {
    RemeshLevel level;
    level.mesh = s == 0 ? mesh : subdivide_midpoint(levels.back().mesh);
    level.file = name + (s == 0 ? "" : s == 1 ? "_x4" : "_x16") + ".vtp";
    const auto q = triangle_qualities(level.mesh.points, level.mesh.triangles);
    level.arrays.push_back({"Quality", Eigen::Map<const Eigen::VectorXd>(q.data(), Eigen::Index(q.size())), true});
    level.entry = mesh_shape_json(describe_mesh_shape(level.mesh));
    level.entry["file"] = level.file;
    if (reference) {
      const auto d = distances_to_surface(level.mesh.points, *reference);
      std::vector<double> on_boundary, inside;
      for (std::size_t i = 0; i < d.size(); ++i)
        (level.mesh.boundary[i] == BoundaryType::interior ? inside : on_boundary).push_back(d[i]);
      nlohmann::json& distance = level.entry["distance_to_reference"] = summarize_distances(d).to_json();
      distance["interior_nodes"] = summarize_distances(inside).to_json();
      distance["boundary_nodes"] = summarize_distances(on_boundary).to_json();
      level.arrays.push_back({"Error_mm", Eigen::Map<const Eigen::VectorXd>(d.data(), Eigen::Index(d.size())), false});
    }
    levels.push_back(std::move(level));
  }
  return levels;
}

nlohmann::json remesh_metrics(const MembraneSummary& ms, const RemeshSummary& rs, const TriMesh& mesh, int boundary_loops) {
  int annulus_nodes = 0, free_edge_nodes = 0;
  for (BoundaryType b : mesh.boundary) annulus_nodes += b == BoundaryType::attached, free_edge_nodes += b == BoundaryType::free_edge;
  return {{"atrial_direction", {ms.atrial_direction.x(), ms.atrial_direction.y(), ms.atrial_direction.z()}},
          {"atrial_direction_estimated", ms.direction_estimated},
          {"extraction", {{"faces_in", ms.faces_in}, {"faces_kept", ms.faces_kept}, {"pieces_kept", ms.pieces_kept},
                          {"pieces_dropped", ms.pieces_dropped}, {"area_mm2", ms.area_mm2}}},
          {"remesh", {{"target_edge_length_mm", rs.target_edge_length}, {"attempts", rs.attempts},
                      {"holes_filled", rs.holes_filled}, {"border_repairs", rs.border_repairs},
                      {"border_vertices_snapped", rs.border_snapped}, {"flap_triangles_cut", rs.flaps_cut}}},
          {"boundary_loops", boundary_loops},
          {"annulus_nodes", annulus_nodes},
          {"free_edge_nodes", free_edge_nodes}};
}

std::string remesh_not_converged_reason(const RemeshOptions& options, const RemeshSummary& remesh, int triangles_found) {
  return "no edge length gave a count within " + std::to_string(int(100 * options.tolerance)) + " % of " +
         std::to_string(options.target_triangles) + " triangles in " + std::to_string(remesh.attempts) +
         " attempts; the closest (" + std::to_string(triangles_found) + ") is written";
}

std::string remesh_report_line(const RemeshLevel& first, int boundary_loops) {
  const nlohmann::json& e = first.entry;
  char text[256];
  std::snprintf(text, sizeof text, "%d triangles, quality mean %.3f min %.3f, valence %.2f, %d boundary loop(s)",
                e["triangles"].get<int>(), e["quality_mean"].get<double>(), e["quality_min"].get<double>(),
                e["mean_interior_valence"].get<double>(), boundary_loops);
  std::string line = text;
  // Five characters of std::to_string's six decimals: "0.123" for distances under 10 mm.
  if (e.contains("distance_to_reference"))
    line += ", mean distance to reference " + std::to_string(e["distance_to_reference"]["mean_mm"].get<double>()).substr(0, 5) + " mm";
  return line;
}

}  // namespace valve
