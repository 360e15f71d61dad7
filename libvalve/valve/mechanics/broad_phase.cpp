#include "valve/mechanics/broad_phase.hpp"

#include <algorithm>
#include <atomic>
#include <cassert>
#include <cmath>
#include <cstdint>
#include <functional>
#include <numeric>

#include "valve/core/error.hpp"
#include "valve/core/parallel.hpp"

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

bool overlap(const Box& a, const Box& b) {
  return (a.hi.array() >= b.lo.array()).all() && (a.lo.array() <= b.hi.array()).all();
}

/// (query_ids[k], target) for every target box that overlaps query box k and that
/// skip(query_ids[k], target) does not refuse, sorted by query id, then target. A uniform
/// grid over the targets, stored as one array of target lists per cell (CSR); a query visits
/// the cells its box overlaps and meets a target once however many of those cells list it
/// (a stamp per target). The cell is the larger of the mean target and the mean query box
/// size, so a point visits one cell and an inflated box a few; it grows while the grid would
/// have more than 4 cells per target (plus 4,096). A target much larger than the mean is
/// listed in every cell it covers: fine for meshes, whose triangles and edges are of one
/// size, not for boxes of very different sizes.
bool finite(const Box& b) { return b.lo.allFinite() && b.hi.allFinite(); }

template <class Skip>
std::vector<std::pair<int, int>> grid_overlaps(const std::vector<Box>& targets, const std::vector<Box>& queries,
                                               const std::vector<int>& query_ids, const Skip& skip) {
  std::vector<std::pair<int, int>> pairs;
  if (targets.empty() || queries.empty()) return pairs;
  Vec3 lo = targets[0].lo, hi = targets[0].hi;
  double target_extent = 0, query_extent = 0;
  // A non-finite coordinate would make the cell count below never fit (and the cast to int
  // undefined); the solvers stop on non-finite states before they get here.
  for (const auto& b : targets) {
    if (!finite(b)) throw NumericalError("broad phase: non-finite positions");
    target_extent += (b.hi - b.lo).maxCoeff();
    lo = lo.cwiseMin(b.lo);
    hi = hi.cwiseMax(b.hi);
  }
  for (const auto& b : queries) {
    if (!finite(b)) throw NumericalError("broad phase: non-finite positions");
    query_extent += (b.hi - b.lo).maxCoeff();
  }
  double cell = std::max({target_extent / targets.size(), query_extent / queries.size(), 1e-12});
  if (!std::isfinite(cell) || !(hi - lo).allFinite()) throw NumericalError("broad phase: coordinates overflow");
  Eigen::Array3i dims;
  const double max_cells = 4.0 * targets.size() + 4096;
  while (true) {
    const Eigen::Array3d d = ((hi - lo) / cell).array().floor() + 1;
    if (d.prod() <= max_cells) {
      dims = d.cast<int>();
      break;
    }
    cell *= 1.25;
  }
  // Clamped before the cast: a query far outside the scene stays a valid int.
  const Eigen::Array3d last = (dims - 1).cast<double>();
  auto cell_of = [&](const Vec3& p) {
    return ((p - lo) / cell).array().floor().max(0.0).min(last).cast<int>().eval();
  };
  auto index = [&](int cx, int cy, int cz) { return (static_cast<long>(cz) * dims.y() + cy) * dims.x() + cx; };
  std::vector<int> start(static_cast<size_t>(dims.prod()) + 1, 0), entries;
  auto for_cells = [&](const Box& b, auto&& visit) {
    const Eigen::Array3i a = cell_of(b.lo), c = cell_of(b.hi);
    for (int cz = a.z(); cz <= c.z(); ++cz)
      for (int cy = a.y(); cy <= c.y(); ++cy)
        for (int cx = a.x(); cx <= c.x(); ++cx) visit(index(cx, cy, cz));
  };
  for (const auto& b : targets) for_cells(b, [&](long k) { ++start[k + 1]; });
  std::partial_sum(start.begin(), start.end(), start.begin());
  entries.resize(start.back());
  std::vector<int> fill(start.begin(), start.end() - 1);
  for (size_t t = 0; t < targets.size(); ++t) for_cells(targets[t], [&](long k) { entries[fill[k]++] = static_cast<int>(t); });

  // The queries in chunks (core/parallel.hpp), each chunk's pairs gathered in query order. A
  // target is looked at once per query: `seen` holds, per thread, the last (call, query) stamp
  // that looked at it. The call counter and `seen` belong together (one pair per instantiation
  // of this template): a stamp from another counter could match and drop a pair.
  static std::atomic<std::uint64_t> calls{0};
  const std::uint64_t call = ++calls;
  assert(queries.size() < (std::uint64_t{1} << 32));
  const Box scene{lo, hi};
  const size_t chunks = chunks_for(queries.size());
  std::vector<std::vector<std::pair<int, int>>> found(chunks);
  for_each_chunk(queries.size(), chunks, [&](size_t chunk, size_t begin, size_t end) {
    thread_local std::vector<std::uint64_t> seen;
    if (seen.size() < targets.size()) seen.resize(targets.size(), 0);
    auto& out = found[chunk];
    for (size_t q = begin; q < end; ++q) {
      if (!overlap(queries[q], scene)) continue;
      const size_t first = out.size();
      const int id = query_ids[q];
      const std::uint64_t stamp = (call << 32) | q;
      for_cells(queries[q], [&](long k) {
        for (int j = start[k]; j < start[k + 1]; ++j) {
          const int t = entries[j];
          if (seen[t] == stamp) continue;
          seen[t] = stamp;
          if (skip(id, t) || !overlap(targets[t], queries[q])) continue;
          out.emplace_back(id, t);
        }
      });
      std::sort(out.begin() + first, out.end());
    }
  });
  append_chunks(pairs, found);
  // Runs are sorted per query; ids that are not strictly increasing need a global sort.
  if (std::adjacent_find(query_ids.begin(), query_ids.end(), std::greater_equal<int>()) != query_ids.end())
    std::sort(pairs.begin(), pairs.end());
  return pairs;
}

