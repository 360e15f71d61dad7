#pragma once
// Curve skeleton of a binary 3-D object (the chordae of a segmentation), by sequential
// topology-preserving thinning. Debian 12's ITK 5.2 has no 3-D thinning filter
// (BinaryThinningImageFilter is 2-D; BinaryThinningImageFilter3D is an external module), so
// it is written here.
//
// Topology: 26-connectivity for the object, 6 for the background. A voxel p of X is simple
// (removing it changes no topology) iff (Bertrand & Malandain 1994)
//   - N26*(p) ∩ X is non-empty and 26-connected (one component), and
//   - the 6-components of N18(p) \ X, taken inside N18(p), that contain a face neighbour of p
//     number exactly one.
// Thinning peels border voxels in six directional sub-iterations (±x, ±y, ±z): a voxel whose
// neighbour in that direction is background is removed if it is still simple and is not a
// curve end (it has at least two object neighbours), re-checked at removal so that the
// sequential removal preserves topology. Repeated until a full pass removes nothing, it leaves
// one-voxel-thick curves that keep every end of the object's branches (end points are kept).
#include <cstdint>
#include <vector>

#include "valve/imaging/volume.hpp"

namespace valve {

/// Thins `mask` (1 = object, per voxel of `geometry`, ImageGeometry::linear_index order) to
/// a curve skeleton. Voxels on the image border are treated as having background outside.
std::vector<std::uint8_t> curve_skeleton(const ImageGeometry& geometry, std::vector<std::uint8_t> mask);

/// True if the centre of the 3 × 3 × 3 block `cube` (index x + 3 y + 9 z, 1 = object) is a
/// simple point (exposed for tests).
bool is_simple_point(const std::uint8_t cube[27]);

}  // namespace valve
