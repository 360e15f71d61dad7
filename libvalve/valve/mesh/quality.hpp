#pragma once
// Triangle quality q = 4√3 a / (s1² + s2² + s3²) (seed 3.2.2.1): 1 for an equilateral
// triangle, 0 for a degenerate one.
#include <vector>

#include "valve/mesh/tri_mesh.hpp"

namespace valve {

double triangle_quality(const Vec3& a, const Vec3& b, const Vec3& c);
std::vector<double> triangle_qualities(const MatX3& x, const std::vector<Tri>& triangles);

struct QualitySummary {
  double mean = 0, min = 0, max = 0;
  int below_0_6 = 0;  // count of triangles under the usual FE accuracy threshold
};
QualitySummary summarize_quality(const std::vector<double>& q);

/// What a remeshed membrane is judged by (seed 5.2.2: near-equilateral, six edges per node).
struct MeshShapeReport {
  int nodes = 0, triangles = 0;
  QualitySummary quality;
  double quality_min_away_from_boundary = 0;  // over triangles without a boundary node
  double mean_interior_valence = 0;  // edges per interior node (6 for a regular mesh)
  int boundary_loops = 0;
  int non_manifold_edges = 0;     // shared by more than two triangles
  int non_manifold_vertices = 0;  // whose triangles do not form one fan
  bool manifold() const { return non_manifold_edges == 0 && non_manifold_vertices == 0; }
};
MeshShapeReport describe_mesh_shape(const TriMesh& mesh);

}  // namespace valve