/// A bounding volume hierarchy over the inflated boxes: a binary tree built top down, each
/// node's boxes split at the median centre along the longest axis of their centres' extent,
/// down to leaves of at most kLeafSize; each query point walks the subtrees whose box holds it.
/// O(T log T) to build, O(log T + pairs) per query on meshes. Written here rather than taken
/// from CGAL's AABB tree: that tree answers kernel predicates on geometric objects, and would
/// bring CGAL's headers into the mechanics layer (core/ compiles none), for what is a box test.
class BoxTree {
 public:
  explicit BoxTree(const std::vector<Box>& boxes) : boxes_(boxes), order_(boxes.size()) {
    std::iota(order_.begin(), order_.end(), 0);
    if (!boxes.empty()) build(0, static_cast<int>(boxes.size()));
  }
  /// The boxes that hold p, in any order.
  template <class Visit>
  void visit_holding(const Vec3& p, Visit&& visit) const {
    if (nodes_.empty()) return;
    int stack[64];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
      const Node& n = nodes_[stack[--top]];
      if (!inside(n.box, p)) continue;
      if (n.right < 0) {
        for (int k = n.begin; k < n.end; ++k)
          if (inside(boxes_[order_[k]], p)) visit(order_[k]);
        continue;
      }
      stack[top++] = n.left;
      stack[top++] = n.right;
    }
  }

 private:
  static constexpr int kLeafSize = 4;
  struct Node {
    Box box;
    int begin, end;        // the range of order_ below this node
    int left = -1, right = -1;
  };
  int build(int begin, int end) {
    const int id = static_cast<int>(nodes_.size());
    nodes_.push_back({boxes_[order_[begin]], begin, end});
    Box box = boxes_[order_[begin]];
    Vec3 lo = box.lo + box.hi, hi = lo;  // twice the centres' extent
    for (int k = begin + 1; k < end; ++k) {
      const Box& b = boxes_[order_[k]];
      box.lo = box.lo.cwiseMin(b.lo), box.hi = box.hi.cwiseMax(b.hi);
      const Vec3 c = b.lo + b.hi;
      lo = lo.cwiseMin(c), hi = hi.cwiseMax(c);
    }
    nodes_[id].box = box;
    if (end - begin <= kLeafSize) return id;
    int axis = 0;
    (hi - lo).maxCoeff(&axis);
    const int mid = begin + (end - begin) / 2;
    std::nth_element(order_.begin() + begin, order_.begin() + mid, order_.begin() + end, [&](int a, int b) {
      return boxes_[a].lo[axis] + boxes_[a].hi[axis] < boxes_[b].lo[axis] + boxes_[b].hi[axis];
    });
    // Halving the range bounds the depth by log2(T / kLeafSize) + 1, well within the stack.
    const int left = build(begin, mid);
    const int right = build(mid, end);
    nodes_[id].left = left, nodes_[id].right = right;
    return id;
  }

  const std::vector<Box>& boxes_;
  std::vector<int> order_;
  std::vector<Node> nodes_;
};

