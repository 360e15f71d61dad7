#include "valve/analysis/leaflet_columns.hpp"

#include <Eigen/Geometry>
#include <Eigen/SparseCholesky>

#include <algorithm>
#include <cmath>
#include <limits>

#include "valve/analysis/leaflet_metrics.hpp"
#include "valve/mesh/closest_point.hpp"
#include "valve/mesh/topology.hpp"

namespace valve {

namespace {

// Arc length of the point of the polyline `line` (rest positions X, cumulative arc `arc`)
// nearest to p.
double nearest_arc(const Vec3& p, const std::vector<int>& line, const std::vector<double>& arc, const VecX& X) {
  double best = std::numeric_limits<double>::infinity(), s = 0;
  for (std::size_t k = 1; k < line.size(); ++k) {
    const Vec3 a = node3(X, line[k - 1]), b = node3(X, line[k]);
    const double t = point_segment_parameter(p, a, b);
    const double dist2 = (a + t * (b - a) - p).squaredNorm();
    if (dist2 < best) best = dist2, s = arc[k - 1] + t * (arc[k] - arc[k - 1]);
  }
  return s;
}

}  // namespace

LeafletColumns::LeafletColumns(const TriMesh& m, int leaflet) {
  const int n = m.num_nodes();
  across_.assign(n, std::numeric_limits<double>::quiet_NaN());
  for (int t = 0; t < m.num_triangles(); ++t)
    if (m.leaflet.empty() || m.leaflet[t] == leaflet) tris_.push_back(m.triangles[t]);
  free_edge_ = free_edge_polyline(m, leaflet);
  if (free_edge_.size() < 2) {
    free_edge_.clear();
    return;
  }
  const VecX X = flatten(m.points);
  arc_.assign(free_edge_.size(), 0.0);
  for (std::size_t k = 1; k < free_edge_.size(); ++k)
    arc_[k] = arc_[k - 1] + (node3(X, free_edge_[k]) - node3(X, free_edge_[k - 1])).norm();

  const Topology topo = build_topology(tris_, n);
  edges_.reserve(topo.edges.size());
  for (const Edge& e : topo.edges) edges_.push_back({e.a, e.b, e.tris[0], e.tris[1]});

  // Border values: the free edge's own arc, elsewhere the projection onto the free edge.
  std::vector<char> fixed(n, 0), in_leaflet(n, 0);
  for (const Tri& t : tris_)
    for (int k = 0; k < 3; ++k) in_leaflet[t[k]] = 1;
  for (const auto& loop : topo.loops)
    for (int v : loop) fixed[v] = 1, across_[v] = nearest_arc(node3(X, v), free_edge_, arc_, X);
  for (std::size_t k = 0; k < free_edge_.size(); ++k) across_[free_edge_[k]] = arc_[k];

  // Cotangent weights on the rest mesh, clamped at 0.
  std::vector<double> weight(edges_.size(), 0.0);
  for (const Tri& t : tris_)
    for (int k = 0; k < 3; ++k) {
      const int i = t[k], j = t[(k + 1) % 3], o = t[(k + 2) % 3];
      const Vec3 e1 = node3(X, i) - node3(X, o), e2 = node3(X, j) - node3(X, o);
      const double twice_area = e1.cross(e2).norm();
      if (!(twice_area > 0)) continue;  // a degenerate triangle has no angle to weigh
      const EdgeTris* e = find_edge(i, j);
      weight[e - edges_.data()] += 0.5 * e1.dot(e2) / twice_area;
    }
  std::vector<double> diagonal(n, 0.0);
  std::vector<std::vector<int>> neighbours(n);  // over positive weights
  for (std::size_t e = 0; e < edges_.size(); ++e) {
    weight[e] = std::max(weight[e], 0.0);
    diagonal[edges_[e].a] += weight[e];
    diagonal[edges_[e].b] += weight[e];
    if (weight[e] > 0) neighbours[edges_[e].a].push_back(edges_[e].b), neighbours[edges_[e].b].push_back(edges_[e].a);
  }
  // Interior nodes that no chain of positive weights ties to the border (possible only where
  // clamped obtuse angles cut a patch off) keep their projection: left unknown, they would
  // make the system singular. Every other unknown then reaches a border value, so the
  // matrix is irreducibly diagonally dominant, hence positive definite.
  std::vector<char> reached(fixed);
  std::vector<int> stack;
  for (int v = 0; v < n; ++v)
    if (fixed[v]) stack.push_back(v);
  while (!stack.empty()) {
    const int v = stack.back();
    stack.pop_back();
    for (int w : neighbours[v])
      if (!reached[w]) reached[w] = 1, stack.push_back(w);
  }
  std::vector<int> unknown(n, -1);
  int nu = 0;
  for (int v = 0; v < n; ++v) {
    if (!in_leaflet[v] || fixed[v]) continue;
    if (reached[v])
      unknown[v] = nu++;
    else
      across_[v] = nearest_arc(node3(X, v), free_edge_, arc_, X);
  }
  if (nu == 0) return;
  std::vector<Eigen::Triplet<double>> entries;
  VecX rhs = VecX::Zero(nu);
  for (int v = 0; v < n; ++v)
    if (unknown[v] >= 0) entries.emplace_back(unknown[v], unknown[v], diagonal[v]);
  for (std::size_t e = 0; e < edges_.size(); ++e) {
    const int a = edges_[e].a, b = edges_[e].b, ua = unknown[a], ub = unknown[b];
    if (weight[e] == 0) continue;
    if (ua >= 0 && ub >= 0) {
      entries.emplace_back(ua, ub, -weight[e]);
      entries.emplace_back(ub, ua, -weight[e]);
    } else if (ua >= 0) {
      rhs[ua] += weight[e] * across_[b];
    } else if (ub >= 0) {
      rhs[ub] += weight[e] * across_[a];
    }
  }
  Eigen::SparseMatrix<double> L(nu, nu);
  L.setFromTriplets(entries.begin(), entries.end());
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(L);
  const VecX s = solver.info() == Eigen::Success ? VecX(solver.solve(rhs)) : VecX();
  const bool solved = s.size() == nu && s.allFinite();
  // Not expected (the matrix is positive definite); should the factorization fail all the
  // same, the projection, which the harmonic values only refine, stands in.
  for (int v = 0; v < n; ++v)
    if (unknown[v] >= 0) across_[v] = solved ? s[unknown[v]] : nearest_arc(node3(X, v), free_edge_, arc_, X);
}

const LeafletColumns::EdgeTris* LeafletColumns::find_edge(int a, int b) const {
  if (a > b) std::swap(a, b);
  const auto it = std::lower_bound(edges_.begin(), edges_.end(), std::make_pair(a, b),
                                   [](const EdgeTris& e, const std::pair<int, int>& key) {
                                     return std::make_pair(e.a, e.b) < key;
                                   });
  return it != edges_.end() && it->a == a && it->b == b ? &*it : nullptr;
}

std::vector<EdgePoint> LeafletColumns::trace(double s) const {
  std::vector<EdgePoint> path;
  if (free_edge_.empty() || !(s > 0) || s > arc_.back()) return path;
  const auto above = [&](int v) { return across_[v] >= s; };
  const auto crossing = [&](int below, int over) {
    return EdgePoint{below, over, (s - across_[below]) / (across_[over] - across_[below])};
  };
  // The free-edge segment where the column begins: arc_[k - 1] < s <= arc_[k].
  std::size_t k = 1;
  while (k + 1 < arc_.size() && arc_[k] < s) ++k;
  int u = free_edge_[k - 1], v = free_edge_[k];  // u below, v above
  path.push_back(crossing(u, v));
  const EdgeTris* edge = find_edge(u, v);
  if (!edge) return path;
  int tri = edge->t0;
  for (std::size_t steps = 0; steps <= tris_.size() && tri >= 0; ++steps) {
    const Tri& t = tris_[tri];
    int w = t[0];
    for (int c = 0; c < 3; ++c)
      if (t[c] != u && t[c] != v) w = t[c];
    // Leave through the other edge the line crosses: (u, w) if w is above, else (w, v).
    if (above(w))
      v = w;
    else
      u = w;
    path.push_back(crossing(u, v));
    edge = find_edge(u, v);
    if (!edge) break;
    tri = edge->t0 == tri ? edge->t1 : edge->t0;
  }
  return path;
}

}  // namespace valve
