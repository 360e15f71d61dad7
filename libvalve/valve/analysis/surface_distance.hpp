#pragma once
// Distances from points to a triangulated surface (the nearest point anywhere on it, not
// only its nodes), through CGAL's AABB tree. Used to measure a remeshed membrane against
// its ground truth and a simulated valve against a closed-valve scan.
#include <vector>

#include "valve/mesh/tri_mesh.hpp"

namespace valve {

/// Unsigned distance from each row of `points` to the surface of `reference`, mm.
std::vector<double> distances_to_surface(const MatX3& points, const TriMesh& reference);

}  // namespace valve
