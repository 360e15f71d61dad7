#include "valve/analysis/distance_stats.hpp"

#include <algorithm>
#include <cmath>

#include "valve/core/error.hpp"

namespace valve {

nlohmann::json DistanceStats::to_json() const {
  return {{"mean_mm", mean}, {"max_mm", max}, {"rms_mm", rms}, {"p95_mm", p95}, {"count", count}};
}

DistanceStats summarize_distances(const std::vector<double>& d) {
  DistanceStats s;
  s.count = static_cast<int>(d.size());
  if (d.empty()) return s;
  double sum = 0, sum2 = 0;
  for (double x : d) sum += x, sum2 += x * x, s.max = std::max(s.max, x);
  s.mean = sum / d.size();
  s.rms = std::sqrt(sum2 / d.size());
  // 95th percentile by linear interpolation between order statistics.
  std::vector<double> sorted = d;
  std::sort(sorted.begin(), sorted.end());
  const double pos = 0.95 * (sorted.size() - 1);
  const size_t lo = static_cast<size_t>(std::floor(pos));
  const size_t hi = std::min(lo + 1, sorted.size() - 1);
  s.p95 = sorted[lo] + (pos - lo) * (sorted[hi] - sorted[lo]);
  return s;
}

std::vector<double> corresponding_node_distances(const MatX3& a, const MatX3& b) {
  if (a.rows() != b.rows())
    throw InputError("node correspondence: expected meshes with the same number of nodes, found " +
                     std::to_string(a.rows()) + " and " + std::to_string(b.rows()));
  std::vector<double> d(a.rows());
  for (Eigen::Index i = 0; i < a.rows(); ++i) d[i] = (a.row(i) - b.row(i)).norm();
  return d;
}

}  // namespace valve
