#pragma once
// Label map -> closed surface (seed 5.2.2: "segmented and triangulated"): VTK's discrete
// flying edges on the chosen labels, then windowed-sinc smoothing, which removes the voxel
// staircase without shrinking the surface (Taubin's low-pass filter, unlike Laplacian
// smoothing). The surface is closed (the volume is padded by one background voxel), its
// normals point out of the tissue, and its points are in the image's physical (LPS) frame.
#include <vector>

#include "valve/imaging/volume.hpp"
#include "valve/mesh/tri_mesh.hpp"

namespace valve {

struct TriangulationOptions {
  std::vector<int> labels{label_leaflet};
  int smoothing_iterations = 20;  // windowed sinc; 0: none
  double pass_band = 0.1;         // 0 < pass band < 2; smaller smooths more
  bool largest_only = false;      // keep only the largest connected surface
};

struct TriangulationSummary {
  int regions = 0;           // connected surfaces before `largest_only`
  double area_mm2 = 0;
  double enclosed_volume_mm3 = 0;  // from the divergence theorem; the tissue volume for closed surfaces
};

/// Throws InputError when no voxel carries one of the labels.
TriMesh triangulate_labels(const LabelMap& labels, const TriangulationOptions& options, TriangulationSummary* summary);

}  // namespace valve
