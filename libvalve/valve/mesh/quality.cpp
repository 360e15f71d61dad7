#include "valve/mesh/quality.hpp"

#include "valve/mesh/topology.hpp"

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

MeshShapeReport describe_mesh_shape(const TriMesh& mesh) {
  MeshShapeReport r;
  r.nodes = mesh.num_nodes();
  r.triangles = mesh.num_triangles();
  r.quality = summarize_quality(triangle_qualities(mesh.points, mesh.triangles));
  const Topology topo = build_topology(mesh.triangles, mesh.num_nodes());
  r.boundary_loops = static_cast<int>(topo.loops.size());
  r.non_manifold_edges = topo.non_manifold_edges;
  std::vector<int> valence(mesh.num_nodes(), 0), boundary_edges(mesh.num_nodes(), 0), fan_triangles(mesh.num_nodes(), 0);
  for (const Edge& e : topo.edges) {
    ++valence[e.a];
    ++valence[e.b];
    if (e.tris[1] < 0) ++boundary_edges[e.a], ++boundary_edges[e.b];
  }
  for (const Tri& t : mesh.triangles)
    for (int k = 0; k < 3; ++k) ++fan_triangles[t[k]];
  // One fan: an interior vertex has as many edges as triangles, a boundary vertex one more
  // edge than triangles and exactly two boundary edges.
  double sum = 0;
  int interior = 0;
  for (int i = 0; i < mesh.num_nodes(); ++i) {
    if (fan_triangles[i] == 0) continue;
    const bool fan = boundary_edges[i] == 0 ? valence[i] == fan_triangles[i]
                                            : boundary_edges[i] == 2 && valence[i] == fan_triangles[i] + 1;
    r.non_manifold_vertices += !fan;
    if (boundary_edges[i] == 0) sum += valence[i], ++interior;
  }
  r.mean_interior_valence = interior ? sum / interior : 0;
  r.quality_min_away_from_boundary = 1;
  for (const Tri& t : mesh.triangles)
    if (!boundary_edges[t[0]] && !boundary_edges[t[1]] && !boundary_edges[t[2]])
      r.quality_min_away_from_boundary = std::min(
          r.quality_min_away_from_boundary, triangle_quality(mesh.points.row(t[0]), mesh.points.row(t[1]), mesh.points.row(t[2])));
  return r;
}

}  // namespace valve
