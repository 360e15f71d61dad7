#pragma once
// Where the annulus goes when the valve closes (seed 5.2.2): the closed-valve mesh's annulus
// ring is registered rigidly to the open mesh's annulus, and each open annulus node is mapped
// to the point of the closed ring at the same fraction of arc length, the ring's start and
// sense chosen to minimise the squared node-to-target distances.
#include <string>
#include <vector>

#include "valve/analysis/rigid_registration.hpp"
#include "valve/mesh/tri_mesh.hpp"

namespace valve {

/// The annulus of a membrane mesh as an ordered ring of node indices: the boundary loop with
/// the most nodes marked fixed (NodeRole) or attached (BoundaryType), restricted to those
/// nodes. Empty if the mesh has no boundary loop with a marked node.
std::vector<int> annulus_ring(const TriMesh& mesh);

/// The atrial direction of a valve mesh: the normal of the best-fit plane (least-squares, the
/// covariance's smallest eigenvector) of its fixed or attached nodes, pointing away from the
/// leaflets' centroid (the leaflets hang into the ventricle); +z with fewer than 3 such nodes.
Vec3 annulus_atrial_direction(const TriMesh& mesh);

/// `count` points equally spaced by arc length along the closed polyline through `ring`
/// (rows in order): ICP against ring nodes directly would lock onto node spacing.
MatX3 resample_ring(const MatX3& ring, int count);

struct AnnulusTargets {
  std::vector<int> nodes;        // open mesh annulus nodes (ring order)
  MatX3 targets;                 // their closed positions, in the open mesh's frame
  RigidTransform registration;   // closed mesh frame -> open mesh frame
  double ring_rms_mm = 0;        // RMS distance of the registered closed ring to the open one
  double mean_motion_mm = 0, max_motion_mm = 0;
  double open_length_mm = 0, closed_length_mm = 0;
};

/// Throws InputError naming `closed_file` when the closed mesh has no annulus ring (no
/// boundary loop with fixed or attached nodes), or `open_file` for the open mesh.
AnnulusTargets annulus_targets(const TriMesh& open, const TriMesh& closed, bool register_rigidly,
                               const std::string& open_file, const std::string& closed_file);

/// The same by node correspondence, for two states of one mesh (a model's open and closed
/// frames, same node numbering): every fixed or attached node of the open mesh goes to the
/// position of the same node in the closed mesh, after an optional rigid fit of the closed
/// annulus nodes onto the open ones (Umeyama, no scaling). Throws InputError naming
/// `closed_file` when the node counts differ, `open_file` when there is no annulus.
AnnulusTargets annulus_targets_by_node(const TriMesh& open, const TriMesh& closed, bool register_rigidly,
                                       const std::string& open_file, const std::string& closed_file);

}  // namespace valve
