#pragma once
// Projected orifice of a closed valve: the part of its cross-section that no leaflet covers
// when seen along the valve axis. Where it is not zero, blood has a straight way through.
//
// Why: the coaptation heights (coaptation.hpp) say whether each pair of leaflets meets along
// its free edges; a closed three-leaflet valve can still keep a hole at the centre, where the
// three free edges should meet, and the free edges' distances from the axis say how far
// each one stops, not whether the others cover the hole. The seed (4.4) calls that hole the
// central gap that makes a central regurgitant jet.
//
// Cross-section: the polygon of the deformed attached nodes (BoundaryType::attached),
// projected onto the plane normal to the axis and sorted by their angle about it. Its edges
// are the chords the wall triangles project to, so the strip between chord and root circle
// does not count as an opening.
// Leaflets: each triangle projected, dilated by half the coaptation threshold (threshold/2
// = 0.25 mm, half the leaflet's thickness): the leaflets are 0.5 mm sheets drawn as their
// mid-surfaces, and the contact holds touching mid-surfaces about 0.25 mm apart, so two
// leaflets pressed together in a vertical fin project to two lines 0.25 mm apart that only
// their thickness closes (without it each closed valve of the ten-mesh study would show
// 0.25 mm × the fins' length as an opening).
// Area: pixels of `pixel_mm` whose centres lie in the cross-section and farther than the
// dilation from every projected triangle, times the pixel's area; the error is about the
// opening's perimeter times the pixel (0.02 mm: under 0.1 mm² for a 1 mm² hole).
#include "valve/analysis/coaptation.hpp"
#include "valve/mesh/tri_mesh.hpp"

namespace valve {

struct OrificeResult {
  double area_mm2 = -1;            // -1 when the mesh has fewer than 3 attached nodes or the
                                   // axis does not pass inside their ring
  double cross_section_mm2 = -1;   // area of the cross-section polygon (-1 likewise)
};

/// Projected orifice of the deformed valve `x` (3N, node-major, mm) along `axis`, the
/// leaflets dilated by `dilation_mm`. Throws InputError for a non-positive pixel, a
/// negative dilation, a degenerate axis, or positions / BoundaryType of the wrong size.
OrificeResult projected_orifice(const TriMesh& mesh, const VecX& x, const ValveAxis& axis, double dilation_mm,
                                double pixel_mm = 0.02);

}  // namespace valve
