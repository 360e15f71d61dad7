#pragma once
// Chordae found in a segmentation (seed 5.2.2), without a hand-made chordae file: the
// chordae label is thinned to a curve skeleton (imaging/skeleton.hpp) and
// read as a graph whose vertices are the skeleton's curve ends and junctions (26-adjacent
// junction voxels are one branch point) and whose edges are the voxel paths between them.
//   - Spurs: a branch shorter than min_spur_mm from a junction to a free end is a bump of
//     the chord's surface left by thinning, and is removed (the junction, if it is left with
//     two branches, joins them).
//   - Ends: an end within insertion_distance_mm of other tissue (papillary muscle) is a
//     papillary tip, else one within that distance of leaflet tissue an insertion (the
//     segmentation's opening cuts each chord a little short of the tissue it joins); any
//     other end is a papillary tip too (where the scan holds no muscle, chords end in free
//     space on the ventricular side). Tips on other tissue are counted separately.
//   - Convergence tips: a junction at least convergence_clearance_mm from leaflet tissue
//     and farther from it than every vertex it is joined to, none of them a tip end, is a
//     papillary tip as well (the chords of one muscle meet there, and thinning leaves a
//     junction rather than an end); 0 turns the rule off.
//   - Components of the graph without a tip or without an insertion cannot tether a leaflet
//     and are dropped (counted).
// Every segment is a straight chord between two vertices, directed from the tip side (fewer
// graph edges from a tip) toward the insertions, all typed secondary: the type follows from
// where the insertions land on the mesh (classify_by_insertion, after snapping).
#include "valve/chordae/chordae_network.hpp"
#include "valve/imaging/volume.hpp"

namespace valve {

struct ChordaeExtractionOptions {
  double insertion_distance_mm = 1.0;
  double min_spur_mm = 0.75;
  double convergence_clearance_mm = 5.0;
};

struct ChordaeExtractionSummary {
  long chordae_voxels = 0, skeleton_voxels = 0;
  int junctions = 0, spurs_removed = 0, components = 0, components_dropped = 0;
  int insertions = 0, papillary_tips = 0, tips_on_other_tissue = 0, convergence_tips = 0;
  double total_length_mm = 0;  // sum of straight segment lengths kept
};

/// Throws InputError (naming `file`) when the label map has no chordae voxels or no chord
/// joins leaflet tissue to a tip.
ChordaeNetwork chordae_from_labels(const LabelMap& labels, const ChordaeExtractionOptions& options, const std::string& file,
                                   ChordaeExtractionSummary* summary = nullptr);

}  // namespace valve
