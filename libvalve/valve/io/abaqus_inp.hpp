#pragma once
// Reading an Abaqus input deck (.inp): nodes, elements, node and element sets, enough for the
// Texas TriValve model (S4R leaflet shells, T3D2 chordae trusses, Annular_Nodes,
// Free_Edge_Nodes), plus what a closure run needs from its model data: per-element local
// 1-directions (*Distribution, location=ELEMENT: the fiber), sections (*Shell Section
// thickness, *Solid Section truss area, each with its elset and material), *Material blocks
// (their options' keyword lines and numbers) and nodal *Boundary values (prescribed
// displacements, zeros = held). Steps and loads are not read. Keywords are case-insensitive;
// "**" lines are comments; GENERATE ranges are expanded; "Instance.id" node references keep
// the id. The deck's units are taken as mm, tonne, s, MPa (the Texas TriValve deck's).
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
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
  std::map<std::string, std::vector<int>> element_sets;  // set name (upper case) -> element ids
  struct Section {
    std::string kind;      // "SHELL" or "SOLID"
    std::string elset;     // as written
    std::string material;  // as written
    double value = 0;      // shell thickness or truss area (mm, mm²): the first data value
  };
  std::vector<Section> sections;  // in file order
  struct MaterialOption {
    std::vector<std::string> words;  // the keyword line, upper case, e.g. "*HYPERELASTIC", "OGDEN", "N=3"
    const std::string& keyword() const { return words.front(); }
    std::vector<double> data;        // every number of its data lines
    int line = 0;
  };
  struct Material {
    std::string name;  // as written
    int line = 0;
    std::vector<MaterialOption> options;
  };
  std::map<std::string, Material> materials;  // upper-case name -> material
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
/// are the model's lengths (its positions, e.g. an open frame). A truss in the elset of a
/// *Solid Section takes that section's area and material, whose law (chord_law_json) the
/// network carries; the diameter is that of the mean section area (0.5 mm, seed Table 5.1,
/// without sections). A papillary tip's prescribed displacement is not applied: the largest
/// is returned in `max_tip_motion_mm`. `file` names the deck in messages and source lines.
ChordaeNetwork truss_chordae(const AbaqusModel& model, const std::vector<int>& model_rows, const TriMesh& leaflets,
                             const std::string& file, double* max_tip_motion_mm = nullptr);

/// A leaflet material of the deck as a material object of configs/materials
/// (config/material_config.hpp), with a source line quoting the deck:
///   *Anisotropic Hyperelastic, USER, named VUANISO_ISO* -> iso_exponential (C0, D, C1, C2),
///   *Anisotropic Hyperelastic, USER, named VUANISO_HGO* -> hgo (C10, D, k1, k2, κ, C01),
///   *Hyperelastic, NEO HOOKE (C10, D1) -> iso_exponential with C0 = 2 C10, C1 = 0.
/// (the branches of the Texas TriValve subroutine Leaflet_Material.f, which dispatches on the
/// material name). Any other kind is an InputError naming the material.
nlohmann::json leaflet_material_json(const AbaqusModel::Material& material, const std::string& file);

/// A chordae material of the deck as a chord law (config/material_config.hpp parse_rod_law):
///   *Hyperelastic, OGDEN, N (μ1, α1, …, μN, αN, D1, …, DN) -> ogden,
///   *Hyperelastic, NEO HOOKE (C10, D1) -> ogden N = 1 with μ = 2 C10, α = 2,
///   *Elastic (E, ν) -> linear with E.
/// Any other kind is an InputError naming the material.
nlohmann::json chord_law_json(const AbaqusModel::Material& material, const std::string& file);

/// Each shell element block (leaflet index = block index, as shell_mesh numbers them) with
/// its *Shell Section's material and thickness, in the scene's leaflet_materials form:
/// [{"leaflets": [i], "material": {...}, "thickness": "0.65 mm"}, ...]. Empty when the deck has
/// no shell sections; a block without one is an InputError.
nlohmann::json leaflet_materials_json(const AbaqusModel& model, const std::string& file);

}  // namespace valve
