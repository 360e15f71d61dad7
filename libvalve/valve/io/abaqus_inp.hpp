#pragma once
// Reading the geometry of an Abaqus input deck (.inp): nodes, elements and node sets, enough
// for the Texas TriValve model (S4R leaflet shells, T3D2 chordae trusses, Annular_Nodes,
// Free_Edge_Nodes). Materials, steps and loads are not read. Keywords are case-insensitive;
// "**" lines are comments; GENERATE ranges are expanded.
#include <filesystem>
#include <map>
#include <string>
#include <unordered_map>
#include <vector>

#include "valve/mesh/tri_mesh.hpp"

namespace valve {

struct AbaqusElementBlock {
  std::string type;   // upper case, e.g. "S4R", "T3D2"
  std::string elset;  // as written
  std::vector<int> ids;
  std::vector<std::vector<int>> nodes;  // node ids per element
};

struct AbaqusModel {
  std::vector<int> node_ids;  // in file order
  MatX3 points;               // row i: node node_ids[i]
  std::unordered_map<int, int> row_of_node;
  std::vector<AbaqusElementBlock> blocks;
  std::map<std::string, std::vector<int>> node_sets;  // set name (upper case) -> node ids
};

/// Throws InputError naming the file and line for anything it cannot read.
AbaqusModel read_abaqus_inp(const std::filesystem::path& path);

/// The shell elements (S3*, S4*) as a triangle mesh over the nodes they use, quads split
/// along their shorter diagonal; Leaflet = index of the element block; nodes in the set
/// `annulus_set` are fixed and attached, those in `free_edge_set` free edge (sets that are
/// missing are ignored). `model_rows` receives, per mesh node, its row in model.points.
TriMesh shell_mesh(const AbaqusModel& model, const std::string& annulus_set, const std::string& free_edge_set,
                   std::vector<int>* model_rows = nullptr);

/// The two-node truss/beam elements (T3D2, B31) as segments between node rows.
std::vector<std::pair<int, int>> line_elements(const AbaqusModel& model);

}  // namespace valve
