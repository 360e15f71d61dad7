#pragma once
// A scene as a CalculiX (ccx 2.20) input deck, to cross-check valve's membrane FE against an
// established solver, and the displacements read back from ccx's .dat file.
//
// What is written: the triangles as S3 shells of the scene's thickness (*SHELL SECTION; ccx
// 2.20 takes M3D3 membranes but applies no *DLOAD pressure to them: measured, zero
// displacement). A shell adds a bending stiffness E t³/12 that valve's membrane lacks; for thin
// sheets it is negligible (the cross-check scenes use t/R = 0.005). The material as *HYPERELASTIC, NEO HOOKE (C10 = C0/2, D1 = D), the
// same function as the scene's "iso_exponential" law with C1 = 0 and "compressible": true
// (W = C0/2 (Ī1 − 3) + (J − 1)²/D); every fixed node held in x, y, z; the scene's pressure as
// a *DLOAD P on every element (under NLGEOM a follower load, as valve's pressure term), its
// sign set by the scene's direction and CalculiX's shell-face convention; one *STATIC step
// with NLGEOM, ramped from 0 to the full load. Anything else a scene declares (contact,
// chordae, bending, aortic root, annulus motion, edge loads, other laws, leaflet_materials)
// has no counterpart here and is refused with the key named (InputError).
#include <filesystem>
#include <string>

#include "valve/scene/scene_config.hpp"
#include "valve/mesh/tri_mesh.hpp"

namespace valve {

struct CalculixDeckOptions {
  double initial_increment = 0.02;  // of the step (load factor)
  double minimum_increment = 1e-6;
  int max_increments = 1000;
};

/// The deck's text for `mesh` loaded as `scene` says; throws InputError for what it cannot
/// express (naming the scene key).
std::string calculix_deck(const SceneConfig& scene, const TriMesh& mesh, const CalculixDeckOptions& options = {});

/// Node displacements (mm) of the last "displacements (vx,vy,vz)" block of a ccx .dat file,
/// one row per node 1..num_nodes. Throws InputError when the file holds none or misses nodes.
MatX3 read_calculix_displacements(const std::filesystem::path& dat_file, int num_nodes);

}  // namespace valve
