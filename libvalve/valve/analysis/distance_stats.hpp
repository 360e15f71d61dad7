#pragma once
// Distances between two meshes and their summary statistics (mean, max, RMS, 95th
// percentile), used by valve-compare and the studies.
#include <nlohmann/json.hpp>
#include <vector>

#include "valve/core/types.hpp"

namespace valve {

struct DistanceStats {
  double mean = 0, max = 0, rms = 0, p95 = 0;
  int count = 0;
  nlohmann::json to_json() const;
};

DistanceStats summarize_distances(const std::vector<double>& d);

/// |a_i - b_i| for meshes with the same node numbering (e.g. two models on one mesh, or
/// the Texas TriValve frames). Throws InputError if the node counts differ.
std::vector<double> corresponding_node_distances(const MatX3& a, const MatX3& b);

}  // namespace valve
