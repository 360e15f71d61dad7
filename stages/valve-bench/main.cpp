// valve-bench --scene SCENE.json --out DIR [--mesh FILE] [--repetitions N] [--broad-phase] [--quiet]
// Cost of the scene's closure with both models (seed Table 3.3):
// internal-force time per element per evaluation (forces only, and with the Jacobian), the
// M-S/FE ratio, and for each model the closure's wall time, steps, factorizations and total
// time over one factorization of the same system (the tangent at the solution, its diagonal
// raised until the run's solver takes it whole: one_factorization_shift, a fraction of its
// largest entry). The closure is the scene's whole model, its
// chordae and annulus motion included, as valve-simulate runs it, with the scene's solver.
// Writes DIR/bench.json and DIR/bench.csv.
// --broad-phase: instead, the contact broad phase (sweep and prune, spatial hash, BVH) at the
// mesh's positions (e.g. a closed valve from valve-simulate) and on its ×4 and ×16
// subdivisions; writes DIR/broad_phase.json and DIR/broad_phase.csv.
// Timings are medians over repetitions within this process; quote them with their ratios.
#include <cstdio>
#include <filesystem>
#include <optional>
#include <sstream>

#include "valve/scene/scene_config.hpp"
#include "valve/core/atomic_file.hpp"
#include "valve/core/cli.hpp"
#include "valve/core/stage_arguments.hpp"
#include "valve/core/error.hpp"
#include "valve/io/mesh_io.hpp"
#include "valve/mesh/validate.hpp"
#include "valve/scene/benchmark.hpp"
#include "valve/scene/scene_model.hpp"
#include "valve/solver/linear_solver.hpp"
#include "stage_usage.hpp"

using namespace valve;
namespace fs = std::filesystem;

int main(int argc, char** argv) {
  limit_blas_threads_unless_set();
  return run_stage("valve-bench", kStageUsage, [&] {
    CommandLine cl(argc, argv, {"scene", "out", "mesh", "repetitions", "set"}, {"quiet", "broad-phase"});
    const fs::path scene_file = cl.require("scene");
    const fs::path out = cl.require("out");
    json j = load_json_file(scene_file);
    if (auto v = cl.get("mesh")) j["mesh"] = fs::absolute(*v).string();
    for (const auto& a : cl.get_all("set")) apply_override(j, a, scene_file.string());
    const SceneConfig scene = parse_scene(j, scene_file.string(), scene_file.parent_path());
    for (const std::string& w : scene.warnings) std::fprintf(stderr, "valve-bench: warning: %s\n", w.c_str());
    const int reps = static_cast<int>(StageArguments(cl, {}).integer("repetitions", 7, 1, 1000));
    const TriMesh mesh = read_mesh(scene.mesh_path);
    validate_mesh(mesh, scene.mesh_path.string());

    StageSummary summary("bench", out);
    summary.add_input("scene", scene_file);
    summary.add_input("mesh", scene.mesh_path);
    summary.parameters() = scene.used;
    if (cl.has("broad-phase")) {
      std::ostringstream csv;
      csv << "method,triangles,margin_mm,seconds,pairs\n";
      nlohmann::json rows = nlohmann::json::array();
      for (const auto& c : measure_broad_phase(scene, mesh, reps)) {
        csv << c.method << "," << c.triangles << "," << c.margin_mm << "," << c.seconds << "," << c.pairs << "\n";
        rows.push_back({{"method", c.method}, {"triangles", c.triangles}, {"margin_mm", c.margin_mm},
                        {"seconds", c.seconds}, {"pairs", c.pairs}});
      }
      summary.metrics()["broad_phase"] = rows;
      write_file_atomic(out / "broad_phase.csv", csv.str());
      write_file_atomic(out / "broad_phase.json", rows.dump(2) + "\n");
      summary.write();
      if (!cl.has("quiet")) std::printf("%s", csv.str().c_str());
      return 0;
    }
    std::optional<TriMesh> closed;
    if (scene.annulus_motion) closed = read_mesh(scene.annulus_motion->closed_mesh);
    const SceneModel scene_model = prepare_scene_model(scene, mesh, closed ? &*closed : nullptr);
    if (scene.chordae) summary.add_input("chordae", scene.chordae->file);
    if (scene.annulus_motion) summary.add_input("closed_mesh", scene.annulus_motion->closed_mesh);
    nlohmann::json models = nlohmann::json::object();
    std::ostringstream csv;
    csv << "model,triangles,force_ns_per_element,force_and_jacobian_ns_per_element,solver,status,steps,factorizations,"
           "solve_seconds,one_factorization_seconds,ratio_to_factorization,one_factorization_shift\n";
    std::map<std::string, ClosureCost> closures;
    std::map<std::string, TermCost> terms;
    for (ModelKind m : {ModelKind::mass_spring, ModelKind::membrane_fe}) {
      const std::string name = to_string(m);
      closures[name] = measure_closure(scene, scene_model, m, reps);
      // Term cost at the loaded state of this model (realistic strains for the exponential).
      terms[name] = measure_term_cost(scene, mesh, m, closures[name].x, reps);
      const auto& c = closures[name];
      const auto& t = terms[name];
      models[name] = {{"force_ns_per_element", t.force_ns_per_element},
                      {"force_and_jacobian_ns_per_element", t.force_and_jacobian_ns_per_element},
                      {"solve_seconds", c.solve_seconds},
                      {"one_factorization_seconds", c.one_factorization_seconds},
                      {"one_factorization_shift", c.one_factorization_shift},
                      {"ratio_to_factorization", c.ratio_to_factorization},
                      {"solver", c.solver}};
      csv << name << "," << mesh.num_triangles() << "," << t.force_ns_per_element << ","
          << t.force_and_jacobian_ns_per_element << "," << c.solver["solver"].get<std::string>() << ","
          << c.solver["status"].get<std::string>() << "," << c.solver["steps"] << "," << c.solver["factorizations"] << ","
          << c.solve_seconds << "," << c.one_factorization_seconds << "," << c.ratio_to_factorization << ","
          << c.one_factorization_shift << "\n";
      if (c.one_factorization_shift < 0)
        std::fprintf(stderr, "valve-bench: warning: %s: the final tangent did not factorize at any diagonal shift; no factorization timed\n",
                     name.c_str());
    }
    const double force_ratio = terms["mass_spring"].force_ns_per_element / terms["membrane_fe"].force_ns_per_element;
    const double jac_ratio = terms["mass_spring"].force_and_jacobian_ns_per_element /
                             terms["membrane_fe"].force_and_jacobian_ns_per_element;
    const double run_ratio = closures["membrane_fe"].solve_seconds / closures["mass_spring"].solve_seconds;
    summary.metrics()["models"] = models;
    summary.metrics()["ms_over_fe_force_time"] = force_ratio;
    summary.metrics()["ms_over_fe_force_and_jacobian_time"] = jac_ratio;
    summary.metrics()["fe_over_ms_closure_time"] = run_ratio;
    summary.metrics()["seed"] = {{"ms_over_fe_force_time", 0.10}, {"fe_over_ms_closure_time", "20-30"}};
    write_file_atomic(out / "bench.csv", csv.str());
    write_file_atomic(out / "bench.json", summary.metrics().dump(2) + "\n");
    summary.write();
    if (!cl.has("quiet")) {
      std::printf("%s", csv.str().c_str());
      std::printf("M-S/FE internal-force time per element: %.3f (seed 0.10); with Jacobian: %.3f\n", force_ratio, jac_ratio);
      std::printf("FE/M-S closure time: %.2f (seed 20-30)\n", run_ratio);
    }
    return 0;
  });
}
