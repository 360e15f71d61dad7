#pragma once
// Rigid point-to-point ICP (Besl & McKay 1992): alternately pair each source point with its
// nearest target point and solve for the best rotation and translation of the pairs in
// closed form (Umeyama 1991, Eigen::umeyama without scaling). Used to register a simulated
// valve to a closed-valve scan by their annuli (seed 5.2.2) or by all points, and a closed
// annulus ring to an open one. Nearest neighbours come from a k-d tree of the target
// (mesh/nearest_points.hpp), built once per registration.
#include "valve/core/types.hpp"

namespace valve {

struct RigidTransform {
  Mat3 rotation = Mat3::Identity();
  Vec3 translation = Vec3::Zero();
  Vec3 apply(const Vec3& p) const { return rotation * p + translation; }
  MatX3 apply(const MatX3& points) const;
  double rotation_angle_deg() const;
};

struct IcpOptions {
  int max_iterations = 1000;
  double tolerance = 1e-8;  // mm: stop when no source point moves more between iterations
  bool align_centroids_first = true;
};

struct IcpResult {
  RigidTransform transform;  // maps source onto target
  double rms = 0;            // RMS nearest-point distance at the last pairing, mm
  int iterations = 0;
  bool converged = false;
};

/// Registers `source` onto `target` (rows are points).
IcpResult icp_point_to_point(const MatX3& source, const MatX3& target, const IcpOptions& options = {});

}  // namespace valve
