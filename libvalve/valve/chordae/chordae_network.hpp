#pragma once
// The chordae tendineae as a graph (seed 5.2.2): every segment end is a mesh node of the
// leaflets (an insertion), a papillary muscle tip or a branch point. Segments are typed
// primary (to the free edge), secondary (to the ventricular surface of the belly) or strut
// (the two thick anterior chords).
//
// JSON form (chordae.json), physical coordinates in mm (LPS):
//   {"diameter_mm": 0.5,
//    "points": [{"kind": "papillary_tip"|"branch"|"insertion", "position": [x, y, z],
//                "mesh_node": i (insertions; -1 if not snapped yet), "name": "..."}, ...],
//    "segments": [{"from": i, "to": j, "type": "primary"|"secondary"|"strut",
//                  "scale": 1.0 (rest length factor, < 1 shortens a chord as a repair does),
//                  "rest_length_mm": L0 (optional: the length at scale 1; default: the
//                                    open-geometry length),
//                  "material": "NAME" (optional: a key of "materials"),
//                  "area_mm2": A0 (optional: the section; default: from diameter_mm)}, ...],
//    "materials": {"NAME": a chord law (config/material_config.hpp parse_rod_law), ...}}
// The rest length is scale × L0, so a scale applied later (a repair, the scene's
// chordae.rest_length_scale) acts on files that carry their rest lengths.
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "valve/core/types.hpp"

namespace valve {

enum class ChordPointKind { papillary_tip, branch, insertion };
enum class ChordType { primary, secondary, strut };

struct ChordPoint {
  ChordPointKind kind = ChordPointKind::branch;
  Vec3 position = Vec3::Zero();
  int mesh_node = -1;
  std::string name;
};

struct ChordSegment {
  int from = 0, to = 0;
  ChordType type = ChordType::primary;
  double scale = 1.0;        // rest length factor (chord shortening)
  double rest_length = 0.0;  // mm at scale 1; 0 = not set (the open-geometry length)
  std::string material;      // a key of ChordaeNetwork::materials; "" = the scene's chord law
  double area = 0.0;         // mm²; 0 = not set (from the network's diameter)
};

struct ChordaeNetwork {
  std::vector<ChordPoint> points;
  std::vector<ChordSegment> segments;
  double diameter = 0.5;  // mm (seed Table 5.1)
  std::map<std::string, nlohmann::json> materials;  // chord laws by name, as in the file

  int count(ChordType type) const;
  int count(ChordPointKind kind) const;
  /// Length of segment s at scale 1: its explicit rest_length, else |from − to|.
  double unscaled_rest_length(int s) const;
  /// Rest length of segment s: scale × unscaled_rest_length(s).
  double rest_length(int s) const;
};

const char* to_string(ChordPointKind kind);
const char* to_string(ChordType type);
nlohmann::json to_json(const ChordaeNetwork& network);

/// The chords of the listed types with the trunks that carry them: every segment of those
/// types, plus, for each, the shortest path (in rest length) from its end nearer a papillary
/// tip to a tip through segments of any type. Typing is per segment and a trunk may carry
/// another type's name (the Texas TriValve deck types every trunk secondary), yet a primary
/// chord without its trunk hangs loose. Kept segments keep their types; kept points keep their
/// order.
ChordaeNetwork chords_of_types(const ChordaeNetwork& network, const std::vector<std::string>& types);

/// Reads chordae.json (the form above), checking it as a network: every segment joins two
/// distinct existing points, no chord has zero length, insertions are segment ends, and every
/// insertion is connected to a papillary tip. Errors name the file and the key
/// ("points[3].position", "segments[7]"), as InputError.
ChordaeNetwork read_chordae_json(const nlohmann::json& doc, const std::string& file);

}  // namespace valve
