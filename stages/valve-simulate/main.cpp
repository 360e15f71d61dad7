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
// valve-simulate --scene-keys prints every scene key (type, default, range) as a markdown table.
// Exit 0 ok, 2 bad input, 3 not converged or failed (the summary says why; a non-converged
// run still writes its last state, a failed one writes no mesh).
#include <cstdio>
#include <filesystem>
#include <memory>

#include "valve/scene/scene_config.hpp"
#include "valve/core/atomic_file.hpp"
#include "valve/core/cli.hpp"
#include "valve/core/error.hpp"
#include "valve/core/progress.hpp"
#include "valve/io/chordae_io.hpp"
#include "valve/io/mesh_io.hpp"
#include "valve/scene/biaxial_protocol.hpp"
#include "valve/scene/closure_files.hpp"
#include "valve/scene/closure_report.hpp"
#include "valve/scene/simulation.hpp"
#include "stage_usage.hpp"

using namespace valve;
namespace fs = std::filesystem;

int main(int argc, char** argv) {
  limit_blas_threads_unless_set();
  return run_stage("valve-simulate", kStageUsage, [&] {
    CommandLine cl(argc, argv, {"scene", "config", "out", "mesh", "model", "pressure", "solver", "set", "mesh-copies"}, {"time-series", "quiet", "scene-keys"});
    if (cl.has("scene-keys")) {
      std::fputs(scene_key_table_markdown().c_str(), stdout);
      return 0;
    }
    const std::vector<std::string> mesh_copies = parse_mesh_copies(cl.get("mesh-copies"));
    const fs::path scene_file = cl.get("scene") ? *cl.get("scene") : cl.require("config");
    const fs::path out = cl.require("out");
    json j = scene_json_with_overrides(scene_file, cl);
    if (cl.has("time-series")) j["output"]["time_series"] = true;
    const SceneConfig scene = parse_scene(j, scene_file.string(), scene_file.parent_path());
    for (const std::string& w : scene.warnings) std::fprintf(stderr, "valve-simulate: warning: %s\n", w.c_str());
    const bool quiet = cl.has("quiet");

    const TriMesh mesh = read_leaflet_mesh(scene.mesh_path);
    std::optional<TriMesh> closed;
    if (scene.annulus_motion) closed = read_mesh(scene.annulus_motion->closed_mesh);
    const SceneModel model = prepare_scene_model(scene, mesh, closed ? &*closed : nullptr);
    auto system = build_system(scene, model);

    StageSummary summary("simulate", out);
    remove_closure_files(out);
    summary.add_input("scene", scene_file);
    summary.add_input("mesh", scene.mesh_path);
    if (scene.chordae) summary.add_input("chordae", scene.chordae->file);
    if (scene.annulus_motion) summary.add_input("closed_mesh", scene.annulus_motion->closed_mesh);
    summary.parameters() = scene.used;

    Progress progress("valve-simulate", quiet);
    ClosureTimeSeries series(out, mesh, scene.time_series, scene.time_series_every);
    SimulationHooks hooks;
    hooks.on_step = [&](const VecX& x, double t) {
      series.step(unflatten(model.leaflet_state(x)), t);
      progress.update(-1, "t = " + std::to_string(t) + " ms, " + std::to_string(series.steps()) + " steps");
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

    ClosureRunReport run = closure_run_metrics(scene, mesh, model, *system, res, full_state);
    summary.metrics() = std::move(run.metrics);
    if (biaxial) summary.metrics()["biaxial"] = biaxial->report();
    if (run.chordae && full_state.allFinite())
      write_chordae_vtp(out / "closed.chordae.vtp", *model.chordae, &run.chordae->attachment_positions, &run.chordae->tension);
    if (res.summary.status == SolverStatus::failed || !res.x.allFinite()) {
      remove_closure_files(out);  // this run's chordae and time series
      summary.set_status("failed", res.summary.reason);
      summary.write();
      std::fprintf(stderr, "valve-simulate: failed: %s\n", res.summary.reason.c_str());
      return 3;
    }

    const ClosedValveAnalysis analysis = analyze_closed_valve(scene, mesh, res.x);
    if (analysis.coaptation) summary.metrics()["coaptation"] = coaptation_metrics(*analysis.coaptation, analysis.coaptation_options);
    write_closed_valve_files(out, mesh, res.x, analysis, mesh_copies);
    series.finish();
    summary.metrics()["max_displacement_mm"] = analysis.max_displacement_mm;
    if (!analysis.leaflets.empty()) summary.metrics()["leaflets"] = analysis.leaflets;
    const bool ok = res.summary.status == SolverStatus::ok;
    summary.set_status(ok ? "ok" : "not_converged", res.summary.reason);
    summary.write();
    if (!quiet) {
      std::printf("valve-simulate: %s\n", res.summary.one_line().c_str());
      for (const auto& l : analysis.leaflets)
        std::printf("  leaflet %d: free edge %.3f mm, midline %.3f mm\n", l["leaflet"].get<int>(),
                    l["free_edge_mm"].get<double>(), l["midline_mm"].get<double>());
      if (analysis.coaptation) std::printf("  coaptation: %s\n", analysis.coaptation->report().c_str());
    }
    return ok ? 0 : 3;
  });
}
