#include "valve/chordae/chordae_placement.hpp"

#include <algorithm>
#include <cstdlib>

#include "valve/chordae/chordae_attachment.hpp"
#include "valve/chordae/slicer_markups.hpp"
#include "valve/core/error.hpp"

namespace valve {

ChordaeNetwork place_chordae(ChordaeNetwork net, const TriMesh& mesh, const ChordaePlacementOptions& options,
                             const std::string& source) {
  // Snap first (positions become mesh nodes), then the checks of a chordae.json.
  snap_insertions(net, mesh.points, options.snap_tolerance_mm, source);
  if (options.type_by_insertion) classify_by_insertion(net, mesh);
  net = read_chordae_json(to_json(net), source);
  for (const std::string& s : options.segment_scales) {
    const auto eq = s.find('=');
    char* end = nullptr;
    const long index = eq == std::string::npos ? -1 : std::strtol(s.c_str(), &end, 10);
    const double factor = eq == std::string::npos ? 0 : std::strtod(s.c_str() + eq + 1, nullptr);
    if (eq == std::string::npos || index < 0 || index >= static_cast<long>(net.segments.size()) || !(factor >= 0.2 && factor <= 5))
      throw InputError("valve-chordae: --scale: expected SEGMENT=FACTOR with SEGMENT in [0, " + std::to_string(net.segments.size() - 1) +
                       "] and FACTOR in [0.2, 5], found \"" + s + "\"");
    net.segments[index].scale = factor;
  }
  for (std::size_t s = 0; s < net.segments.size(); ++s) net.segments[s].rest_length = net.unscaled_rest_length(static_cast<int>(s));
  return net;
}

nlohmann::json chordae_metrics(const ChordaeNetwork& net) {
  double total = 0, longest = 0;
  for (std::size_t s = 0; s < net.segments.size(); ++s) {
    total += net.rest_length(static_cast<int>(s));
    longest = std::max(longest, net.rest_length(static_cast<int>(s)));
  }
  return {{"segments", net.segments.size()},
          {"primary", net.count(ChordType::primary)},
          {"secondary", net.count(ChordType::secondary)},
          {"strut", net.count(ChordType::strut)},
          {"papillary_tips", net.count(ChordPointKind::papillary_tip)},
          {"branch_points", net.count(ChordPointKind::branch)},
          {"insertions", net.count(ChordPointKind::insertion)},
          {"total_rest_length_mm", total},
          {"longest_segment_mm", longest}};
}

nlohmann::json to_json(const ChordaeExtractionSummary& s) {
  return {{"chordae_voxels", s.chordae_voxels},
          {"skeleton_voxels", s.skeleton_voxels},
          {"junctions", s.junctions},
          {"spurs_removed", s.spurs_removed},
          {"components", s.components},
          {"components_dropped", s.components_dropped},
          {"tips_on_other_tissue", s.tips_on_other_tissue},
          {"convergence_tips", s.convergence_tips}};
}

}  // namespace valve
