#include "valve/mesh/quality.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

namespace valve {

double triangle_quality(const Vec3& a, const Vec3& b, const Vec3& c) {
  const double area = 0.5 * (b - a).cross(c - a).norm();
  const double s = (b - a).squaredNorm() + (c - b).squaredNorm() + (a - c).squaredNorm();
  return s > 0 ? 4.0 * std::sqrt(3.0) * area / s : 0.0;
}

std::vector<double> triangle_qualities(const MatX3& x, const std::vector<Tri>& triangles) {
  std::vector<double> q;
  q.reserve(triangles.size());
  for (const auto& t : triangles) q.push_back(triangle_quality(x.row(t[0]), x.row(t[1]), x.row(t[2])));
  return q;
}

QualitySummary summarize_quality(const std::vector<double>& q) {
  QualitySummary s;
  if (q.empty()) return s;
  s.min = *std::min_element(q.begin(), q.end());
  s.max = *std::max_element(q.begin(), q.end());
  double sum = 0;
  for (double v : q) {
    sum += v;
    if (v < 0.6) ++s.below_0_6;
  }
  s.mean = sum / q.size();
  return s;
}

}  // namespace valve
