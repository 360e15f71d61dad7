#include "valve/imaging/segmentation_report.hpp"

namespace valve {

int segmentation_working_copies(const SegmentationOptions& options) { return options.chordae_method == "hessian" ? 18 : 6; }

nlohmann::json segmentation_metrics(const SegmentationSummary& s, const SegmentationOptions& o, const std::string& name) {
  const double voxel = s.cropped.spacing.prod();
  return {{"labels", name + ".nrrd"},
          {"slicer_segmentation", name + ".seg.nrrd"},
          {"threshold", s.threshold},
          {"threshold_method", o.threshold_method},
          {"size", {s.cropped.size[0], s.cropped.size[1], s.cropped.size[2]}},
          {"spacing_mm", {s.cropped.spacing.x(), s.cropped.spacing.y(), s.cropped.spacing.z()}},
          {"origin_mm", {s.cropped.origin.x(), s.cropped.origin.y(), s.cropped.origin.z()}},
          {"voxels", {{"tissue", s.voxels_tissue}, {"leaflet", s.voxels_leaflet}, {"chordae", s.voxels_chordae}, {"other", s.voxels_other}}},
          {"volume_mm3", {{"leaflet", s.voxels_leaflet * voxel}, {"chordae", s.voxels_chordae * voxel}, {"other", s.voxels_other * voxel}}},
          {"components", s.components},
          {"leaflet_components", s.leaflet_components},
          {"chordae_separated", s.chordae_separated},
          {"chordae_method", o.chordae_method},
          {"chordae_pieces", s.chordae_pieces}};
}

}  // namespace valve
