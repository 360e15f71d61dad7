#include "valve/scene/scene_model.hpp"

#include <algorithm>

#include "valve/config/json_reader.hpp"
#include "valve/config/material_config.hpp"
#include "valve/core/error.hpp"

namespace valve {

namespace {

// Starting guess for the free nodes when some nodes are moved by `displacement`: each free
// node moves by the inverse-square-distance weighted mean of the moved nodes' displacements
// (Shepard interpolation), so the first equilibrium solve starts without folded triangles.
MatX3 spread_displacement(const MatX3& rest, const std::vector<int>& moved, const MatX3& displacement) {
  MatX3 u = MatX3::Zero(rest.rows(), 3);
  std::vector<char> is_moved(rest.rows(), 0);
  for (std::size_t k = 0; k < moved.size(); ++k) {
    u.row(moved[k]) = displacement.row(k);
    is_moved[moved[k]] = 1;
  }
  for (int i = 0; i < rest.rows(); ++i) {
    if (is_moved[i]) continue;
    Vec3 sum = Vec3::Zero();
    double wsum = 0;
    for (std::size_t k = 0; k < moved.size(); ++k) {
      const double d2 = std::max((rest.row(i) - rest.row(moved[k])).squaredNorm(), 1e-12);
      sum += displacement.row(k).transpose() / d2;
      wsum += 1 / d2;
    }
    if (wsum > 0) u.row(i) = (sum / wsum).transpose();
  }
  return u;
}

}  // namespace

SceneModel prepare_scene_model(const SceneConfig& sc, const TriMesh& leaflets, const TriMesh* closed) {
  SceneModel model;
  model.mesh = leaflets;
  model.mesh.fill_defaults();
  model.leaflet_nodes = leaflets.num_nodes();
  if (sc.annulus_motion) {
    if (!closed) throw Error("prepare_scene_model: the scene moves the annulus but no closed mesh was given");
    const auto targets = sc.annulus_motion->correspondence == AnnulusMotionConfig::Correspondence::nodes
                             ? annulus_targets_by_node
                             : annulus_targets;
    model.annulus = targets(leaflets, *closed, sc.annulus_motion->register_rigidly, sc.mesh_path.string(),
                            sc.annulus_motion->closed_mesh.string());
    const MatX3& start = leaflets.start_positions();
    MatX3 disp(static_cast<int>(model.annulus->nodes.size()), 3);
    for (std::size_t k = 0; k < model.annulus->nodes.size(); ++k)
      disp.row(k) = model.annulus->targets.row(k) - start.row(model.annulus->nodes[k]);
    // build_system fixes the annulus nodes (whatever the scene says of node roles).
    model.mesh.initial = start + spread_displacement(start, model.annulus->nodes, disp);
  }
  if (sc.chordae) {
    const ChordaeConfig& cc = *sc.chordae;
    ChordaeNetwork net = read_chordae_json(load_json_file(cc.file), cc.file.string());
    if (cc.diameter > 0) net.diameter = cc.diameter;
    // Insertions snapped to another mesh (or not at all) are snapped to this one; a node
    // index is trusted only when the node sits where the file says.
    for (ChordPoint& p : net.points)
      if (p.kind == ChordPointKind::insertion && p.mesh_node >= 0 &&
          (p.mesh_node >= leaflets.num_nodes() || (leaflets.points.row(p.mesh_node).transpose() - p.position).norm() > 1e-6))
        p.mesh_node = -1;
    snap_insertions(net, leaflets.points, cc.snap_tolerance, cc.file.string());
    net = chords_of_types(net, cc.types);
    if (net.segments.empty())
      throw_input_error(sc.file.string(), "chordae.types", "types present in " + cc.file.string(), "no chord of those types");
    for (ChordSegment& s : net.segments) s.scale *= cc.rest_length_scale;
    ChordMaterial material;
    material.default_law = std::make_shared<LinearRodLaw>(cc.youngs_modulus);
    material.diameter = cc.diameter;
    material.density = sc.density;
    material.condense_chains = cc.chains == ChordaeConfig::Chains::condensed ||
                               (cc.chains == ChordaeConfig::Chains::automatic && sc.solver == SolverKind::quasistatic);
    if (cc.law == ChordaeConfig::Law::file)
      for (const auto& [name, law] : net.materials) {
        JsonReader r(law, cc.file.string(), "materials." + name);
        material.named_laws[name] = parse_rod_law(r);
      }
    model.attachment = attach_chordae(net, leaflets.num_nodes(), material);
    model.mesh = with_chordae_nodes(model.mesh, model.attachment);
    if (!cc.papillary_tips.empty()) {
      std::vector<int> tips;
      for (std::size_t p = 0; p < net.points.size(); ++p)
        if (net.points[p].kind == ChordPointKind::papillary_tip) tips.push_back(model.attachment.point_node[p] - model.leaflet_nodes);
      if (tips.size() != cc.papillary_tips.size())
        throw_input_error(sc.file.string(), "chordae.papillary_tips", std::to_string(tips.size()) + " positions (one per tip in " + cc.file.string() + ")",
                          std::to_string(cc.papillary_tips.size()));
      // The rest lengths stay those of the open geometry; only the start positions move.
      if (model.mesh.initial.rows() != model.mesh.num_nodes()) model.mesh.initial = model.mesh.points;
      for (std::size_t k = 0; k < tips.size(); ++k) model.mesh.initial.row(model.leaflet_nodes + tips[k]) = cc.papillary_tips[k].transpose();
    }
    model.chordae = net;
  }
  return model;
}

}  // namespace valve
