#pragma once
// The annulus-motion scene of the scene tests: a flat annular membrane (annulus_membrane, 48
// nodes per ring) whose closed-state annulus is the open one contracted by 10 % about the
// centre, with no pressure, solved statically.
#include "support/test_meshes.hpp"
#include "valve/scene/scene_config.hpp"
#include "valve/scene/scene_model.hpp"

namespace valve::test {

struct AnnulusScene {
  TriMesh open = annulus_membrane(48, 1.0), closed = annulus_membrane(48, 0.9);
  SceneConfig config = parse_scene({{"mesh", "open.vtp"},
                                    {"model", "mass_spring"},
                                    {"material", "mitral_leaflet_table51"},
                                    {"annulus_motion", {{"closed_mesh", "closed.vtp"}, {"register", false}}},
                                    {"solver", {{"type", "static"}}}},
                                   "scene.json", ".");
  SceneModel model = prepare_scene_model(config, open, &closed);
};

}  // namespace valve::test
