#include "valve/mesh/topology.hpp"

#include <algorithm>
#include <map>

namespace valve {

std::vector<std::pair<int, int>> unique_edges(const std::vector<Tri>& triangles) {
  std::vector<std::pair<int, int>> e;
  e.reserve(triangles.size() * 3);
  for (const auto& t : triangles)
    for (int k = 0; k < 3; ++k) {
      int a = t[k], b = t[(k + 1) % 3];
      if (a > b) std::swap(a, b);
      e.emplace_back(a, b);
    }
  std::sort(e.begin(), e.end());
  e.erase(std::unique(e.begin(), e.end()), e.end());
  return e;
}

Topology build_topology(const std::vector<Tri>& triangles, int num_nodes) {
  Topology topo;
  struct Half {
    int a, b, tri;
  };
  std::vector<Half> halves;
  halves.reserve(triangles.size() * 3);
  for (int t = 0; t < static_cast<int>(triangles.size()); ++t)
    for (int k = 0; k < 3; ++k) {
      const int a = triangles[t][k], b = triangles[t][(k + 1) % 3];
      halves.push_back({std::min(a, b), std::max(a, b), t});
    }
  std::sort(halves.begin(), halves.end(), [](const Half& x, const Half& y) {
    return x.a != y.a ? x.a < y.a : (x.b != y.b ? x.b < y.b : x.tri < y.tri);
  });
  for (size_t i = 0; i < halves.size();) {
    size_t j = i;
    while (j < halves.size() && halves[j].a == halves[i].a && halves[j].b == halves[i].b) ++j;
    Edge e{halves[i].a, halves[i].b, {halves[i].tri, j - i > 1 ? halves[i + 1].tri : -1}};
    if (j - i > 2) ++topo.non_manifold_edges;
    topo.edges.push_back(e);
    i = j;
  }
  // Boundary loops: follow directed boundary half-edges (oriented as in their triangle).
  std::multimap<int, int> next;  // from -> to
  for (const auto& e : topo.edges) {
    if (e.tris[1] != -1) continue;
    const Tri& t = triangles[e.tris[0]];
    for (int k = 0; k < 3; ++k) {
      const int a = t[k], b = t[(k + 1) % 3];
      if (std::min(a, b) == e.a && std::max(a, b) == e.b) next.emplace(a, b);
    }
  }
  (void)num_nodes;
  while (!next.empty()) {
    auto it = next.begin();
    const int start = it->first;
    std::vector<int> loop{start};
    int cur = it->second;
    next.erase(it);
    while (cur != start) {
      loop.push_back(cur);
      auto nt = next.find(cur);
      if (nt == next.end()) break;  // open chain (non-manifold boundary): keep what we have
      cur = nt->second;
      next.erase(nt);
    }
    topo.loops.push_back(std::move(loop));
  }
  return topo;
}

bool share_vertex(const Tri& a, const Tri& b) {
  for (int u = 0; u < 3; ++u)
    for (int v = 0; v < 3; ++v)
      if (a[u] == b[v]) return true;
  return false;
}

}  // namespace valve
