#include "valve/analysis/rigid_registration.hpp"

#include <Eigen/Geometry>
#include <cmath>

#include "valve/mesh/nearest_points.hpp"

namespace valve {

MatX3 RigidTransform::apply(const MatX3& points) const {
  MatX3 out(points.rows(), 3);
  for (int i = 0; i < points.rows(); ++i) out.row(i) = apply(Vec3(points.row(i).transpose())).transpose();
  return out;
}

double RigidTransform::rotation_angle_deg() const {
  const double c = std::clamp((rotation.trace() - 1) / 2, -1.0, 1.0);
  return std::acos(c) * 180 / M_PI;
}

IcpResult icp_point_to_point(const MatX3& source, const MatX3& target, const IcpOptions& options) {
  IcpResult res;
  if (source.rows() == 0 || target.rows() == 0) return res;
  if (options.align_centroids_first)
    res.transform.translation = (target.colwise().mean() - source.colwise().mean()).transpose();
  const int n = static_cast<int>(source.rows());
  Eigen::Matrix3Xd src(3, n), dst(3, n);
  const NearestPoints nearest_target(target);
  for (int it = 0; it < options.max_iterations; ++it) {
    double sum = 0;
    for (int i = 0; i < n; ++i) {
      double d = 0;
      const int best = nearest_target.nearest(res.transform.apply(Vec3(source.row(i).transpose())), &d);
      src.col(i) = source.row(i).transpose();
      dst.col(i) = target.row(best).transpose();
      sum += d * d;
    }
    res.rms = std::sqrt(sum / n);
    res.iterations = it + 1;
    const Eigen::Matrix4d T = Eigen::umeyama(src, dst, false);
    RigidTransform next;
    next.rotation = T.topLeftCorner<3, 3>();
    next.translation = T.topRightCorner<3, 1>();
    // Converged when no point moves by more than the tolerance between iterations: on a
    // curve the pairs slide slowly, so a small change of the RMS alone stops too early.
    double moved = 0;
    for (int i = 0; i < n; ++i) moved = std::max(moved, (next.apply(Vec3(src.col(i))) - res.transform.apply(Vec3(src.col(i)))).norm());
    res.transform = next;
    if (moved < options.tolerance) {
      res.converged = true;
      break;
    }
  }
  return res;
}

}  // namespace valve
