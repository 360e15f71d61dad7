#pragma once
// Chordae drawn in 3D Slicer as markup curves (.mrk.json): each curve runs from a papillary
// tip (first control point) to an insertion on the leaflet (last control point); control
// points in between are points along the chord. Points of different curves closer than
// `merge_distance` are one point (a shared tip, or a branch point where chords split).
// Slicer stores RAS or LPS ("coordinateSystem"); positions are converted to LPS.
// A curve whose name contains "strut" is a strut chord; otherwise the chord is primary when
// its insertion ends up on a free-edge node and secondary when not (decided after snapping,
// see classify_by_insertion).
// Landmarks go the other way: write_slicer_curves saves curves (annulus ring, free edges,
// coaptation line) that Slicer's Markups module opens.
#include <filesystem>
#include <string>
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

/// A curve for Slicer's Markups module: open ("Curve") or closed ("ClosedCurve").
struct MarkupCurve {
  std::string name;
  MatX3 points;  // control points in order, LPS mm
  bool closed = false;
};

/// Writes the curves as one markups file (.mrk.json, markups schema v1.0.3; LPS, mm),
/// atomically. Curves with fewer than two points are left out: Slicer draws no curve for them.
void write_slicer_curves(const std::filesystem::path& path, const std::vector<MarkupCurve>& curves);

/// The landmarks of a valve mesh at positions x (3N) as curves, from its boundary loops: the
/// annulus (runs of fixed or attached nodes; closed where a whole loop is attached), the free
/// edges (runs of free-edge nodes with the attached corners at their ends) and, given
/// per-node coaptation flags, the coaptation line (the stretches of free edge whose nodes
/// coapt). Several runs are numbered: "annulus", "annulus 2", ...
std::vector<MarkupCurve> valve_landmark_curves(const TriMesh& mesh, const VecX& x, const std::vector<int>* coapting = nullptr);

}  // namespace valve
