#pragma once
// Eigen aliases used across libvalve. Positions of N nodes are stored either as an
// N x 3 row-major matrix (mesh geometry) or as a flat 3N vector (solver state), with
// node i's coordinates at entries 3i, 3i+1, 3i+2.
#include <Eigen/Core>
#include <algorithm>
#include <cstdint>
#include <vector>

namespace valve {

using Vec2 = Eigen::Vector2d;
using Vec3 = Eigen::Vector3d;
using Mat2 = Eigen::Matrix2d;
using Mat3 = Eigen::Matrix3d;
using VecX = Eigen::VectorXd;
using MatX3 = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;
using Tri = Eigen::Vector3i;

/// Node i's 3-vector inside a flat 3N vector.
inline auto node3(VecX& v, int i) { return v.segment<3>(3 * i); }
inline auto node3(const VecX& v, int i) { return v.segment<3>(3 * i); }

/// The largest |v_i| over the nodes of a flat 3N vector (e.g. the longest move of a step).
inline double largest_node_norm(const VecX& v) {
  double m = 0;
  for (int i = 0; i < v.size() / 3; ++i) m = std::max(m, node3(v, i).norm());
  return m;
}

/// [a]×, the matrix with [a]× b = a × b.
inline Mat3 cross_matrix(const Vec3& a) {
  Mat3 m;
  m << 0, -a.z(), a.y(), a.z(), 0, -a.x(), -a.y(), a.x(), 0;
  return m;
}

/// Flattens an N x 3 matrix into a 3N vector (node-major).
inline VecX flatten(const MatX3& m) {
  return Eigen::Map<const VecX>(m.data(), m.size());
}
/// Inverse of flatten.
inline MatX3 unflatten(const VecX& v) {
  return Eigen::Map<const MatX3>(v.data(), v.size() / 3, 3);
}

}  // namespace valve
