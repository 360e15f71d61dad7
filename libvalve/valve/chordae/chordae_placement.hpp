#pragma once
// A chordae network put on the leaflet mesh it will hold, as valve-chordae writes it: the
// insertions snapped to mesh nodes, the chords typed by where they land, the network checked
// as a chordae.json would be, per-chord scales applied and the rest lengths fixed from the
// open geometry, so that later edits of positions (closed-state papillary tips) leave them.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "valve/chordae/chordae_extraction.hpp"
#include "valve/chordae/chordae_network.hpp"
#include "valve/mesh/tri_mesh.hpp"

namespace valve {

struct ChordaePlacementOptions {
  double snap_tolerance_mm = 1.5;  ///< farthest an insertion may lie from its mesh node
  /// Types the chords by their insertions (primary on the free edge, else secondary; struts
  /// stay). Off for a chordae.json, whose types are kept.
  bool type_by_insertion = true;
  /// "SEGMENT=FACTOR" each: segment SEGMENT's rest length times FACTOR in [0.2, 5] (0.9
  /// shortens a chord by 10 % as a repair does).
  std::vector<std::string> segment_scales;
};

/// `network` (read from `source`, named in messages) on `mesh`. InputError for an insertion
/// beyond the tolerance, a network that is not a valid chordae.json once snapped, or a scale
/// naming no segment or out of range.
ChordaeNetwork place_chordae(ChordaeNetwork network, const TriMesh& mesh, const ChordaePlacementOptions& options,
                             const std::string& source);

/// The summary's metrics of a network: segments by type, points by kind, and the total and
/// longest rest lengths (after scaling).
nlohmann::json chordae_metrics(const ChordaeNetwork& network);

/// The summary's account of chordae extracted from a label map.
nlohmann::json to_json(const ChordaeExtractionSummary& summary);

}  // namespace valve
