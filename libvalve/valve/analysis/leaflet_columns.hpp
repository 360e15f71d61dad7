#pragma once
// Columns of a leaflet: material lines that run from each point of its free edge down into
// the leaflet, "straight down" in the rest shape. Coaptation heights (coaptation.hpp) are
// measured along them.
//
// Across coordinate. s(v) is the rest arc length along the free edge "above" node v:
// - on the free-edge polyline (free_edge_polyline, corners included) s is the arc length
//   from its first node;
// - on the rest of the leaflet's border, s is the arc length of the nearest point of the
//   free-edge polyline (the rest shape; an attachment point below the free edge gets the
//   free-edge point above it, the commissure sides get the ends, 0 and the length);
// - inside, s is discrete-harmonic: Σ_w c_vw (s_w − s_v) = 0 with cotangent weights
//   c_vw = (cot α + cot β) / 2 on the rest mesh, clamped at 0 so that s obeys the discrete
//   maximum principle (no iso-line closes on itself or turns back to the free edge).
// Cotangent weights reproduce linear functions, so on a flat leaflet whose free edge is a
// straight line and whose border values are the projections, s is exactly the coordinate
// along the free edge, and the columns are the perpendiculars to it. On a leaflet wrapped
// onto a cylinder (valve-generate aortic_valve: a straight free edge on a flat cusp) they
// are the cusp's vertical lines.
//
// Column at s (0 < s ≤ free-edge length): the iso-line {s(p) = s} of the piecewise-linear s,
// traced from the free-edge segment where it begins, triangle by triangle, to the border.
// Inside a triangle s is linear, so the line crosses exactly two of its edges; a node with
// s(v) = s counts as above the line (s(v) ≥ s), the same test everywhere, so the trace never
// stalls on a vertex. Each crossing is a point on a rest edge, (1 − t) X_a + t X_b; any
// per-node field (positions of a deformed shape, an indicator) is interpolated along the
// column with the same (a, b, t), exactly, because it is linear inside each triangle.
//
// Why not columns of nodes (each node assigned to its nearest free-edge node): on an
// unstructured mesh some free-edge nodes are nearest to no other node, so their column holds
// the free-edge node alone and any height measured on it is 0 whatever lies below (3 of the
// 33 free-edge nodes of the three-leaflet aortic valve, among them leaflet 0's middle node).
#include <vector>

#include "valve/mesh/tri_mesh.hpp"

namespace valve {

/// A point on the rest edge (a, b): (1 − t) X_a + t X_b.
struct EdgePoint {
  int a = 0, b = 0;
  double t = 0;
};

class LeafletColumns {
 public:
  /// Builds the across coordinate of `leaflet` (every triangle when the mesh has no
  /// labels) on the rest shape mesh.points. A leaflet without a free edge has no columns.
  LeafletColumns(const TriMesh& mesh, int leaflet);

  /// free_edge_polyline(mesh, leaflet): the free-edge nodes with the two corners.
  const std::vector<int>& free_edge() const { return free_edge_; }
  /// Rest arc length of free_edge() at each of its nodes (0 at the first).
  const std::vector<double>& free_edge_arc() const { return arc_; }
  double free_edge_length() const { return arc_.empty() ? 0.0 : arc_.back(); }
  /// s per node of the mesh; NaN for nodes outside the leaflet (or without a free edge).
  const std::vector<double>& across() const { return across_; }

  /// The column at s, from its point on the free edge to the border; empty when s is not in
  /// (0, free_edge_length()].
  std::vector<EdgePoint> trace(double s) const;

 private:
  std::vector<Tri> tris_;
  std::vector<int> free_edge_;
  std::vector<double> arc_;
  std::vector<double> across_;
  struct EdgeTris {
    int a, b, t0, t1;  // a < b; t1 = -1 on the border
  };
  std::vector<EdgeTris> edges_;  // sorted by (a, b)
  const EdgeTris* find_edge(int a, int b) const;
};

}  // namespace valve
