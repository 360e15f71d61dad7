#pragma once
// Refinement of a triangle mesh for mesh-size studies.
#include "valve/mesh/tri_mesh.hpp"

namespace valve {

/// Midpoint subdivision (each triangle into four), keeping the geometry piecewise flat so
/// that meshes ×1, ×4, ×16 describe the same surface (seed 5.3.3). A new node on an edge
/// between two annulus (free-edge) nodes is annulus (free edge) too and inherits a shared
/// NodeRole; triangles inherit fiber and leaflet.
TriMesh subdivide_midpoint(const TriMesh& mesh);

}  // namespace valve
