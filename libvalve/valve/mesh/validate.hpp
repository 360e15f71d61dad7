#pragma once
// Checks a mesh before simulation: finite coordinates, indices in range, no zero-area or
// duplicate triangles, manifold edges. Throws InputError naming `source` and the first
// offending item.
#include <string>

#include "valve/mesh/tri_mesh.hpp"

namespace valve {

void validate_mesh(const TriMesh& mesh, const std::string& source);

}  // namespace valve
