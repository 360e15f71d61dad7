#pragma once
// What valve-remesh reports: the remeshed membrane and its midpoint subdivisions as meshes
// to write, each with its shape (mesh/quality.hpp) and, against a ground-truth surface, the
// distance of its nodes to it; and the figures of the extraction and the remeshing.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "valve/mesh/named_array.hpp"
#include "valve/mesh/quality.hpp"
#include "valve/mesh/tri_mesh.hpp"
#include "valve/remesh/membrane_extraction.hpp"
#include "valve/remesh/remesher.hpp"

namespace valve {

/// A mesh's shape as the summary lists it: nodes, triangles, quality (mean, min, min away
/// from the boundary, count below 0.6), mean interior valence, boundary loops, manifold.
nlohmann::json mesh_shape_json(const MeshShapeReport& report);

struct RemeshLevel {
  TriMesh mesh;
  std::string file;  ///< NAME.vtp, NAME_x4.vtp, NAME_x16.vtp
  std::vector<NamedArray> arrays;  ///< Quality per triangle; Error_mm per node against a reference
  nlohmann::json entry;  ///< the summary's metrics.meshes entry: file, shape, distance_to_reference
};

/// `mesh` and `subdivisions` (0-2) rounds of midpoint subdivision of it, each splitting every
/// triangle in four. With a reference, each entry has distance_to_reference: the statistics
/// of the node distances to it over all nodes, interior_nodes and boundary_nodes (a free
/// edge or annulus that falls short of the reference's shows in the boundary nodes alone).
std::vector<RemeshLevel> remesh_levels(const TriMesh& mesh, int subdivisions, const std::string& name,
                                       const TriMesh* reference = nullptr);

/// The summary's metrics of extraction and remeshing: atrial direction, extraction, remesh,
/// boundary loops and the annulus and free-edge node counts of `mesh`.
nlohmann::json remesh_metrics(const MembraneSummary& membrane, const RemeshSummary& remesh, const TriMesh& mesh,
                              int boundary_loops);

/// Why a run's mesh is "not_converged": no edge length gave a triangle count within the
/// tolerance of the target, and the closest count found is what is written.
std::string remesh_not_converged_reason(const RemeshOptions& options, const RemeshSummary& remesh, int triangles_found);

/// The stage's one-line report of the first level: triangles, quality, valence, loops and,
/// with a reference, the mean distance to it.
std::string remesh_report_line(const RemeshLevel& first, int boundary_loops);

}  // namespace valve
