#include "valve/analysis/mesh_comparison.hpp"

#include <algorithm>

#include "valve/analysis/annulus_targets.hpp"
#include "valve/analysis/sections.hpp"
#include "valve/analysis/surface_distance.hpp"
#include "valve/core/error.hpp"
#include "valve/mesh/nearest_points.hpp"

namespace valve {

namespace {

MatX3 rows(const MatX3& p, const std::vector<int>& idx) {
  MatX3 out(static_cast<int>(idx.size()), 3);
  for (std::size_t k = 0; k < idx.size(); ++k) out.row(k) = p.row(idx[k]);
  return out;
}

std::vector<int> annulus_of(const TriMesh& mesh, const std::string& name, const char* purpose) {
  const std::vector<int> ring = annulus_ring(mesh);
  if (ring.size() < 3)
    throw_input_error(name, "NodeRole", std::string("an annulus (boundary loop with fixed or attached nodes) ") + purpose,
                      std::to_string(ring.size()) + " such nodes");
  return ring;
}

nlohmann::json cut_both(const TriMesh& simulated, const MatX3& moved, const TriMesh& reference,
                        const ComparisonOptions& options) {
  const MatX3 ring = rows(reference.points, annulus_of(reference, options.reference_name, "for sections"));
  // v points from the leaflets to the annulus: the ring's centre above the mesh's.
  const Vec3 up = ring.colwise().mean().transpose() - reference.points.colwise().mean().transpose();
  const SectionFrame frame = section_frame(ring, options.sections, up);
  nlohmann::json j = to_json(frame);
  j["segments"] = nlohmann::json::array();
  auto add = [&](const char* name, const TriMesh& mesh, const MatX3& points) {
    for (const SectionSegment& g : cut_sections(mesh, points, frame))
      j["segments"].push_back({{"plane", g.plane}, {"offset_mm", frame.offsets[g.plane]}, {"mesh", name},
                               {"u0", g.u0}, {"v0", g.v0}, {"u1", g.u1}, {"v1", g.v1}});
  };
  add("simulated", simulated, moved);
  add("reference", reference, reference.points);
  return j;
}

}  // namespace

MeshComparison compare_meshes(const TriMesh& simulated, const TriMesh& reference, const ComparisonOptions& options) {
  if (options.correspondence == Correspondence::nodes && simulated.num_nodes() != reference.num_nodes())
    throw_input_error(options.reference_name, "points",
                      std::to_string(simulated.num_nodes()) + " nodes (--correspondence nodes)",
                      std::to_string(reference.num_nodes()));
  MeshComparison c;
  c.moved = simulated.points;
  if (options.registration != Registration::none) {
    MatX3 source = simulated.points, target = reference.points;
    if (options.registration == Registration::annulus) {
      source = resample_ring(rows(simulated.points, annulus_of(simulated, options.simulated_name, "to register")), 360);
      target = resample_ring(rows(reference.points, annulus_of(reference, options.reference_name, "to register")), 1440);
    }
    c.icp = icp_point_to_point(source, target);
    c.moved = c.icp.transform.apply(simulated.points);
    c.registered = true;
  }

  if (options.correspondence == Correspondence::nodes) {
    c.error_mm = corresponding_node_distances(c.moved, reference.points);
    c.error = summarize_distances(c.error_mm);
  } else {
    const NearestPoints reference_nodes(reference.points);
    c.node_error_mm.resize(c.moved.rows());
    for (int i = 0; i < c.moved.rows(); ++i) reference_nodes.nearest(c.moved.row(i).transpose(), &c.node_error_mm[i]);
    c.error_mm = distances_to_surface(c.moved, reference);
    TriMesh moved_mesh = simulated;
    moved_mesh.points = c.moved;
    c.reference_error_mm = distances_to_surface(reference.points, moved_mesh);
    c.error = summarize_distances(c.error_mm);
    c.node_error = summarize_distances(c.node_error_mm);
    c.reference_error = summarize_distances(c.reference_error_mm);
    const double total = c.error.mean * c.error.count + c.reference_error.mean * c.reference_error.count;
    const int count = c.error.count + c.reference_error.count;
    c.symmetric_mean_mm = count > 0 ? total / count : 0;
    c.hausdorff_mm = std::max(c.error.max, c.reference_error.max);
  }
  if (options.sections > 0) c.sections = cut_both(simulated, c.moved, reference, options);
  return c;
}

nlohmann::json MeshComparison::metrics() const {
  nlohmann::json m = nlohmann::json::object();
  if (registered)
    m["registration"] = {{"rms_mm", icp.rms},
                         {"iterations", icp.iterations},
                         {"converged", icp.converged},
                         {"rotation_deg", icp.transform.rotation_angle_deg()},
                         {"translation_mm", icp.transform.translation.norm()}};
  if (node_error_mm.empty() && reference_error_mm.empty()) {
    m["node_distance"] = error.to_json();
  } else {
    m["surface_distance"] = error.to_json();
    m["nearest_node_distance"] = node_error.to_json();
    m["reference_to_simulated"] = reference_error.to_json();
    m["symmetric_surface_distance"] = {{"mean_mm", symmetric_mean_mm}, {"hausdorff_mm", hausdorff_mm}};
  }
  if (!sections.is_null()) m["sections"] = sections;
  return m;
}

}  // namespace valve
