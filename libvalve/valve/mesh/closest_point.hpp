#pragma once
// Closest-point queries (Ericson, Real-Time Collision Detection, 5.1.5 and 5.1.9), written
// here rather than taken from CGAL because contact forces and surface distances need the
// barycentric weights of the closest point, which CGAL's squared_distance does not return,
// and contact calls them in its inner loop.
#include <algorithm>
#include <utility>

#include "valve/core/types.hpp"

namespace valve {

/// Index of the row of `points` nearest to p (brute force; -1 if there are none), and its
/// distance in `distance` when given.
int nearest_point_index(const MatX3& points, const Vec3& p, double* distance = nullptr);

/// Closest point of triangle (a, b, c) to p as barycentric weights (w_a, w_b, w_c).
Vec3 closest_point_weights(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c);
/// Parameter s in [0, 1] of the point a + s (b − a) of the segment (a, b) nearest to p (0 when
/// the segment has no length), for points in the plane (Vec2) or in space (Vec3).
template <class V>
double point_segment_parameter(const V& p, const V& a, const V& b) {
  const V ab = b - a;
  return std::clamp((p - a).dot(ab) / std::max(ab.squaredNorm(), 1e-300), 0.0, 1.0);
}
/// Distance from p to the segment (a, b) (to a when the segment has no length). Inline: the
/// voxelizer calls it for every voxel near a tube.
inline double point_segment_distance(const Vec3& p, const Vec3& a, const Vec3& b) {
  return (p - (a + point_segment_parameter(p, a, b) * (b - a))).norm();
}
/// Parameters (s, t) of the closest points a + s (b − a), c + t (d − c) of two segments.
std::pair<double, double> closest_segment_parameters(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d);

/// Distance from p to triangle (a, b, c). Inline: contact's candidate lists call it per pair.
inline double point_triangle_distance(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 w = closest_point_weights(p, a, b, c);
  return (p - (w[0] * a + w[1] * b + w[2] * c)).norm();
}
/// Distance between the segments (a, b) and (c, d).
inline double segment_segment_distance(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  const auto [s, t] = closest_segment_parameters(a, b, c, d);
  return (a + s * (b - a) - c - t * (d - c)).norm();
}

}  // namespace valve
