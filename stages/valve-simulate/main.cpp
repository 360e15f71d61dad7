// valve-simulate --scene SCENE.json --out DIR [--mesh FILE] [--model mass_spring|membrane_fe]
//                [--pressure "80 mmHg"] [--solver bdf2|static|quasistatic] [--set key.path=value ...]
//                [--time-series] [--quiet]
// --mesh-copies stl,ply,obj,vtk: the result mesh also in those formats beside its .vtp (same
// stem, LPS mm; .stl, .ply and .obj hold the geometry only, for printing and CAD).
// Simulates the scene (flags override its keys) and writes DIR/closed.sim.vtp (Displacement,
// GreenStrain, StretchFiber, StretchCross, AreaRatio, and PK2Stress for the FE model),
// optionally a DIR/closed.sim.pvd time series, and DIR/simulate.summary.json; with several
// leaflets also DIR/coaptation_columns.csv (the coaptation band's height down each column of
// every free edge, analysis/coaptation.hpp). DIR/closed.landmarks.mrk.json holds the closed
// annulus ring, free edges and (several leaflets) coaptation line as 3D Slicer markup curves.
// Exit 0 ok, 2 bad input, 3 not converged or failed (the summary says why; a non-converged
// run still writes its last state, a failed one writes no mesh).
#include <algorithm>
#include <cstdio>
#include <memory>
#include <filesystem>
#include <optional>
#include <set>

#include "valve/analysis/coaptation.hpp"
#include "valve/core/atomic_file.hpp"
#include "valve/analysis/surface_intersections.hpp"
#include "valve/io/chordae_io.hpp"
#include "valve/chordae/slicer_markups.hpp"
#include "valve/analysis/leaflet_metrics.hpp"
#include "valve/mechanics/chordae_rods.hpp"
#include "valve/mechanics/contact.hpp"
#include "valve/config/scene_config.hpp"
#include "valve/core/cli.hpp"
#include "valve/core/error.hpp"
#include "valve/core/progress.hpp"
#include "valve/io/mesh_io.hpp"
#include "valve/solver/linear_solver.hpp"
#include "valve/mechanics/kinematics.hpp"
#include "valve/mechanics/membrane_fe.hpp"
#include "valve/mesh/validate.hpp"
#include "valve/scene/biaxial_protocol.hpp"
#include "valve/scene/simulation.hpp"
#include "stage_usage.hpp"

using namespace valve;
namespace fs = std::filesystem;

