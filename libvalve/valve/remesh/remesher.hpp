#pragma once
// Remeshing a leaflet membrane to a target triangle count with near-equilateral triangles
// and about six edges per interior node (seed 5.2.2: 600–700 triangles). Two methods, both
// CGAL:
//   isotropic  Polygon Mesh Processing's isotropic remeshing (Botsch & Kobbelt 2004: split,
//              collapse, flip toward valence 6, tangential relaxation, projection back onto
//              the input) at the edge length L = sqrt(4 A / (√3 N)) of N equilateral
//              triangles covering the area A; L is corrected by sqrt(N_found / N) until the
//              count is within the tolerance.
//   collapse   the seed's route: shortest-edge collapses (Surface_mesh_simplification) down
//              to the target, then tangential relaxation as equal-rest-length springs
//              would do.
// After remeshing, border vertices are put back on the input's border as far as their
// triangles' quality allows (CGAL leaves them on the coarse border it makes, up to 1 mm off).
// The mid-surface offset moves every node against its normal after remeshing, where the
// normals are smooth at the scale of the edges (on the voxel-scale surface they turn sharply at
// the border and the offset would fold it); the border slivers it makes where the surface
// bends are repaired again on the offset surface.
// Both first repair the input (orient, split non-manifold vertices) and fill holes whose
// border is shorter than a fraction of the longest border (pinholes left by segmentation).
#include <string>

#include "valve/mesh/tri_mesh.hpp"

namespace valve {

struct RemeshOptions {
  int target_triangles = 650;
  double tolerance = 0.03;         // accepted relative deviation from the target count
  std::string method = "isotropic";  // isotropic | collapse
  int iterations = 8;              // isotropic remeshing passes per attempt
  int relaxation_steps = 3;        // tangential relaxation steps per pass (isotropic) or total ×10 (collapse)
  int max_attempts = 8;
  double max_hole_fraction = 0.25;  // holes with a border shorter than this × the longest border are filled
  int border_smoothing = 10;        // smoothing passes along the input's borders (voxel zigzag)
  double min_border_quality = 0.5;  // border slivers below this are cut off, merged or flipped
  double mid_surface_offset = 0;    // mm (half the thickness): atrial surface -> mid-surface, after remeshing
  double max_neck = 0.5;            // flaps joined to the membrane by a neck shorter than this × L are cut off

  void validate(const std::string& where) const;
};

struct RemeshSummary {
  double target_edge_length = 0;  // mm (isotropic)
  int attempts = 0;
  int holes_filled = 0;
  int border_repairs = 0;
  int border_snapped = 0;  // border vertices moved back onto the input's border
  int flaps_cut = 0;  // triangles of narrow-necked flaps removed
  bool count_within_tolerance = true;  // false: the closest count found is returned
  int input_triangles = 0;
};

/// Triangles keep no input arrays: roles, boundary types and fibers are reset to defaults.
TriMesh remesh_membrane(const TriMesh& membrane, const RemeshOptions& options, RemeshSummary* summary);

}  // namespace valve
