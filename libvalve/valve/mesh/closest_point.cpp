#include "valve/mesh/closest_point.hpp"

#include <algorithm>
#include <limits>

#include <cmath>

namespace valve {

int nearest_point_index(const MatX3& points, const Vec3& p, double* distance) {
  int best = -1;
  double best_d2 = std::numeric_limits<double>::infinity();
  for (int i = 0; i < points.rows(); ++i) {
    const double d2 = (points.row(i).transpose() - p).squaredNorm();
    if (d2 < best_d2) best_d2 = d2, best = i;
  }
  if (distance) *distance = std::sqrt(best_d2);
  return best;
}

Vec3 closest_point_weights(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return {1, 0, 0};
  const Vec3 bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return {0, 1, 0};
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    const double v = d1 / (d1 - d3);
    return {1 - v, v, 0};
  }
  const Vec3 cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return {0, 0, 1};
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    const double w = d2 / (d2 - d6);
    return {1 - w, 0, w};
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0) {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return {0, 1 - w, w};
  }
  const double denom = va + vb + vc;
  if (!(denom > 0)) return {1, 0, 0};  // degenerate triangle: its first vertex
  const double v = vb / denom, w = vc / denom;
  return {1 - v - w, v, w};
}

std::pair<double, double> closest_segment_parameters(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  const Vec3 d1 = b - a, d2 = d - c, r = a - c;
  const double A = d1.squaredNorm(), E = d2.squaredNorm(), F = d2.dot(r);
  const double eps = 1e-24;
  auto clamp01 = [](double v) { return std::clamp(v, 0.0, 1.0); };
  if (A <= eps && E <= eps) return {0, 0};
  if (A <= eps) return {0, clamp01(F / E)};
  const double C = d1.dot(r);
  if (E <= eps) return {clamp01(-C / A), 0};
  const double B = d1.dot(d2), denom = A * E - B * B;
  double s = denom > 0 ? clamp01((B * F - C * E) / denom) : 0.0;
  double t = (B * s + F) / E;
  if (t < 0) t = 0, s = clamp01(-C / A);
  else if (t > 1) t = 1, s = clamp01((B - C) / A);
  return {s, t};
}

}  // namespace valve
