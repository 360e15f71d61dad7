#pragma once
// How far a simulated valve is from a reference (a closed-valve scan's membrane, or a mesh
// with the same numbering): valve-compare's workflow, registration then distances.
//
// Correspondence nodes: |x_i − y_i| for meshes with one numbering.
// Correspondence nearest: each simulated node's distance to the nearest point of the
// reference surface (the headline) and to the nearest reference node (the seed's metric,
// 5.2.2), and, the other way, each reference node's distance to the simulated surface, so a
// simulated leaflet that is too short cannot hide: it is near the reference everywhere it
// exists, but the reference's uncovered part is far from it. From both directions:
//   average symmetric surface distance  ASSD = (Σ_i d(x_i, Y) + Σ_j d(y_j, X)) / (n_X + n_Y),
//   Hausdorff distance                  H = max(max_i d(x_i, Y), max_j d(y_j, X)),
// both over the nodes of each mesh (node-sampled: between nodes a surface may lie farther by
// up to about half an edge times the surfaces' angle).
//
// Registration (rigid ICP, analysis/rigid_registration.hpp) moves the simulated mesh onto the
// reference: by the annulus rings (the seed's; each ring resampled evenly, 360 points onto
// 1,440) or by all nodes.
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "valve/analysis/distance_stats.hpp"
#include "valve/analysis/rigid_registration.hpp"
#include "valve/mesh/tri_mesh.hpp"

namespace valve {

enum class Correspondence { nodes, nearest };
enum class Registration { none, annulus, all };

struct ComparisonOptions {
  Correspondence correspondence = Correspondence::nearest;
  Registration registration = Registration::annulus;
  int sections = 0;  ///< planes across the reference's annulus (analysis/sections.hpp); 0: none
  /// Names of the two meshes in error messages (their files).
  std::string simulated_name = "simulated", reference_name = "reference";
};

struct MeshComparison {
  bool registered = false;
  IcpResult icp;
  MatX3 moved;                       ///< simulated nodes after registration
  std::vector<double> error_mm;      ///< per simulated node: to its node (nodes) or to the surface (nearest)
  std::vector<double> node_error_mm;       ///< nearest: per simulated node, to the nearest reference node
  std::vector<double> reference_error_mm;  ///< nearest: per reference node, to the simulated surface
  DistanceStats error, node_error, reference_error;
  double symmetric_mean_mm = 0;  ///< ASSD (nearest)
  double hausdorff_mm = 0;       ///< H (nearest)
  nlohmann::json sections;       ///< the frame and segments when options.sections > 0, else null

  /// The summary's metrics: registration, node_distance or surface_distance,
  /// nearest_node_distance, reference_to_simulated and symmetric_surface_distance, sections.
  nlohmann::json metrics() const;
};

/// Throws InputError (naming the mesh) when nodes are asked of meshes with different node
/// counts, or an annulus registration or sections of a mesh without an annulus ring.
MeshComparison compare_meshes(const TriMesh& simulated, const TriMesh& reference, const ComparisonOptions& options);

}  // namespace valve
