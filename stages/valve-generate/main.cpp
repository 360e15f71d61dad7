// valve-generate KIND --out DIR [--triangles N] [--seed S] [--count K] [--fiber-angle DEG]
//                [--side MM] [--diameter MM] [--circumference MM] [--name NAME] [--quiet]
//                [--jitter F]   (stability tests: move interior nodes by up to F spacings -> slivers)
//                [--relax-iterations N]   (triangulate+equalize rounds, default 60; 0 = raw random points)
// --mesh-copies stl,ply,obj,vtk: the result mesh also in those formats beside its .vtp (same
// stem, LPS mm; .stl, .ply and .obj hold the geometry only, for printing and CAD).
// Writes analytic meshes (seed 3.2.2.1, Fig. 3.1) as .vtp with FiberDirection, NodeRole,
// BoundaryType and Leaflet arrays, plus generate.summary.json with their quality.
// KIND: square_patch | clamped_disk (a flat disk of --diameter, rim fixed: pressure tests and
// the CalculiX cross-check) | aortic_leaflet | three_leaflet_valve (Ch. 3) | aortic_valve (Ch. 4:
// [--gamma DEG] [--commissure-height MM] [--graft-leaflet K --graft-width-pct W
// --graft-height-pct H [--graft-commissure-gap MM]], fibers at 25 deg to the free edge rising
// toward each leaflet's midline by default (-25; a positive angle descends toward it; the
// normal valve's choices: configs/aortic_valve_normal.json). A graft is sewn in
// --graft-commissure-gap (default 0.3 mm) along the root wall from its neighbours'
// commissures. --count K writes K meshes with seeds S, S+1, ..., named NAME_<seed>.vtp.
#include <cstdio>
#include <filesystem>

#include "valve/analysis/leaflet_metrics.hpp"
#include "valve/core/cli.hpp"
#include "valve/core/error.hpp"
#include "valve/core/progress.hpp"
#include "valve/io/mesh_io.hpp"
#include "valve/mesh/analytic_mesh.hpp"
#include "valve/mesh/quality.hpp"
#include "stage_usage.hpp"

using namespace valve;
namespace fs = std::filesystem;

int main(int argc, char** argv) {
  return run_stage("valve-generate", kStageUsage, [&] {
    CommandLine cl(argc, argv,
                   {"out", "triangles", "seed", "count", "fiber-angle", "side", "diameter", "circumference", "name", "jitter",
                    "relax-iterations", "gamma", "commissure-height", "graft-leaflet", "graft-width-pct", "graft-height-pct", "graft-commissure-gap", "mesh-copies"},
                   {"quiet"});
    const std::vector<std::string> mesh_copies = parse_mesh_copies(cl.get("mesh-copies"));
    if (cl.positional().size() != 1)
      throw InputError("valve-generate: KIND: expected one of square_patch|aortic_leaflet|three_leaflet_valve|aortic_valve, found " +
                       std::to_string(cl.positional().size()) + " positional arguments");
    AnalyticMeshRequest r;
    r.kind = cl.positional()[0];
    if (r.kind != "square_patch" && r.kind != "clamped_disk" && r.kind != "aortic_leaflet" && r.kind != "three_leaflet_valve" &&
        r.kind != "aortic_valve")
      throw InputError("valve-generate: KIND: expected square_patch|clamped_disk|aortic_leaflet|three_leaflet_valve|aortic_valve, found \"" +
                       r.kind + "\"");
    const fs::path out = cl.require("out");
    const int default_triangles =
        r.kind == "square_patch" ? 229 : r.kind == "clamped_disk" ? 300 : (r.kind == "aortic_leaflet" ? 221 : 663);
    // A valve's leaflets take a third each, and each needs at least two triangles.
    r.triangles = static_cast<int>(whole_number_flag(cl, "triangles", default_triangles, r.is_valve() ? 6 : 2, 5000000));
    const auto seed = static_cast<std::uint64_t>(whole_number_flag(cl, "seed", 1, 0, 1000000000000000L));
    const int count = static_cast<int>(whole_number_flag(cl, "count", 1, 1, 10000));
    r.fiber_angle_deg = number_flag(cl, "fiber-angle", r.kind == "aortic_valve" ? AorticValveOptions{}.fiber_angle_deg : 0, -360, 360);
    const std::string name = cl.get("name").value_or(r.kind);
    if (name.empty() || name.find('/') != std::string::npos || name == "." || name == "..")
      throw InputError("--name: expected a file name without '/', found \"" + name + "\"");

    StageSummary summary("generate", out);
    summary.parameters() = {{"kind", r.kind}, {"triangles", r.triangles}, {"seed", seed}, {"count", count},
                            {"fiber_angle_deg", r.fiber_angle_deg}, {"name", name}};
    r.jitter = number_flag(cl, "jitter", 0.0, 0.0, 100.0);
    r.relax_iterations = static_cast<int>(whole_number_flag(cl, "relax-iterations", r.relax_iterations, 0, 100000));
    if (r.kind == "square_patch") r.side = number_flag(cl, "side", 15.0, 1e-6, 1e6);
    else r.diameter = number_flag(cl, "diameter", 20.0, 1e-6, 1e6);
    if (r.kind == "aortic_valve") {
      r.gamma_deg = number_flag(cl, "gamma", 22.0, 1, 89);
      r.commissure_height = number_flag(cl, "commissure-height", 5.0, 1e-6, 1e6);
      r.graft_leaflet = static_cast<int>(whole_number_flag(cl, "graft-leaflet", 0, 0, 2));
      r.graft_width_pct = number_flag(cl, "graft-width-pct", 0, 0, 99), r.graft_height_pct = number_flag(cl, "graft-height-pct", 0, -49, 99);
      r.graft_commissure_gap = number_flag(cl, "graft-commissure-gap", r.graft_commissure_gap, 0, 5);
    }
    // Each leaflet is one diameter wide at the cylinder (seed 3.2.2.1): a single one needs
    // that much of the circumference.
    if (r.has_leaflets() && r.kind != "aortic_valve") r.circumference = number_flag(cl, "circumference", 3 * r.diameter, r.diameter, 1e7);
    summary.parameters().update(analytic_mesh_parameters(r));
    nlohmann::json meshes = nlohmann::json::array();
    Progress progress("valve-generate", cl.has("quiet"));
    for (int k = 0; k < count; ++k) {
      const TriMesh mesh = generate_analytic_mesh(r, seed + k);
      const auto q = summarize_quality(triangle_qualities(mesh.points, mesh.triangles));
      const std::string file = count == 1 ? name + ".vtp" : name + "_" + std::to_string(seed + k) + ".vtp";
      write_mesh(out / file, mesh);
      write_mesh_copies(out / file, mesh_copies, mesh);
      nlohmann::json entry = {{"file", file}, {"seed", seed + k}, {"nodes", mesh.num_nodes()},
                              {"triangles", mesh.num_triangles()}, {"quality_mean", q.mean},
                              {"quality_min", q.min}, {"quality_below_0_6", q.below_0_6}};
      if (r.has_leaflets()) entry["free_edge_middle_node"] = free_edge_middle_node(mesh, 0);
      meshes.push_back(entry);
      progress.update(double(k + 1) / count, file);
    }
    summary.metrics()["meshes"] = meshes;
    summary.write();
    if (!cl.has("quiet"))
      std::printf("valve-generate: wrote %d mesh(es) to %s\n", count, out.string().c_str());
    return 0;
  });
}
