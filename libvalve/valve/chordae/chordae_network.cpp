#include "valve/chordae/chordae_network.hpp"

#include <algorithm>

namespace valve {

int ChordaeNetwork::count(ChordType type) const {
  return static_cast<int>(std::count_if(segments.begin(), segments.end(), [&](const ChordSegment& s) { return s.type == type; }));
}

int ChordaeNetwork::count(ChordPointKind kind) const {
  return static_cast<int>(std::count_if(points.begin(), points.end(), [&](const ChordPoint& p) { return p.kind == kind; }));
}

const char* to_string(ChordPointKind kind) {
  switch (kind) {
    case ChordPointKind::papillary_tip: return "papillary_tip";
    case ChordPointKind::branch: return "branch";
    case ChordPointKind::insertion: return "insertion";
  }
  return "?";
}

const char* to_string(ChordType type) {
  switch (type) {
    case ChordType::primary: return "primary";
    case ChordType::secondary: return "secondary";
    case ChordType::strut: return "strut";
  }
  return "?";
}

nlohmann::json to_json(const ChordaeNetwork& network) {
  nlohmann::json points = nlohmann::json::array(), segments = nlohmann::json::array();
  for (const auto& p : network.points) {
    nlohmann::json j = {{"kind", to_string(p.kind)}, {"position", {p.position.x(), p.position.y(), p.position.z()}}};
    if (p.kind == ChordPointKind::insertion) j["mesh_node"] = p.mesh_node;
    if (!p.name.empty()) j["name"] = p.name;
    points.push_back(j);
  }
  for (const auto& s : network.segments) segments.push_back({{"from", s.from}, {"to", s.to}, {"type", to_string(s.type)}});
  return {{"diameter_mm", network.diameter}, {"points", points}, {"segments", segments}};
}

}  // namespace valve
