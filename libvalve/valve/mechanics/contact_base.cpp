#include "valve/mechanics/contact_base.hpp"

#include <algorithm>
#include <iterator>

#include "valve/mesh/topology.hpp"

namespace valve {

ContactTopology::ContactTopology(const TriMesh& mesh, bool self_contact, bool between_leaflets)
    : self_(self_contact), between_(between_leaflets), triangles_(mesh.triangles) {
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
  const Topology topo = build_topology(triangles_, n);
  double sum = 0;
  for (const Edge& e : topo.edges) {
    edges_.emplace_back(e.a, e.b);
    boundary_edge_.push_back(e.tris[1] < 0);
    sum += (mesh.points.row(e.a) - mesh.points.row(e.b)).norm();
  }
  mean_edge_ = topo.edges.empty() ? 0.0 : sum / topo.edges.size();
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
  for (int k = 0; k < 3; ++k)
    if (in_ring(node, t[k])) return true;
  return leaflet_rule_excludes(node, leaflet_[triangle]);
}

bool ContactTopology::excluded_edges(int a, int b, int c, int d) const {
  for (int u : {a, b})
    for (int v : {c, d})
      if (in_ring(u, v)) return true;
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
