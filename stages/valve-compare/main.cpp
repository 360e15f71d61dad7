// valve-compare SIMULATED.vtp REFERENCE.vtp --out DIR [--correspondence nodes|nearest]
//               [--register none|annulus|all] [--sections N] [--quiet]
// --mesh-copies stl,ply,obj,vtk: the result mesh also in those formats beside its .vtp (same
// stem, LPS mm; .stl, .ply and .obj hold the geometry only, for printing and CAD).
// How far a simulated valve is from a reference (a closed-valve scan's membrane, or a mesh
// with the same numbering).
//   --correspondence nodes (default when both meshes have the same node count and no
//     registration is asked): the distance from node i to reference node i.
//   --correspondence nearest (default otherwise): from each simulated node to the nearest
//     reference node (the seed's metric, 5.2.2) and to the nearest point of the reference
//     surface (Error_mm).
//   --register annulus (default for nearest): rigid ICP of the simulated annulus ring onto
//     the reference's (seed); all: ICP of all nodes; none: as they are.
//   --sections N: both meshes cut by N planes across the commissure-to-commissure axis of the
//     reference's annulus (analysis/sections.hpp; seed Fig. 5.9), the segments listed in
//     the summary under metrics.sections.segments (plane, mesh, u0, v0, u1, v1 in mm; v
//     points from the leaflets to the annulus) for plotting.
//   With nearest, also the other way: each reference node's distance to the simulated
//     surface (a simulated leaflet too short to cover the reference shows there), and from
//     both the average symmetric surface distance and the Hausdorff distance
//     (analysis/mesh_comparison.hpp).
// Writes DIR/error.vtp (SIMULATED, registered, with Error_mm and for nearest NodeError_mm),
// for nearest DIR/reference_error.vtp (REFERENCE with Error_mm, its distance to SIMULATED)
// and DIR/compare.summary.json (mean, max, RMS, 95th percentile of each direction;
// metrics.symmetric_surface_distance.mean_mm and .hausdorff_mm; registration).
#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include "valve/analysis/mesh_comparison.hpp"
#include "valve/core/cli.hpp"
#include "valve/core/error.hpp"
#include "valve/core/progress.hpp"
#include "valve/io/mesh_io.hpp"
#include "stage_usage.hpp"

using namespace valve;
namespace fs = std::filesystem;

namespace {

Eigen::MatrixXd column(const std::vector<double>& d) {
  Eigen::MatrixXd c(d.size(), 1);
  for (std::size_t i = 0; i < d.size(); ++i) c(i, 0) = d[i];
  return c;
}

}  // namespace

int main(int argc, char** argv) {
  return run_stage("valve-compare", kStageUsage, [&] {
    CommandLine cl(argc, argv, {"out", "correspondence", "register", "sections", "mesh-copies"}, {"quiet"});
    const std::vector<std::string> mesh_copies = parse_mesh_copies(cl.get("mesh-copies"));
    if (cl.positional().size() != 2)
      throw InputError("valve-compare: expected SIMULATED.vtp REFERENCE.vtp, found " + std::to_string(cl.positional().size()) +
                       " file arguments");
    const fs::path sim_file = cl.positional()[0], ref_file = cl.positional()[1];
    const fs::path out = cl.require("out");
    Progress progress("valve-compare", cl.has("quiet"));
    const TriMesh sim = read_mesh(sim_file), ref = read_mesh(ref_file);
    const bool same_numbering = sim.num_nodes() == ref.num_nodes();
    const std::string mode =
        cl.get("correspondence").value_or(same_numbering && !cl.get("register") ? "nodes" : "nearest");
    if (mode != "nodes" && mode != "nearest")
      throw InputError("valve-compare: --correspondence: expected nodes or nearest, found \"" + mode + "\"");
    const std::string reg = cl.get("register").value_or(mode == "nearest" ? "annulus" : "none");
    if (reg != "none" && reg != "annulus" && reg != "all")
      throw InputError("valve-compare: --register: expected none, annulus or all, found \"" + reg + "\"");
    ComparisonOptions options;
    options.correspondence = mode == "nodes" ? Correspondence::nodes : Correspondence::nearest;
    options.registration = reg == "none" ? Registration::none : reg == "annulus" ? Registration::annulus : Registration::all;
    options.simulated_name = sim_file.string();
    options.reference_name = ref_file.string();
    if (const auto v = cl.get("sections")) {
      char* end = nullptr;
      const long n = std::strtol(v->c_str(), &end, 10);
      if (end == v->c_str() || *end != '\0' || n < 1 || n > 50)
        throw InputError("valve-compare: --sections: expected an integer in [1, 50], found \"" + *v + "\"");
      options.sections = static_cast<int>(n);
    }
    const MeshComparison c = compare_meshes(sim, ref, options);

    StageSummary summary("compare", out);
    summary.add_input("simulated", sim_file);
    summary.add_input("reference", ref_file);
    summary.parameters() = {{"correspondence", mode}, {"register", reg}};
    summary.metrics() = c.metrics();
    std::vector<NamedArray> arrays = {{"Error_mm", column(c.error_mm), false}};
    if (mode == "nearest") arrays.push_back({"NodeError_mm", column(c.node_error_mm), false});
    write_mesh(out / "error.vtp", sim, &c.moved, arrays);
    write_mesh_copies(out / "error.vtp", mesh_copies, sim, &c.moved, arrays);
    if (mode == "nearest") {
      const std::vector<NamedArray> reference_arrays = {{"Error_mm", column(c.reference_error_mm), false}};
      write_mesh(out / "reference_error.vtp", ref, nullptr, reference_arrays);
      write_mesh_copies(out / "reference_error.vtp", mesh_copies, ref, nullptr, reference_arrays);
    }
    summary.write();
    progress.finish("distances written");
    if (!cl.has("quiet")) {
      std::printf("valve-compare: %d nodes, %s distance: mean %.3f mm, max %.3f mm, rms %.3f mm, p95 %.3f mm\n", c.error.count,
                  mode == "nodes" ? "node-to-node" : "surface", c.error.mean, c.error.max, c.error.rms, c.error.p95);
      if (mode == "nearest") {
        std::printf("  reference to simulated surface: mean %.3f mm, max %.3f mm; symmetric mean %.3f mm, Hausdorff %.3f mm\n",
                    c.reference_error.mean, c.reference_error.max, c.symmetric_mean_mm, c.hausdorff_mm);
        std::printf("  nearest node (seed metric): mean %.3f mm, max %.3f mm\n", c.node_error.mean, c.node_error.max);
      }
      if (c.registered)
        std::printf("  registration (%s): rms %.3f mm, rotation %.2f deg, translation %.3f mm\n", reg.c_str(), c.icp.rms,
                    c.icp.transform.rotation_angle_deg(), c.icp.transform.translation.norm());
    }
    return 0;
  });
}
