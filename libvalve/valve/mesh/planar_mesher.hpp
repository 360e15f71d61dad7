#pragma once
// Unstructured, near-equilateral triangulation of a planar domain (seed 3.2.2.1): random
// interior points, (constrained) Delaunay triangulation with CGAL, then the interior points
// are moved as if every edge were a spring of equal stiffness and rest length until they
// settle, re-triangulating between moves. The springs only push (as in DistMesh, Persson &
// Strang 2004): a common rest length a little above the mean edge length keeps the spring
// network under slight compression, which spreads points evenly up to the fixed boundary.
// Points pushed towards the boundary are projected back inside a band of 0.3 spacings.
#include <cstdint>
#include <functional>
#include <vector>

#include "valve/core/types.hpp"

namespace valve {

struct PlanarDomain {
  double area = 0;       // mm²
  double perimeter = 0;  // mm
  /// Boundary nodes for a target spacing, in order around the boundary (a closed polygon).
  std::function<std::vector<Vec2>(double spacing)> boundary;
  /// Signed distance to the boundary, negative inside (used to keep interior points inside).
  std::function<double(const Vec2&)> signed_distance;
};

struct PlanarMeshOptions {
  int target_triangles = 229;
  std::uint64_t seed = 1;
  int max_iterations = 60;       // triangulate + relax rounds
  double move_tolerance = 2e-3;  // stop when the largest move is below this fraction of the spacing
  /// Deliberate degradation for stability tests: after meshing, interior nodes are moved at
  /// random by up to `jitter` spacings (moves that would flip or flatten a triangle are
  /// refused), producing slivers. 0 = off.
  double jitter = 0;
};

struct PlanarMesh {
  std::vector<Vec2> points;  // boundary nodes first, then interior nodes
  int num_boundary = 0;
  std::vector<Tri> triangles;  // counter-clockwise
  int iterations = 0;          // rounds used
};

PlanarMesh mesh_planar_domain(const PlanarDomain& domain, const PlanarMeshOptions& options);

/// Deterministic uniform numbers in [0,1) from a 64-bit seed (same on every platform).
class SplitMix64 {
 public:
  explicit SplitMix64(std::uint64_t seed) : state_(seed) {}
  double uniform();

 private:
  std::uint64_t state_;
};

/// Moves interior nodes at random by up to `amplitude` (see PlanarMeshOptions::jitter).
void jitter_interior(PlanarMesh& mesh, double amplitude, SplitMix64& rng);

}  // namespace valve
