#pragma once
// What a scene simulates beyond the leaflet mesh it names: the chordae network (papillary
// tips and branch points appended as extra nodes after the leaflet nodes, chords as rods) and
// the annulus motion from the open to the closed state (seed 5.2.2), whose targets become
// the annulus nodes' start positions.
#include <optional>
#include <vector>

#include "valve/analysis/annulus_targets.hpp"
#include "valve/chordae/chordae_attachment.hpp"
#include "valve/scene/scene_config.hpp"

namespace valve {

struct SceneModel {
  TriMesh mesh;             // leaflets, then chordae nodes; start positions include the annulus motion
  int leaflet_nodes = 0;
  std::optional<ChordaeNetwork> chordae;  // snapped to the mesh, chordae.types with their trunks
  ChordaeAttachment attachment;           // rods and chordae node masses (empty without chordae)
  std::optional<AnnulusTargets> annulus;

  /// The first leaflet_nodes positions of a state vector.
  VecX leaflet_state(const VecX& x) const { return x.head(3 * leaflet_nodes); }
};

/// Reads the scene's chordae file (InputError naming it on bad input) and lays out the model;
/// `closed` is the closed-state mesh the scene's annulus_motion names (required then).
/// Without chordae or annulus motion the model is the mesh itself.
SceneModel prepare_scene_model(const SceneConfig& scene, const TriMesh& leaflets, const TriMesh* closed = nullptr);

}  // namespace valve
