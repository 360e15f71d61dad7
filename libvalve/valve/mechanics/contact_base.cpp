#include "valve/mechanics/contact_base.hpp"

#include <algorithm>
#include <iterator>

#include "valve/mechanics/broad_phase.hpp"
#include "valve/mesh/closest_point.hpp"
#include "valve/mesh/topology.hpp"

namespace valve {

ContactTopology::ContactTopology(const TriMesh& mesh, bool self_contact, bool between_leaflets, double rest_reach)
    : self_(self_contact), between_(between_leaflets), rest_reach_(rest_reach), triangles_(mesh.triangles) {
  const int n = mesh.num_nodes();
  leaflet_ = mesh.leaflet.size() == triangles_.size() ? mesh.leaflet : std::vector<int>(triangles_.size(), 0);
  node_leaflets_.assign(n, {});
  ring_.assign(n, {});
  for (size_t t = 0; t < triangles_.size(); ++t)
    for (int k = 0; k < 3; ++k) {
      node_leaflets_[triangles_[t][k]].push_back(leaflet_[t]);
      for (int j = 0; j < 3; ++j) ring_[triangles_[t][k]].push_back(triangles_[t][j]);
    }
  for (auto* v : {&node_leaflets_, &ring_})
    for (auto& list : *v) {
      std::sort(list.begin(), list.end());
      list.erase(std::unique(list.begin(), list.end()), list.end());
    }
  triangle_nodes_.assign(n, 0);
  for (int i = 0; i < n; ++i) triangle_nodes_[i] = !ring_[i].empty();
  const Topology topo = build_topology(triangles_, n);
  double sum = 0;
  for (const Edge& e : topo.edges) {
    edges_.emplace_back(e.a, e.b);
    boundary_edge_.push_back(e.tris[1] < 0);
    sum += (mesh.points.row(e.a) - mesh.points.row(e.b)).norm();
  }
  mean_edge_ = topo.edges.empty() ? 0.0 : sum / topo.edges.size();
  rest_close_faces_.assign(n, {});
  rest_close_edges_.assign(edges_.size(), {});
  const bool has_start = mesh.initial.rows() == n;
  exclude_close_at(flatten(mesh.points), has_start);
  if (has_start) exclude_close_at(flatten(mesh.initial));
}

bool ContactTopology::same_leaflet(int node, int triangle) const { return on_leaflet(node, leaflet_[triangle]); }

bool ContactTopology::same_leaflet_edges(int a, int b, int c, int d) const {
  for (int l : node_leaflets_[a])
    if (on_leaflet(b, l) && on_leaflet(c, l) && on_leaflet(d, l)) return true;
  return false;
}

namespace {

// Sorts a list of (pair, start gap) and keeps each pair once, with its smallest gap.
template <class Key>
void keep_smallest_gap(std::vector<std::pair<Key, double>>& list) {
  std::sort(list.begin(), list.end());
  list.erase(std::unique(list.begin(), list.end(), [](const auto& a, const auto& b) { return a.first == b.first; }),
             list.end());
}

template <class Key>
double gap_of(const std::vector<std::pair<Key, double>>& list, const Key& key) {
  const auto it = std::lower_bound(list.begin(), list.end(), key, [](const auto& e, const Key& k) { return e.first < k; });
  return it != list.end() && it->first == key ? it->second : 0.0;
}

void sort_unique_lists(std::vector<std::vector<int>>& lists) {
  for (auto& list : lists) {
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
  }
}

std::array<int, 4> edge_pair_key(int a, int b, int c, int d) {
  std::array<int, 4> key{std::min(a, b), std::max(a, b), std::min(c, d), std::max(c, d)};
  if (std::make_pair(key[2], key[3]) < std::make_pair(key[0], key[1])) key = {key[2], key[3], key[0], key[1]};
  return key;
}

}  // namespace

void ContactTopology::exclude_close_at(const VecX& x, bool within_leaflets_only) {
  if (!incidence_only()) return;
  const double touching = kTouchingFraction * rest_reach_;
  // Only nodes of triangles: chord points (nodes without one) are never a contact pair's node.
  for (const auto& [i, t] : broad_phase_pairs(x, triangles_, rest_reach_, BroadPhaseMethod::spatial_hash, triangle_nodes_)) {
    const bool same = same_leaflet(i, t);
    if (within_leaflets_only && !same) continue;
    const Tri& tri = triangles_[t];
    const double d = point_triangle_distance(node3(x, i), node3(x, tri[0]), node3(x, tri[1]), node3(x, tri[2]));
    if (d > rest_reach_) continue;
    if (same || d <= touching)
      rest_close_faces_[i].push_back(t);
    else
      narrow_faces_.push_back({{i, t}, d});
  }
  sort_unique_lists(rest_close_faces_);
  keep_smallest_gap(narrow_faces_);
  std::vector<int> all(edges_.size());
  for (size_t e = 0; e < edges_.size(); ++e) all[e] = static_cast<int>(e);
  for (const auto& [e1, e2] : edge_box_pairs(x, edges_, all, rest_reach_)) {
    const auto [a, b] = edges_[e1];
    const auto [c, d] = edges_[e2];
    const bool same = same_leaflet_edges(a, b, c, d);
    if (within_leaflets_only && !same) continue;
    const double gap = segment_segment_distance(node3(x, a), node3(x, b), node3(x, c), node3(x, d));
    if (gap > rest_reach_) continue;
    if (same || gap <= touching)
      rest_close_edges_[std::min(e1, e2)].push_back(std::max(e1, e2));
    else
      narrow_edges_.push_back({edge_pair_key(a, b, c, d), gap});
  }
  sort_unique_lists(rest_close_edges_);
  keep_smallest_gap(narrow_edges_);
}

double ContactTopology::start_gap(int node, int triangle) const { return gap_of(narrow_faces_, std::make_pair(node, triangle)); }

double ContactTopology::start_gap_edges(int a, int b, int c, int d) const {
  return gap_of(narrow_edges_, edge_pair_key(a, b, c, d));
}

bool ContactTopology::close_at_rest(int node, int triangle) const {
  const auto& list = rest_close_faces_[node];
  return std::binary_search(list.begin(), list.end(), triangle);
}

bool ContactTopology::edges_close_at_rest(int e1, int e2) const {
  const auto& list = rest_close_edges_[std::min(e1, e2)];
  return std::binary_search(list.begin(), list.end(), std::max(e1, e2));
}

bool ContactTopology::in_ring(int node, int other) const {
  return std::binary_search(ring_[node].begin(), ring_[node].end(), other);
}

bool ContactTopology::on_leaflet(int node, int leaflet) const {
  return std::binary_search(node_leaflets_[node].begin(), node_leaflets_[node].end(), leaflet);
}

bool ContactTopology::leaflet_rule_excludes(int node, int leaflet) const {
  const bool self = on_leaflet(node, leaflet) && node_leaflets_[node].size() == 1;
  return self ? !self_ : !between_;
}

bool ContactTopology::excluded(int node, int triangle) const {
  const Tri& t = triangles_[triangle];
  if (incidence_only()) {
    if (node == t[0] || node == t[1] || node == t[2] || close_at_rest(node, triangle)) return true;
  } else {
    for (int k = 0; k < 3; ++k)
      if (in_ring(node, t[k])) return true;
  }
  return leaflet_rule_excludes(node, leaflet_[triangle]);
}

bool ContactTopology::excluded_edges(int e1, int e2) const {
  const auto [a, b] = edges_[e1];
  const auto [c, d] = edges_[e2];
  if (incidence_only()) {
    if (a == c || a == d || b == c || b == d || edges_close_at_rest(e1, e2)) return true;
  } else {
    for (int u : {a, b})
      for (int v : {c, d})
        if (in_ring(u, v)) return true;
  }
  // Both of an edge's nodes share its leaflet; the rule is decided by the first node.
  for (int l : node_leaflets_[c])
    if (on_leaflet(d, l)) return leaflet_rule_excludes(a, l);
  return true;
}

bool grow_couplings(std::vector<std::pair<int, int>>& pattern, std::vector<std::pair<int, int>> added) {
  std::sort(added.begin(), added.end());
  added.erase(std::unique(added.begin(), added.end()), added.end());
  std::vector<std::pair<int, int>> merged;
  std::set_union(pattern.begin(), pattern.end(), added.begin(), added.end(), std::back_inserter(merged));
  const bool grew = merged.size() != pattern.size();
  pattern = std::move(merged);
  return grew;
}

}  // namespace valve
