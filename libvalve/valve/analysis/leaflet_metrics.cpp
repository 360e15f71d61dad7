#include "valve/analysis/leaflet_metrics.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <string>

#include "valve/core/error.hpp"
#include "valve/mesh/closest_point.hpp"
#include "valve/mesh/topology.hpp"

namespace valve {
namespace {

/// Per node, 1 if a triangle of `leaflet` uses it (every triangle when the mesh has no labels).
std::vector<char> leaflet_node_mask(const TriMesh& m, int leaflet) {
  std::vector<char> in_leaflet(m.num_nodes(), 0);
  for (int t = 0; t < m.num_triangles(); ++t)
    if (m.leaflet.empty() || m.leaflet[t] == leaflet)
      for (int k = 0; k < 3; ++k) in_leaflet[m.triangles[t][k]] = 1;
  return in_leaflet;
}

}  // namespace

std::vector<int> free_edge_polyline(const TriMesh& m, int leaflet) {
  std::vector<Tri> tris;
  for (int t = 0; t < m.num_triangles(); ++t)
    if (m.leaflet.empty() || m.leaflet[t] == leaflet) tris.push_back(m.triangles[t]);
  const Topology topo = build_topology(tris, m.num_nodes());
  for (const auto& loop : topo.loops) {
    const int n = static_cast<int>(loop.size());
    auto is_free = [&](int k) { return m.boundary[loop[((k % n) + n) % n]] == BoundaryType::free_edge; };
    int start = -1;
    for (int k = 0; k < n; ++k)
      if (is_free(k) && !is_free(k - 1)) {
        start = k;
        break;
      }
    if (start < 0) continue;
    std::vector<int> out{loop[((start - 1) % n + n) % n]};
    int k = start;
    while (is_free(k) && static_cast<int>(out.size()) <= n) out.push_back(loop[(k++) % n]);
    out.push_back(loop[k % n]);
    return out;
  }
  return {};
}

double polyline_length(const std::vector<int>& nodes, const VecX& x) {
  double l = 0;
  for (size_t k = 1; k < nodes.size(); ++k) l += (node3(x, nodes[k]) - node3(x, nodes[k - 1])).norm();
  return l;
}

int free_edge_middle_node(const TriMesh& m, int leaflet) {
  const auto line = free_edge_polyline(m, leaflet);
  if (line.size() < 3) return -1;
  const VecX X = flatten(m.points);
  const double half = 0.5 * polyline_length(line, X);
  double acc = 0, best = 1e300;
  int node = -1;
  for (size_t k = 1; k + 1 < line.size(); ++k) {
    acc += (node3(X, line[k]) - node3(X, line[k - 1])).norm();
    if (std::abs(acc - half) < best) best = std::abs(acc - half), node = line[k];
  }
  return node;
}

SurfacePoint closest_surface_point(const TriMesh& m, const Vec3& p) {
  SurfacePoint best{0, Vec3(1, 0, 0)};
  double bd = 1e300;
  for (int t = 0; t < m.num_triangles(); ++t) {
    const Tri& tri = m.triangles[t];
    const Vec3 a = m.points.row(tri[0]), b = m.points.row(tri[1]), c = m.points.row(tri[2]);
    const Vec3 w = closest_point_weights(p, a, b, c);
    const double d = (w[0] * a + w[1] * b + w[2] * c - p).squaredNorm();
    if (d < bd) bd = d, best = {t, w};
  }
  return best;
}

Vec3 evaluate(const TriMesh& m, const SurfacePoint& sp, const VecX& x) {
  const Tri& t = m.triangles[sp.triangle];
  return sp.barycentric[0] * node3(x, t[0]) + sp.barycentric[1] * node3(x, t[1]) + sp.barycentric[2] * node3(x, t[2]);
}

double Midline::length(const TriMesh& m, const VecX& x) const {
  double l = 0;
  for (size_t k = 1; k < points.size(); ++k) l += (evaluate(m, points[k], x) - evaluate(m, points[k - 1], x)).norm();
  return l;
}

Midline leaflet_midline(const TriMesh& m, int leaflet, int samples) {
  Midline ml;
  const int top = free_edge_middle_node(m, leaflet);
  if (top < 0) return ml;
  const std::vector<char> in_leaflet = leaflet_node_mask(m, leaflet);
  const Vec3 P = m.points.row(top);
  int bottom = -1;
  double far = -1;
  for (int i = 0; i < m.num_nodes(); ++i)
    if (in_leaflet[i] && m.boundary[i] == BoundaryType::attached) {
      const double d = (m.points.row(i).transpose() - P).norm();
      if (d > far) far = d, bottom = i;
    }
  if (bottom < 0) return ml;
  const Vec3 Q = m.points.row(bottom);
  for (int k = 0; k <= samples; ++k) ml.points.push_back(closest_surface_point(m, P + (Q - P) * (double(k) / samples)));
  return ml;
}

double belly_drop(const TriMesh& m, const VecX& x, int leaflet, const Vec3& axis) {
  if (x.size() != 3 * m.num_nodes())
    throw InputError("belly_drop: expected " + std::to_string(3 * m.num_nodes()) + " coordinates, found " + std::to_string(x.size()));
  const double length = axis.stableNorm();
  const int top = free_edge_middle_node(m, leaflet);
  if (!(length > 0) || !std::isfinite(length) || top < 0) return 0;
  const std::vector<char> in_leaflet = leaflet_node_mask(m, leaflet);
  // "Up" from the attachment (its mean rest position) towards the free-edge middle.
  const VecX X = flatten(m.points);
  Vec3 attachment_mean = Vec3::Zero();
  int attached = 0;
  for (int i = 0; i < m.num_nodes(); ++i)
    if (in_leaflet[i] && m.boundary[i] == BoundaryType::attached) attachment_mean += node3(X, i), ++attached;
  if (attached == 0) return 0;
  attachment_mean /= attached;
  const Vec3 up = (node3(X, top) - attachment_mean).dot(axis) < 0 ? Vec3(-axis / length) : Vec3(axis / length);
  int nadir = -1;  // the attachment's lowest rest node
  for (int i = 0; i < m.num_nodes(); ++i)
    if (in_leaflet[i] && m.boundary[i] == BoundaryType::attached && (nadir < 0 || node3(X, i).dot(up) < node3(X, nadir).dot(up)))
      nadir = i;
  double drop = 0;
  for (int i = 0; i < m.num_nodes(); ++i)
    if (in_leaflet[i]) drop = std::max(drop, (node3(x, nadir) - node3(x, i)).dot(up));
  return drop;
}

}  // namespace valve
