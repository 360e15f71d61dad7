#include "valve/mechanics/broad_phase.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>

#include "valve/core/error.hpp"

namespace valve {
namespace {

struct Box {
  Vec3 lo, hi;
};

std::vector<Box> inflated_boxes(const VecX& x, const std::vector<Tri>& triangles, double margin) {
  std::vector<Box> boxes(triangles.size());
  for (size_t t = 0; t < triangles.size(); ++t) {
    Vec3 lo = node3(x, triangles[t][0]), hi = lo;
    for (int k = 1; k < 3; ++k) {
      lo = lo.cwiseMin(Vec3(node3(x, triangles[t][k])));
      hi = hi.cwiseMax(Vec3(node3(x, triangles[t][k])));
    }
    boxes[t] = {lo.array() - margin, hi.array() + margin};
  }
  return boxes;
}

bool inside(const Box& b, const Vec3& p) {
  return (p.array() >= b.lo.array()).all() && (p.array() <= b.hi.array()).all();
}

std::vector<int> query_nodes(int n, const std::vector<char>& query) {
  std::vector<int> nodes;
  for (int i = 0; i < n; ++i)
    if (query.empty() || query[i]) nodes.push_back(i);
  return nodes;
}

std::vector<std::pair<int, int>> sweep_and_prune(const VecX& x, const std::vector<Box>& boxes,
                                                 std::vector<int> nodes) {
  std::vector<int> order(boxes.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int a, int b) { return boxes[a].lo.x() < boxes[b].lo.x(); });
  std::sort(nodes.begin(), nodes.end(), [&](int a, int b) { return x[3 * a] < x[3 * b]; });
  std::vector<std::pair<int, int>> pairs;
  std::vector<int> active;
  size_t next = 0;
  for (int i : nodes) {
    const Vec3 p = node3(x, i);
    while (next < order.size() && boxes[order[next]].lo.x() <= p.x()) active.push_back(order[next++]);
    // Boxes entirely left of the sweep line can never contain a later node.
    active.erase(std::remove_if(active.begin(), active.end(), [&](int t) { return boxes[t].hi.x() < p.x(); }),
                 active.end());
    for (int t : active)
      if (inside(boxes[t], p)) pairs.emplace_back(i, t);
  }
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}

std::vector<std::pair<int, int>> spatial_hash(const VecX& x, const std::vector<Box>& boxes,
                                              const std::vector<int>& nodes) {
  std::vector<std::pair<int, int>> pairs;
  if (boxes.empty() || nodes.empty()) return pairs;
  double mean_extent = 0;
  Vec3 lo = boxes[0].lo, hi = boxes[0].hi;
  for (const auto& b : boxes) {
    mean_extent += (b.hi - b.lo).maxCoeff();
    lo = lo.cwiseMin(b.lo);
    hi = hi.cwiseMax(b.hi);
  }
  const double cell = std::max(mean_extent / boxes.size(), 1e-12);
  // Cell keys packed from integer coordinates relative to the scene's lower corner.
  const Eigen::Array3d count = ((hi - lo) / cell).array().floor() + 1;
  auto key = [&](const Eigen::Array3i& c) {
    return (static_cast<int64_t>(c.z()) * static_cast<int64_t>(count.y()) + c.y()) * static_cast<int64_t>(count.x()) + c.x();
  };
  auto cell_of = [&](const Vec3& p) { return ((p - lo) / cell).array().floor().cast<int>().eval(); };
  std::vector<std::pair<int64_t, int>> entries;  // (cell key, triangle)
  for (size_t t = 0; t < boxes.size(); ++t) {
    const Eigen::Array3i a = cell_of(boxes[t].lo), b = cell_of(boxes[t].hi);
    for (int cz = a.z(); cz <= b.z(); ++cz)
      for (int cy = a.y(); cy <= b.y(); ++cy)
        for (int cx = a.x(); cx <= b.x(); ++cx) entries.emplace_back(key({cx, cy, cz}), static_cast<int>(t));
  }
  std::sort(entries.begin(), entries.end());
  for (int i : nodes) {
    const Vec3 p = node3(x, i);
    if ((p.array() < lo.array()).any() || (p.array() > hi.array()).any()) continue;
    const int64_t k = key(cell_of(p));
    auto it = std::lower_bound(entries.begin(), entries.end(), std::make_pair(k, -1));
    for (; it != entries.end() && it->first == k; ++it)
      if (inside(boxes[it->second], p)) pairs.emplace_back(i, it->second);
  }
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}

}  // namespace

BroadPhaseMethod parse_broad_phase(const std::string& name) {
  if (name == "sweep_and_prune") return BroadPhaseMethod::sweep_and_prune;
  if (name == "spatial_hash") return BroadPhaseMethod::spatial_hash;
  throw InputError("broad phase: expected sweep_and_prune or spatial_hash, found '" + name + "'");
}

std::string to_string(BroadPhaseMethod m) {
  return m == BroadPhaseMethod::sweep_and_prune ? "sweep_and_prune" : "spatial_hash";
}

std::vector<std::pair<int, int>> broad_phase_pairs(const VecX& x, const std::vector<Tri>& triangles,
                                                   double margin, BroadPhaseMethod method,
                                                   const std::vector<char>& query) {
  const auto boxes = inflated_boxes(x, triangles, margin);
  auto nodes = query_nodes(static_cast<int>(x.size() / 3), query);
  return method == BroadPhaseMethod::sweep_and_prune ? sweep_and_prune(x, boxes, std::move(nodes))
                                                     : spatial_hash(x, boxes, nodes);
}

std::vector<std::pair<int, int>> edge_box_pairs(const VecX& x, const std::vector<std::pair<int, int>>& edges,
                                                const std::vector<int>& query_edges, double margin) {
  std::vector<Box> boxes(edges.size());
  double widest_x = 0;
  for (size_t e = 0; e < edges.size(); ++e) {
    const Vec3 a = node3(x, edges[e].first), b = node3(x, edges[e].second);
    boxes[e] = {a.cwiseMin(b), a.cwiseMax(b)};
    widest_x = std::max(widest_x, boxes[e].hi.x() - boxes[e].lo.x());
  }
  std::vector<int> order(edges.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int a, int b) { return boxes[a].lo.x() < boxes[b].lo.x(); });
  std::vector<double> lower_x(order.size());
  for (size_t k = 0; k < order.size(); ++k) lower_x[k] = boxes[order[k]].lo.x();

  std::vector<std::pair<int, int>> pairs;
  for (int q : query_edges) {
    const Vec3 lo = boxes[q].lo.array() - margin, hi = boxes[q].hi.array() + margin;
    const size_t first = pairs.size();
    // An edge reaching into [lo.x, hi.x] starts at most its own x extent before lo.x.
    auto k = std::lower_bound(lower_x.begin(), lower_x.end(), lo.x() - widest_x) - lower_x.begin();
    for (; k < static_cast<long>(order.size()) && lower_x[k] <= hi.x(); ++k) {
      const int e = order[k];
      if (e != q && (boxes[e].hi.array() >= lo.array()).all() && (boxes[e].lo.array() <= hi.array()).all())
        pairs.emplace_back(q, e);
    }
    // Each query's run sorted on its own: with every edge a query (interior edge contact) one
    // sort of the whole list cost as much as the sweep.
    std::sort(pairs.begin() + first, pairs.end());
  }
  if (!std::is_sorted(query_edges.begin(), query_edges.end())) std::sort(pairs.begin(), pairs.end());
  return pairs;
}

}  // namespace valve
