#include "valve/scene/closure_report.hpp"

#include <algorithm>
#include <memory>
#include <set>

#include "valve/analysis/leaflet_metrics.hpp"
#include "valve/analysis/surface_intersections.hpp"
#include "valve/core/error.hpp"
#include "valve/mechanics/chordae_rods.hpp"
#include "valve/mechanics/contact_base.hpp"
#include "valve/mechanics/kinematics.hpp"
#include "valve/mechanics/membrane_fe.hpp"

namespace valve {

namespace {

nlohmann::json contact_metrics(const ContactForceTerm& c, const TriMesh& mesh, const VecX& x) {
  const ContactStatistics& st = c.statistics();
  nlohmann::json j = {{"detection_mm", c.detection_distance()},
                      {"candidate_updates", st.candidate_updates},
                      {"candidate_pairs", st.candidate_pairs},
                      {"narrow_pairs", st.narrow_pairs},
                      {"active_pairs", st.active_pairs},
                      {"deepest_penetration_mm", st.deepest_penetration},
                      {"closest_distance_mm", st.closest_distance},
                      {"broad_phase_seconds", st.broad_phase_seconds}};
  if (!x.allFinite()) return j;
  std::vector<char> anchored(mesh.num_nodes(), 0);
  for (int i = 0; i < mesh.num_nodes(); ++i) anchored[i] = mesh.roles[i] != NodeRole::free;
  const SurfaceIntersections crossing = find_surface_intersections(mesh.triangles, x, mesh.leaflet, anchored);
  j["intersecting_triangle_pairs"] = crossing.pairs;
  j["intersecting_pairs_between_leaflets"] = crossing.between_leaflets;
  j["intersecting_pairs_one_edge_apart"] = crossing.one_edge_apart;
  j["intersecting_pairs_both_anchored"] = crossing.both_anchored;
  j["intersection_pairs_skipped_degenerate"] = crossing.degenerate_skipped;
  j["first_intersecting_pairs"] = crossing.first_pairs;
  return j;
}

}  // namespace

ClosureRunReport closure_run_metrics(const SceneConfig& scene, const TriMesh& mesh, const SceneModel& model,
                                     const MechanicalSystem& system, const SimulationResult& result, const VecX& full_state) {
  ClosureRunReport report;
  nlohmann::json& m = report.metrics;
  m["solver"] = result.summary.to_json();
  m["model"] = to_string(scene.model);
  m["nodes"] = mesh.num_nodes();
  m["triangles"] = mesh.num_triangles();
  nlohmann::json increments = nlohmann::json::array();
  for (const auto& inc : result.increments)
    increments.push_back({{"load", inc.load}, {"status", to_string(inc.summary.status)}, {"steps", inc.summary.steps}});
  m["increments"] = increments;
  if (result.root)
    m["aortic_root"] = {{"status", to_string(result.root->summary.status)},
                        {"reason", result.root->summary.reason},
                        {"mesh_diameter_mm", result.root->mesh_diameter},
                        {"unloaded_diameter_mm", result.root->unloaded_diameter},
                        {"tube_only_diameter_mm", result.root->tube_diameter},
                        {"loaded_diameter_mm", result.root->loaded_diameter},
                        {"newton_iterations", result.root->summary.newton_iterations},
                        {"wall_seconds", result.root->summary.wall_seconds}};
  if (model.annulus) {
    const AnnulusTargets& a = *model.annulus;
    m["annulus_motion"] = {{"nodes", a.nodes.size()},
                           {"mean_motion_mm", a.mean_motion_mm},
                           {"max_motion_mm", a.max_motion_mm},
                           {"open_length_mm", a.open_length_mm},
                           {"closed_length_mm", a.closed_length_mm},
                           {"ring_registration_rms_mm", a.ring_rms_mm},
                           {"ring_registration_rotation_deg", a.registration.rotation_angle_deg()}};
  }
  for (const auto& term : system.terms()) {
    if (const auto* c = dynamic_cast<const ChordaeTerm*>(term.get()); c && model.chordae) {
      const ChordaeNetwork& net = *model.chordae;
      ChordaeState state;
      state.tension = model.attachment.segment_tensions(c->tensions(full_state));
      int taut = 0;
      double max_tension = 0;
      for (double t : state.tension) taut += t > 0, max_tension = std::max(max_tension, t);
      m["chordae"] = {{"segments", net.segments.size()},
                      {"primary", net.count(ChordType::primary)},
                      {"secondary", net.count(ChordType::secondary)},
                      {"strut", net.count(ChordType::strut)},
                      {"taut", taut},
                      {"max_tension_N", max_tension}};
      state.attachment_positions = model.attachment.point_positions(full_state);
      report.chordae = std::move(state);
    }
    if (const auto* c = dynamic_cast<const ContactForceTerm*>(term.get()))
      m["contact"] = contact_metrics(*c, mesh, model.leaflet_state(full_state));
  }
  return report;
}

ClosedValveAnalysis analyze_closed_valve(const SceneConfig& scene, const TriMesh& mesh, const VecX& x) {
  if (!x.allFinite()) throw NumericalError("analyze_closed_valve: the closed positions are not finite");
  ClosedValveAnalysis a;
  const MatX3 pos = unflatten(x);
  const MatX3 disp = pos - mesh.points;
  const auto kin = triangle_kinematics(mesh, x);
  Eigen::MatrixXd green(mesh.num_triangles(), 3), sf(mesh.num_triangles(), 1), sc(mesh.num_triangles(), 1),
      ar(mesh.num_triangles(), 1);
  for (int t = 0; t < mesh.num_triangles(); ++t) {
    // Tensor components (E11, E22, E12), as ParaView users expect; kinematics keeps 2 E12.
    green.row(t) << kin[t].green[0], kin[t].green[1], 0.5 * kin[t].green[2];
    sf(t, 0) = kin[t].stretch_fiber;
    sc(t, 0) = kin[t].stretch_cross;
    ar(t, 0) = kin[t].area_ratio;
  }
  a.arrays = {{"Displacement", disp, false},
              {"GreenStrain", green, true},
              {"StretchFiber", sf, true},
              {"StretchCross", sc, true},
              {"AreaRatio", ar, true}};
  if (scene.model == ModelKind::membrane_fe) {
    std::vector<std::unique_ptr<MembraneFETerm>> laws;
    laws.push_back(std::make_unique<MembraneFETerm>(mesh, scene.material.law(), scene.thickness));
    for (const auto& lm : scene.leaflet_materials)
      laws.push_back(std::make_unique<MembraneFETerm>(mesh, lm.material.law(), lm.thickness));
    const std::vector<int> group = material_groups(scene, mesh);
    Eigen::MatrixXd S(mesh.num_triangles(), 3);
    for (int t = 0; t < mesh.num_triangles(); ++t) S.row(t) = laws[group[t]]->stress(x, t).transpose();
    a.arrays.push_back({"PK2Stress", S, true});
  }
  // Coaptation (seed 4.2.5) wherever leaflets can meet: a mesh of several leaflets.
  if (std::set<int>(mesh.leaflet.begin(), mesh.leaflet.end()).size() > 1) {
    a.coaptation_options = scene.coaptation;
    if (scene.aortic_root)
      a.coaptation_options.axis = ValveAxis{scene.aortic_root->axis_point, scene.aortic_root->axis_direction};
    a.coaptation = analyze_coaptation(mesh, x, a.coaptation_options);
    Eigen::MatrixXd gap(mesh.num_nodes(), 1), flag(mesh.num_nodes(), 1);
    for (int i = 0; i < mesh.num_nodes(); ++i) gap(i, 0) = a.coaptation->gap_mm[i], flag(i, 0) = a.coaptation->coapting[i];
    a.arrays.push_back({kCoaptationGapArray, gap, false});
    a.arrays.push_back({kCoaptingArray, flag, false});
  }
  for (int i = 0; i < disp.rows(); ++i) a.max_displacement_mm = std::max(a.max_displacement_mm, disp.row(i).norm());
  int num_leaflets = 1;
  for (int l : mesh.leaflet) num_leaflets = std::max(num_leaflets, l + 1);
  const VecX X = flatten(mesh.points);
  for (int l = 0; l < num_leaflets; ++l) {
    const auto edge = free_edge_polyline(mesh, l);
    if (edge.empty()) continue;
    const Midline mid = leaflet_midline(mesh, l);
    double rest_area = 0;  // the tissue a graft of this size takes (graft studies compare it)
    for (int t = 0; t < mesh.num_triangles(); ++t)
      if (mesh.leaflet[t] == l) rest_area += triangle_area(mesh.points, mesh.triangles[t]);
    a.leaflets.push_back({{"leaflet", l},
                          {"rest_area_mm2", rest_area},
                          {"free_edge_rest_mm", polyline_length(edge, X)},
                          {"free_edge_mm", polyline_length(edge, x)},
                          {"midline_rest_mm", mid.length(mesh, X)},
                          {"midline_mm", mid.length(mesh, x)}});
    if (scene.aortic_root) a.leaflets.back()["belly_drop_mm"] = belly_drop(mesh, x, l, scene.aortic_root->axis_direction);
  }
  return a;
}

}  // namespace valve
