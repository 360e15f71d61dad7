#pragma once
// Reading an Abaqus input deck (.inp): nodes, elements and node sets, enough for the Texas
// TriValve model (S4R leaflet shells, T3D2 chordae trusses, Annular_Nodes, Free_Edge_Nodes),
// plus what a closure run needs from its model data: per-element local 1-directions
// (*Distribution, location=ELEMENT: the fiber), truss cross-sections (*Solid Section) and
// nodal *Boundary values (prescribed displacements, zeros = held). Materials, steps and
// loads are not read. Keywords are case-insensitive; "**" lines are comments; GENERATE
// ranges are expanded; "Instance.id" node references keep the id.
#include <filesystem>
#include <map>
#include <string>
#include <unordered_map>
#include <vector>

#include "valve/chordae/chordae_network.hpp"
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
  /// Per element id: the first vector (a) of its *Distribution row, the local 1-direction
  /// of a rectangular orientation before projection onto the shell.
  std::unordered_map<int, Vec3> element_direction;
  /// Cross-section areas (mm²) of the *Solid Section lines, in file order (trusses).
  std::vector<double> section_areas;
  /// *Boundary values per node id: displacement per dof (x, y, z) and which dofs are set.
  struct NodalBoundary {
    Vec3 displacement = Vec3::Zero();
    int dof_mask = 0;  // bit k set: dof k+1 prescribed
  };
  std::map<int, NodalBoundary> boundary;
};

/// Throws InputError naming the file and line for anything it cannot read.
AbaqusModel read_abaqus_inp(const std::filesystem::path& path);

/// The shell elements (S3*, S4*) as a triangle mesh over the nodes they use, quads split
/// along their shorter diagonal; Leaflet = index of the element block; fiber = the element's
/// *Distribution direction projected onto the triangle (the default where none); nodes in the set
/// `annulus_set` are fixed and attached, those in `free_edge_set` free edge (sets that are
/// missing are ignored). `model_rows` receives, per mesh node, its row in model.points.
TriMesh shell_mesh(const AbaqusModel& model, const std::string& annulus_set, const std::string& free_edge_set,
                   std::vector<int>* model_rows = nullptr);

/// The two-node truss/beam elements (T3D2, B31) as segments between node rows.
std::vector<std::pair<int, int>> line_elements(const AbaqusModel& model);

/// The truss elements as a chordae network on `leaflets` = shell_mesh(model, ...) with its
/// `model_rows`: a truss node that is a shell node is an insertion (mesh_node set), one with
/// all three translations held by *Boundary a papillary tip, any other a branch point.
/// Segments touching a free-edge insertion are primary, the others secondary. Rest lengths
/// are the model's lengths (its positions, e.g. an open frame); the diameter is that of the
/// mean *Solid Section area (0.5 mm, seed Table 5.1, without sections). A papillary tip's
/// prescribed displacement is not applied: the largest is returned in `max_tip_motion_mm`.
ChordaeNetwork truss_chordae(const AbaqusModel& model, const std::vector<int>& model_rows, const TriMesh& leaflets,
                             double* max_tip_motion_mm = nullptr);

}  // namespace valve
