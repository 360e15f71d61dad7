#pragma once
// Chordae drawn in 3D Slicer as markup curves (.mrk.json): each curve runs from a papillary
// tip (first control point) to an insertion on the leaflet (last control point); control
// points in between are points along the chord. Points of different curves closer than
// `merge_distance` are one point (a shared tip, or a branch point where chords split).
// Slicer stores RAS or LPS ("coordinateSystem"); positions are converted to LPS.
// A curve whose name contains "strut" is a strut chord; otherwise the chord is primary when
// its insertion ends up on a free-edge node and secondary when not (decided after snapping,
// see classify_by_insertion).
#include <filesystem>
#include <vector>

#include "valve/chordae/chordae_network.hpp"
#include "valve/mesh/tri_mesh.hpp"

namespace valve {

/// Reads one or more .mrk.json files into a network (insertions not yet snapped).
/// InputError names the file and key ("markups[2].controlPoints") for malformed input.
ChordaeNetwork read_slicer_curves(const std::vector<std::filesystem::path>& files, double merge_distance);

/// Types every non-strut segment by where its chord lands: the chord (the segments from a
/// tip or branch to an insertion, and the segments feeding them) is primary if its insertion
/// is a free-edge node of `mesh` (BoundaryType free_edge), else secondary.
void classify_by_insertion(ChordaeNetwork& network, const TriMesh& mesh);

}  // namespace valve
