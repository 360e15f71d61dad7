#pragma once
// Segmentation of a micro-CT volume of a valve into a label map (seed 5.2.2: "images were
// cropped, segmented and triangulated"): crop to a physical box, denoise, threshold (Otsu or
// explicit), close small holes, then split the tissue:
//   - chordae_method "opening": a morphological opening with a ball wider than a chord but
//     narrower than the leaflet removes the chordae; what it removed, in pieces large enough,
//     is label_chordae. Works where leaflets are thicker than chords (the phantoms);
//   - chordae_method "hessian": tissue voxels whose smoothed image is tube-shaped are removed
//     instead (Hessian eigenvalues |l1| <= |l2| <= |l3| at scale tube_scale: a bright tube has
//     l2 and l3 both negative and alike, a bright sheet only l3; tube seeds where l2/l3 >=
//     tube_ratio within tube_ridge_offset of the ridge (a sheet's rim rises into the sheet),
//     grown into the tube's surface voxels that are not clearly inside a sheet: l2/l3 >=
//     sheet_ratio, or some eigenvalue >= 0);
//     the leaflet label is then closed within the tissue by notch_closing_radius, because
//     the tubes bite notches into the leaflet where chords insert.
//     Shape, not thickness, tells chords from leaflets, so it also works where both are equally
//     thick (the Texas TriValve deck: 0.65 mm each);
//   - of what survives, the connected component(s) holding the seed points (or the largest)
//     are label_leaflet, the rest (papillary muscles, wall) label_other_tissue.
// Runs on ITK filters; ITK types stay in the .cpp.
#include <string>
#include <vector>

#include "valve/imaging/volume.hpp"

namespace valve {

struct SegmentationOptions {
  bool crop = false;
  Vec3 crop_lo = Vec3::Zero(), crop_hi = Vec3::Zero();  // physical box, mm
  std::string denoise = "gaussian";     // none | gaussian | median
  double gaussian_sigma = 0.15;         // mm
  int median_radius = 1;                // voxels
  int diffusion_iterations = 0;         // curvature anisotropic diffusion after denoising (0: off)
  double diffusion_conductance = 1.0;
  std::string threshold_method = "otsu";  // otsu | explicit
  double threshold = 0;                 // grey value, for explicit
  std::vector<Vec3> seeds;              // physical points inside the leaflets; empty: largest component
  double closing_radius = 0.2;          // mm (0: none)
  std::string chordae_method = "opening";  // opening | hessian
  double chordae_opening_radius = 0.3;  // mm; must exceed the chord radius (0: no chordae split)
  double tube_scale = 0.25;             // mm, Gaussian scale of the Hessian (about the chord radius)
  double tube_ratio = 0.5;              // l2/l3 at or above which a voxel lies on a tube
  double tube_ridge_offset = 0.35;      // mm, seeds lie this near the axis of their tube
  double sheet_ratio = 0.1;             // tubes grow into tissue with l2/l3 at or above this
  int tube_growth_voxels = 2;           // growth passes (26-neighbourhood)
  double notch_closing_radius = 0.75;   // mm, closing of the leaflet label (hessian; 0: none)
  double min_component_mm3 = 0.5;       // smaller pieces of tissue are noise
  double max_foreground_fraction = 0.5; // a threshold keeping more than this is refused
  double max_spacing_ratio = 4.0;       // largest / smallest spacing accepted

  /// Throws InputError naming the key for values out of range.
  void validate(const std::string& where) const;
};

struct SegmentationSummary {
  double threshold = 0;
  std::size_t voxels_tissue = 0, voxels_leaflet = 0, voxels_chordae = 0, voxels_other = 0;
  int components = 0;         // after the opening, above the minimum size
  int leaflet_components = 0;
  int chordae_pieces = 0;     // before the Hessian method's notch closing
  bool chordae_separated = false;
  ImageGeometry cropped;
};

/// Throws InputError for an empty segmentation, a threshold that keeps (nearly) everything,
/// strongly anisotropic spacing, an empty crop and seeds outside the tissue.
LabelMap segment_valve(const Volume& volume, const SegmentationOptions& options, SegmentationSummary* summary);

}  // namespace valve
