#pragma once
// Leaflet dimensions used by the seed (Fig. 3.1, Table 3.2): the free-edge length and the
// radial midline length, measured on the deformed mesh; and how far a closed cusp's belly
// billows below its attachment (Fig. 4.7).
#include <vector>

#include "valve/mesh/tri_mesh.hpp"

namespace valve {

/// Ordered nodes of leaflet `leaflet`'s free edge, from one attached corner to the other
/// (corners included). Empty if the leaflet has no free edge.
std::vector<int> free_edge_polyline(const TriMesh& mesh, int leaflet = 0);

/// Free-edge node at half the rest arc length of the free edge (the seed's monitor node);
/// -1 if there is no free edge.
int free_edge_middle_node(const TriMesh& mesh, int leaflet = 0);

/// Length of a node polyline at positions x (3N).
double polyline_length(const std::vector<int>& nodes, const VecX& x);

/// A point of the rest surface as triangle + barycentric coordinates.
struct SurfacePoint {
  int triangle;
  Vec3 barycentric;
};
/// Closest point on the rest mesh (brute force over triangles).
SurfacePoint closest_surface_point(const TriMesh& mesh, const Vec3& p);
Vec3 evaluate(const TriMesh& mesh, const SurfacePoint& sp, const VecX& x);

/// The radial midline of a leaflet: in the rest state, the straight segment from the
/// free-edge middle node to the attached node farthest from it, sampled at `samples`
/// points projected onto the rest surface; its length is measured at positions x.
struct Midline {
  std::vector<SurfacePoint> points;
  double length(const TriMesh& mesh, const VecX& x) const;
};
Midline leaflet_midline(const TriMesh& mesh, int leaflet = 0, int samples = 200);

/// How far the belly of leaflet `leaflet` hangs below its attachment along a valve axis (mm,
/// ≥ 0): the largest distance along `axis` by which a node of the leaflet at positions x lies
/// beyond the leaflet's lowest attached node (BoundaryType attached, as for the midline;
/// lowest at rest) in the same direction. "Up" points from the mean rest position of the
/// attached nodes towards the free-edge middle, so the axis may point either way. The seed
/// judged fiber fields by it: fibers parallel to the free edge let the belly billow toward
/// the ventricle, fibers at 25° do not (Fig. 4.7).
/// 0 when the leaflet has no attached node, no free edge or the axis has no direction;
/// throws InputError when x does not have 3N entries.
double belly_drop(const TriMesh& mesh, const VecX& x, int leaflet, const Vec3& axis);

}  // namespace valve