int main(int argc, char** argv) {
  limit_blas_threads_unless_set();
  return run_stage("valve-simulate", kStageUsage, [&] {
    CommandLine cl(argc, argv, {"scene", "config", "out", "mesh", "model", "pressure", "solver", "set", "mesh-copies"}, {"time-series", "quiet"});
    const std::vector<std::string> mesh_copies = parse_mesh_copies(cl.get("mesh-copies"));
    const fs::path scene_file = cl.get("scene") ? *cl.get("scene") : cl.require("config");
    const fs::path out = cl.require("out");
    json j = scene_json_with_overrides(scene_file, cl);
    if (cl.has("time-series")) j["output"]["time_series"] = true;
    const SceneConfig scene = parse_scene(j, scene_file.string(), scene_file.parent_path());
    const bool quiet = cl.has("quiet");

    std::vector<NamedArray> mesh_arrays;
    const TriMesh mesh = read_mesh(scene.mesh_path, &mesh_arrays);
    validate_mesh(mesh, scene.mesh_path.string());
    // Every leaflet law here is anisotropic, and without the array each triangle's fiber
    // would silently follow its first edge (TriMesh::fill_defaults): a random field.
    if (std::none_of(mesh_arrays.begin(), mesh_arrays.end(),
                     [](const NamedArray& a) { return a.per_cell && a.name == "FiberDirection"; }))
      throw_input_error(scene.mesh_path.string(), "FiberDirection", "a cell array of fiber directions (the leaflet laws are anisotropic)", "none");
    std::optional<TriMesh> closed;
    if (scene.annulus_motion) closed = read_mesh(scene.annulus_motion->closed_mesh);
    const SceneModel model = prepare_scene_model(scene, mesh, closed ? &*closed : nullptr);
    auto system = build_system(scene, model);

    StageSummary summary("simulate", out);
    // This run's outputs replace an earlier run's: none of those may stay beside this run's
    // summary, whatever this run ends with (a failed run writes no mesh).
    auto remove_outputs = [&out] {
      std::error_code ec;
      for (const char* name : {"closed.sim.vtp", "closed.sim.pvd", "closed.chordae.vtp", "coaptation_columns.csv",
                               "closed.landmarks.mrk.json"})
        fs::remove(out / name, ec);
      for (const auto& format : kMeshCopyFormats) fs::remove(out / ("closed.sim." + format), ec);
      if (fs::is_directory(out / "series", ec))
        for (const auto& e : fs::directory_iterator(out / "series", ec))
          if (e.path().filename().string().rfind("step_", 0) == 0 && e.path().extension() == ".vtp") fs::remove(e.path(), ec);
    };
    remove_outputs();
    summary.add_input("scene", scene_file);
    summary.add_input("mesh", scene.mesh_path);
    if (scene.chordae) summary.add_input("chordae", scene.chordae->file);
    if (scene.annulus_motion) summary.add_input("closed_mesh", scene.annulus_motion->closed_mesh);
    summary.parameters() = scene.used;

    Progress progress("valve-simulate", quiet);
    std::vector<std::string> series_files;
    std::vector<double> series_times;
    long accepted = 0;
    SimulationHooks hooks;
    hooks.on_step = [&](const VecX& x, double t) {
      ++accepted;
      progress.update(-1, "t = " + std::to_string(t) + " ms, " + std::to_string(accepted) + " steps");
      if (scene.time_series && accepted % scene.time_series_every == 0) {
        const std::string name = "series/step_" + std::to_string(accepted) + ".vtp";
        const MatX3 pos = unflatten(model.leaflet_state(x));
        write_mesh(out / name, mesh, &pos);
        series_files.push_back(name);
        series_times.push_back(t);
      }
    };
    std::unique_ptr<BiaxialProtocol> biaxial;
    if (scene.strain_markers) {
      biaxial = std::make_unique<BiaxialProtocol>(scene, mesh);
      biaxial->install(hooks);
    }
    SimulationResult res = simulate(scene, model.mesh, *system, hooks);
    const VecX full_state = res.x;
    res.x = model.leaflet_state(full_state);
    progress.finish(res.summary.one_line());

    summary.metrics()["solver"] = res.summary.to_json();
    summary.metrics()["model"] = to_string(scene.model);
    summary.metrics()["nodes"] = mesh.num_nodes();
    summary.metrics()["triangles"] = mesh.num_triangles();
    nlohmann::json incs = nlohmann::json::array();
    for (const auto& inc : res.increments)
      incs.push_back({{"load", inc.load}, {"status", to_string(inc.summary.status)}, {"steps", inc.summary.steps}});
    summary.metrics()["increments"] = incs;
    if (biaxial) summary.metrics()["biaxial"] = biaxial->report();
    if (res.root)
      summary.metrics()["aortic_root"] = {{"status", to_string(res.root->summary.status)},
                                          {"reason", res.root->summary.reason},
                                          {"mesh_diameter_mm", res.root->mesh_diameter},
                                          {"unloaded_diameter_mm", res.root->unloaded_diameter},
                                          {"tube_only_diameter_mm", res.root->tube_diameter},
                                          {"loaded_diameter_mm", res.root->loaded_diameter},
                                          {"newton_iterations", res.root->summary.newton_iterations},
                                          {"wall_seconds", res.root->summary.wall_seconds}};
    if (model.annulus) {
      const AnnulusTargets& a = *model.annulus;
      summary.metrics()["annulus_motion"] = {{"nodes", a.nodes.size()},
                                             {"mean_motion_mm", a.mean_motion_mm},
                                             {"max_motion_mm", a.max_motion_mm},
                                             {"open_length_mm", a.open_length_mm},
                                             {"closed_length_mm", a.closed_length_mm},
                                             {"ring_registration_rms_mm", a.ring_rms_mm},
                                             {"ring_registration_rotation_deg", a.registration.rotation_angle_deg()}};
    }
    for (const auto& term : system->terms())
      if (const auto* c = dynamic_cast<const ChordaeTerm*>(term.get())) {
        const std::vector<double> tension = c->tensions(full_state);
        const ChordaeNetwork& net = *model.chordae;
        int taut = 0;
        double max_tension = 0;
        for (double t : tension) taut += t > 0, max_tension = std::max(max_tension, t);
        summary.metrics()["chordae"] = {{"segments", net.segments.size()},
                                        {"primary", net.count(ChordType::primary)},
                                        {"secondary", net.count(ChordType::secondary)},
                                        {"strut", net.count(ChordType::strut)},
                                        {"taut", taut},
                                        {"max_tension_N", max_tension}};
        MatX3 at(static_cast<int>(net.points.size()), 3);
        for (std::size_t p = 0; p < net.points.size(); ++p) at.row(p) = node3(full_state, model.attachment.point_node[p]).transpose();
        if (full_state.allFinite()) write_chordae_vtp(out / "closed.chordae.vtp", net, &at, &tension);
      }
    for (const auto& term : system->terms())
      if (const auto* c = dynamic_cast<const ContactForceTerm*>(term.get())) {
        const ContactStatistics& st = c->statistics();
        summary.metrics()["contact"] = {{"detection_mm", c->detection_distance()},
                                        {"candidate_updates", st.candidate_updates},
                                        {"candidate_pairs", st.candidate_pairs},
                                        {"active_pairs", st.active_pairs},
                                        {"deepest_penetration_mm", st.deepest_penetration},
                                        {"closest_distance_mm", st.closest_distance},
                                        {"broad_phase_seconds", st.broad_phase_seconds}};
        // Checked apart from the contact term, which sees only unsigned distances.
        if (res.x.allFinite()) {
          std::vector<char> anchored(mesh.num_nodes(), 0);
          for (int i = 0; i < mesh.num_nodes(); ++i) anchored[i] = mesh.roles[i] != NodeRole::free;
          const SurfaceIntersections crossing = find_surface_intersections(mesh.triangles, res.x, mesh.leaflet, anchored);
          summary.metrics()["contact"]["intersecting_triangle_pairs"] = crossing.pairs;
          summary.metrics()["contact"]["intersecting_pairs_between_leaflets"] = crossing.between_leaflets;
          summary.metrics()["contact"]["intersecting_pairs_one_edge_apart"] = crossing.one_edge_apart;
          summary.metrics()["contact"]["intersecting_pairs_both_anchored"] = crossing.both_anchored;
          summary.metrics()["contact"]["intersection_pairs_skipped_degenerate"] = crossing.degenerate_skipped;
          summary.metrics()["contact"]["first_intersecting_pairs"] = crossing.first_pairs;
        }
      }
    if (res.summary.status == SolverStatus::failed || !res.x.allFinite()) {
      remove_outputs();  // this run's chordae and time series
      summary.set_status("failed", res.summary.reason);
      summary.write();
      std::fprintf(stderr, "valve-simulate: failed: %s\n", res.summary.reason.c_str());
      return 3;
    }

    const MatX3 pos = unflatten(res.x);
    const MatX3 disp = pos - mesh.points;
    const auto kin = triangle_kinematics(mesh, res.x);
    Eigen::MatrixXd green(mesh.num_triangles(), 3), sf(mesh.num_triangles(), 1), sc(mesh.num_triangles(), 1),
        ar(mesh.num_triangles(), 1);
    for (int t = 0; t < mesh.num_triangles(); ++t) {
      // Written as tensor components (E11, E22, E12), as ParaView users expect.
      green.row(t) << kin[t].green[0], kin[t].green[1], 0.5 * kin[t].green[2];
      sf(t, 0) = kin[t].stretch_fiber;
      sc(t, 0) = kin[t].stretch_cross;
      ar(t, 0) = kin[t].area_ratio;
    }
    std::vector<NamedArray> arrays{{"Displacement", disp, false},
                                   {"GreenStrain", green, true},
                                   {"StretchFiber", sf, true},
                                   {"StretchCross", sc, true},
                                   {"AreaRatio", ar, true}};
    if (scene.model == ModelKind::membrane_fe) {
      // Each triangle's stress from its own material (leaflet_materials, else the scene's).
      std::vector<std::unique_ptr<MembraneFETerm>> laws;
      laws.push_back(std::make_unique<MembraneFETerm>(mesh, scene.material.law(), scene.thickness));
      for (const auto& lm : scene.leaflet_materials)
        laws.push_back(std::make_unique<MembraneFETerm>(mesh, lm.material.law(), lm.thickness));
      const std::vector<int> group = material_groups(scene, mesh);
      Eigen::MatrixXd S(mesh.num_triangles(), 3);
      for (int t = 0; t < mesh.num_triangles(); ++t) S.row(t) = laws[group[t]]->stress(res.x, t).transpose();
      arrays.push_back({"PK2Stress", S, true});
    }
    // Coaptation (seed 4.2.5) wherever leaflets can meet: a mesh of several leaflets.
    std::optional<CoaptationResult> coaptation;
    if (std::set<int>(mesh.leaflet.begin(), mesh.leaflet.end()).size() > 1) {
      CoaptationOptions coaptation_options = scene.coaptation;
      if (scene.aortic_root) coaptation_options.axis = ValveAxis{scene.aortic_root->axis_point, scene.aortic_root->axis_direction};
      coaptation = analyze_coaptation(mesh, res.x, coaptation_options);
      Eigen::MatrixXd gap(mesh.num_nodes(), 1), flag(mesh.num_nodes(), 1);
      for (int i = 0; i < mesh.num_nodes(); ++i) gap(i, 0) = coaptation->gap_mm[i], flag(i, 0) = coaptation->coapting[i];
      arrays.push_back({kCoaptationGapArray, gap, false});
      arrays.push_back({kCoaptingArray, flag, false});
      summary.metrics()["coaptation"] = coaptation_metrics(*coaptation, coaptation_options);
    }
    write_mesh(out / "closed.sim.vtp", mesh, &pos, arrays);
    write_mesh_copies(out / "closed.sim.vtp", mesh_copies, mesh, &pos, arrays);
    if (coaptation) write_file_atomic(out / "coaptation_columns.csv", coaptation_columns_csv(*coaptation));
    write_slicer_curves(out / "closed.landmarks.mrk.json", valve_landmark_curves(mesh, res.x, coaptation ? &coaptation->coapting : nullptr));
    if (scene.time_series) write_pvd(out / "closed.sim.pvd", series_files, series_times);

    double max_disp = 0;
    for (int i = 0; i < disp.rows(); ++i) max_disp = std::max(max_disp, disp.row(i).norm());
    summary.metrics()["max_displacement_mm"] = max_disp;
    nlohmann::json leaflets = nlohmann::json::array();
    int num_leaflets = 1;
    for (int l : mesh.leaflet) num_leaflets = std::max(num_leaflets, l + 1);
    const VecX X = flatten(mesh.points);
    for (int l = 0; l < num_leaflets; ++l) {
      const auto edge = free_edge_polyline(mesh, l);
      if (edge.empty()) continue;
      const Midline mid = leaflet_midline(mesh, l);
      leaflets.push_back({{"leaflet", l},
                          {"free_edge_rest_mm", polyline_length(edge, X)},
                          {"free_edge_mm", polyline_length(edge, res.x)},
                          {"midline_rest_mm", mid.length(mesh, X)},
                          {"midline_mm", mid.length(mesh, res.x)}});
      if (scene.aortic_root) leaflets.back()["belly_drop_mm"] = belly_drop(mesh, res.x, l, scene.aortic_root->axis_direction);
    }
    if (!leaflets.empty()) summary.metrics()["leaflets"] = leaflets;
    const bool ok = res.summary.status == SolverStatus::ok;
    summary.set_status(ok ? "ok" : "not_converged", res.summary.reason);
    summary.write();
    if (!quiet) {
      std::printf("valve-simulate: %s\n", res.summary.one_line().c_str());
      for (const auto& l : leaflets)
        std::printf("  leaflet %d: free edge %.3f mm, midline %.3f mm\n", l["leaflet"].get<int>(),
                    l["free_edge_mm"].get<double>(), l["midline_mm"].get<double>());
      if (coaptation) std::printf("  coaptation: %s\n", coaptation->report().c_str());
    }
    return ok ? 0 : 3;
  });
}
