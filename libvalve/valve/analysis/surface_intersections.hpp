#pragma once
// Does a deformed surface pass through itself? An independent check of contact handling
// (no interpenetration): the contact terms see only pairs closer than their
// separation and measure unsigned distances, so a pair that crossed between two steps would
// look to them like a pair in contact. Here every two triangles that share no node are
// tested for intersection with CGAL's exact predicates (Epick: the answer is exact for the
// given coordinates), after CGAL's box_intersection_d has paired the overlapping bounding
// boxes.
//
// Pairs that share a node are not tested: they meet at that node or edge by construction,
// and telling a fold across a shared edge from a valid crease needs the surface's own
// geometry, not an intersection test. A crossing anywhere else shows up as at least one
// intersecting pair; touching (distance exactly 0) counts as intersecting.
//
// Pairs one edge apart (a node of one triangle joined by a mesh edge to a node of the
// other) are counted apart as well: folds tighter than two triangles, largely out of the
// contact terms' reach (contact_base.hpp: a node never touches a triangle that shares a
// vertex with its 1-ring, so the pairs through the joining node are excluded, though other
// pairs of the same two triangles may still act). A heuristic split: pairs further apart
// are crossings contact should have stopped.
//
// A degenerate triangle (collinear nodes) has no plane; it is tested as its longest edge,
// a segment, and one collapsed to a point is skipped (counted in degenerate_skipped).
#include <utility>
#include <vector>

#include "valve/core/types.hpp"

namespace valve {

struct SurfaceIntersections {
  long pairs = 0;                                // intersecting pairs of triangles sharing no node
  long between_leaflets = 0;                     // of those, pairs of two different leaflets
  long one_edge_apart = 0;                       // of those, pairs one mesh edge apart (tight folds)
  long both_anchored = 0;                        // of those, pairs whose two triangles each have
                                                 // an anchored node (leaflets sewn side by side)
  long degenerate_skipped = 0;                   // candidate pairs with a triangle collapsed to a point
  std::vector<std::pair<int, int>> first_pairs;  // up to 10 of them (triangle indices, ascending)
};

/// Intersections of the surface `triangles` at positions `x` (3N, node-major, mm);
/// `leaflet` (one per triangle, or empty: one leaflet) splits them into self-intersections
/// and crossings between leaflets; `anchored` (one per node, or empty: none) marks the nodes
/// held in place (a valve's attachment), where two leaflets sewn along the same stretch of
/// wall without shared nodes overlap by construction. Throws InputError when x does not have
/// 3N finite entries, a triangle names a missing node or a per-item list has the wrong size.
SurfaceIntersections find_surface_intersections(const std::vector<Tri>& triangles, const VecX& x,
                                                const std::vector<int>& leaflet = {},
                                                const std::vector<char>& anchored = {});

}  // namespace valve
