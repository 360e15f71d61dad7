#pragma once
// The triangle membrane mesh: rest positions, triangles, per-triangle fiber direction,
// per-node role for the mechanics and per-node boundary type for analysis.
#include <string>
#include <vector>

#include "valve/core/types.hpp"

namespace valve {

/// What the mechanics does with a node (the `NodeRole` point array).
enum class NodeRole : int { free = 0, fixed = 1, prescribed = 2 };

/// Where a node sits on the leaflet (the `BoundaryType` point array).
enum class BoundaryType : int { interior = 0, attached = 1, free_edge = 2 };

struct TriMesh {
  MatX3 points;                      // rest positions, mm
  std::vector<Tri> triangles;        // node indices, counter-clockwise seen from +normal
  MatX3 fiber;                       // per triangle: unit fiber direction in the rest state
  std::vector<NodeRole> roles;       // per node
  std::vector<BoundaryType> boundary;  // per node
  std::vector<int> leaflet;          // per triangle: leaflet index (0 for single-leaflet meshes)
  MatX3 initial;                     // starting positions if they differ from `points` (else empty)

  int num_nodes() const { return static_cast<int>(points.rows()); }
  /// Where a simulation starts: `initial` if given, else the rest positions.
  const MatX3& start_positions() const { return initial.rows() == num_nodes() ? initial : points; }
  int num_triangles() const { return static_cast<int>(triangles.size()); }
  /// Fills missing per-node / per-triangle arrays with defaults (free, interior, leaflet 0,
  /// fiber along the first edge projected in-plane).
  void fill_defaults();
};

/// Rest-state unit normal of triangle t (by winding), given node positions.
Vec3 triangle_normal(const MatX3& x, const Tri& t);
double triangle_area(const MatX3& x, const Tri& t);

}  // namespace valve