/// `nodes` in increasing order (query_nodes), so the gathered pairs are sorted.
std::vector<std::pair<int, int>> bounding_volume_hierarchy(const VecX& x, const std::vector<Box>& boxes,
                                                           const std::vector<int>& nodes) {
  if (boxes.empty() || nodes.empty()) return {};  // as the grid, which returns before its checks
  // As the grid: non-finite positions stop here (a NaN centre would break the median splits).
  for (const auto& b : boxes)
    if (!finite(b)) throw NumericalError("broad phase: non-finite positions");
  for (int i : nodes)
    if (!node3(x, i).allFinite()) throw NumericalError("broad phase: non-finite positions");
  const BoxTree tree(boxes);
  // The queries in chunks (core/parallel.hpp), each node's triangles sorted, gathered in order.
  const size_t chunks = chunks_for(nodes.size());
  std::vector<std::vector<std::pair<int, int>>> found(chunks);
  for_each_chunk(nodes.size(), chunks, [&](size_t chunk, size_t begin, size_t end) {
    auto& out = found[chunk];
    for (size_t q = begin; q < end; ++q) {
      const size_t first = out.size();
      tree.visit_holding(node3(x, nodes[q]), [&](int t) { out.emplace_back(nodes[q], t); });
      std::sort(out.begin() + first, out.end());
    }
  });
  std::vector<std::pair<int, int>> pairs;
  append_chunks(pairs, found);
  return pairs;
}

std::vector<std::pair<int, int>> spatial_hash(const VecX& x, const std::vector<Box>& boxes,
                                              const std::vector<int>& nodes) {
  std::vector<Box> points(nodes.size());
  for (size_t k = 0; k < nodes.size(); ++k) points[k] = {node3(x, nodes[k]), node3(x, nodes[k])};
  return grid_overlaps(boxes, points, nodes, [](int, int) { return false; });
}

}  // namespace

BroadPhaseMethod parse_broad_phase(const std::string& name) {
  if (name == "sweep_and_prune") return BroadPhaseMethod::sweep_and_prune;
  if (name == "spatial_hash") return BroadPhaseMethod::spatial_hash;
  if (name == "bvh") return BroadPhaseMethod::bvh;
  throw InputError("broad phase: expected sweep_and_prune, spatial_hash or bvh, found '" + name + "'");
}

std::string to_string(BroadPhaseMethod m) {
  switch (m) {
    case BroadPhaseMethod::sweep_and_prune: return "sweep_and_prune";
    case BroadPhaseMethod::spatial_hash: return "spatial_hash";
    case BroadPhaseMethod::bvh: return "bvh";
  }
  return "spatial_hash";
}

std::vector<std::pair<int, int>> broad_phase_pairs(const VecX& x, const std::vector<Tri>& triangles,
                                                   double margin, BroadPhaseMethod method,
                                                   const std::vector<char>& query) {
  const auto boxes = inflated_boxes(x, triangles, margin);
  auto nodes = query_nodes(static_cast<int>(x.size() / 3), query);
  switch (method) {
    case BroadPhaseMethod::sweep_and_prune: return sweep_and_prune(x, boxes, std::move(nodes));
    case BroadPhaseMethod::bvh: return bounding_volume_hierarchy(x, boxes, nodes);
    case BroadPhaseMethod::spatial_hash: break;
  }
  return spatial_hash(x, boxes, nodes);
}

std::vector<std::pair<int, int>> edge_box_pairs(const VecX& x, const std::vector<std::pair<int, int>>& edges,
                                                const std::vector<int>& query_edges, double margin) {
  std::vector<Box> boxes(edges.size()), queries;
  for (size_t e = 0; e < edges.size(); ++e) {
    const Vec3 a = node3(x, edges[e].first), b = node3(x, edges[e].second);
    boxes[e] = {a.cwiseMin(b), a.cwiseMax(b)};
  }
  queries.reserve(query_edges.size());
  std::vector<char> is_query(edges.size(), 0);
  for (int q : query_edges) {
    queries.push_back({boxes[q].lo.array() - margin, boxes[q].hi.array() + margin});
    is_query[q] = 1;
  }
  // Itself, and a query edge below this one: that pair is (lower, this) from the other side.
  return grid_overlaps(boxes, queries, query_edges, [&](int q, int e) { return e == q || (is_query[e] && e < q); });
}

}  // namespace valve
