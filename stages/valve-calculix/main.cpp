// valve-calculix --scene S.json --out DIR [--mesh M.vtp] [--pressure P] [--set key.path=value ...]
//                [--ccx PATH] [--quiet]
// --mesh-copies stl,ply,obj,vtk: the result mesh also in those formats beside its .vtp (same
// stem, LPS mm; .stl, .ply and .obj hold the geometry only, for printing and CAD).
// Solves a scene with CalculiX (ccx, Debian's calculix-ccx) instead of valve's own solver, to
// cross-check the membrane FE against an established code: writes DIR/model.inp (the scene as
// thin S3 shells with *HYPERELASTIC, NEO HOOKE, fixed nodes and a follower pressure under
// NLGEOM; scene/calculix_deck.hpp says what is expressed and why shells), runs ccx in DIR (its own output in
// DIR/ccx.log), and writes DIR/closed.ccx.vtp (the mesh at ccx's loaded positions, with
// Displacement) and DIR/calculix.summary.json (max displacement, ccx's wall time). Compare
// with valve-simulate's closed.sim.vtp node by node: valve-compare A B --correspondence nodes
// --register none. The scene takes what valve-simulate's takes (--mesh, --pressure, --set).
// Exit codes: 0 ok; 2 bad input (a scene key CalculiX cannot express, named); 3 ccx not
// found, failed or wrote no displacements (reason in the summary).
#include <chrono>
#include <cstdio>
#include <filesystem>

#include "valve/scene/scene_config.hpp"
#include "valve/core/atomic_file.hpp"
#include "valve/core/cli.hpp"
#include "valve/core/error.hpp"
#include "valve/io/mesh_io.hpp"
#include "valve/mesh/validate.hpp"
#include "valve/pipeline/process.hpp"
#include "valve/scene/calculix_deck.hpp"
#include "stage_usage.hpp"

using namespace valve;
namespace fs = std::filesystem;

int main(int argc, char** argv) {
  return run_stage("valve-calculix", kStageUsage, [&] {
    CommandLine cl(argc, argv, {"scene", "out", "mesh", "pressure", "set", "ccx", "mesh-copies"}, {"quiet"});
    const std::vector<std::string> mesh_copies = parse_mesh_copies(cl.get("mesh-copies"));
    const fs::path scene_file = cl.require("scene");
    const fs::path out = fs::absolute(cl.require("out"));
    const json j = scene_json_with_overrides(scene_file, cl);
    const SceneConfig scene = parse_scene(j, scene_file.string(), scene_file.parent_path());
    const TriMesh mesh = read_mesh(scene.mesh_path);
    validate_mesh(mesh, scene.mesh_path.string());
    const std::string deck = calculix_deck(scene, mesh);

    StageSummary summary("calculix", out);
    summary.add_input("scene", scene_file);
    summary.add_input("mesh", scene.mesh_path);
    summary.parameters() = scene.used;
    std::optional<fs::path> ccx = cl.get("ccx") ? std::optional<fs::path>(*cl.get("ccx")) : find_on_path("ccx");
    if (!ccx || !fs::exists(*ccx)) {
      summary.set_status("failed", "ccx not found (apt-get install calculix-ccx, or --ccx PATH)");
      summary.write();
      std::fprintf(stderr, "valve-calculix: ccx not found\n");
      return 3;
    }
    write_file_atomic(out / "model.inp", deck);
    const auto start = std::chrono::steady_clock::now();
    const ProcessExit exit = run_process(*ccx, {ccx->string(), "-i", "model"}, out, out / "ccx.log");
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    summary.metrics()["ccx"] = ccx->string();
    summary.metrics()["ccx_wall_seconds"] = seconds;
    summary.metrics()["nodes"] = mesh.num_nodes();
    summary.metrics()["triangles"] = mesh.num_triangles();
    MatX3 u;
    try {
      if (exit.code != 0) throw InputError("ccx exited with " + std::to_string(exit.code) + " (see ccx.log)");
      u = read_calculix_displacements(out / "model.dat", mesh.num_nodes());
    } catch (const InputError& e) {
      summary.set_status("failed", e.what());
      summary.write();
      std::fprintf(stderr, "valve-calculix: %s\n", e.what());
      return 3;
    }
    const MatX3 loaded = mesh.points + u;
    write_mesh(out / "closed.ccx.vtp", mesh, &loaded, {NamedArray{"Displacement", u, false}});
    write_mesh_copies(out / "closed.ccx.vtp", mesh_copies, mesh, &loaded, {NamedArray{"Displacement", u, false}});
    summary.metrics()["max_displacement_mm"] = u.rowwise().norm().maxCoeff();
    summary.metrics()["mesh"] = "closed.ccx.vtp";
    summary.write();
    if (!cl.has("quiet"))
      std::printf("valve-calculix: max displacement %.4g mm in %.2f s -> %s\n", u.rowwise().norm().maxCoeff(), seconds,
                  (out / "closed.ccx.vtp").string().c_str());
    return 0;
  });
}
