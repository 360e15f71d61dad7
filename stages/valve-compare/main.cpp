// valve-compare SIMULATED.vtp REFERENCE.vtp --out DIR [--correspondence nodes] [--quiet]
// Distances from each node of SIMULATED to REFERENCE: with --correspondence nodes (the
// default, for meshes with the same node numbering: two models on one mesh, the Texas
// TriValve frames) the distance to the node with the same index. Writes DIR/error.vtp
// (SIMULATED with the point array Error_mm) and DIR/compare.summary.json (mean, max, RMS,
// 95th percentile).
#include <cstdio>
#include <filesystem>

#include "valve/analysis/distance_stats.hpp"
#include "valve/core/cli.hpp"
#include "valve/core/error.hpp"
#include "valve/io/mesh_io.hpp"

using namespace valve;
namespace fs = std::filesystem;

int main(int argc, char** argv) {
  return run_stage("valve-compare", [&] {
    CommandLine cl(argc, argv, {"out", "correspondence"}, {"quiet"});
    if (cl.positional().size() != 2)
      throw InputError("valve-compare: expected SIMULATED.vtp REFERENCE.vtp, found " + std::to_string(cl.positional().size()) +
                       " file arguments");
    const fs::path sim_file = cl.positional()[0], ref_file = cl.positional()[1];
    const fs::path out = cl.require("out");
    const std::string mode = cl.get("correspondence").value_or("nodes");
    if (mode != "nodes") throw InputError("valve-compare: --correspondence: expected nodes, found \"" + mode + "\"");
    const TriMesh sim = read_mesh(sim_file), ref = read_mesh(ref_file);
    const auto d = corresponding_node_distances(sim.points, ref.points);
    const DistanceStats st = summarize_distances(d);
    StageSummary summary("compare", out);
    summary.add_input("simulated", sim_file);
    summary.add_input("reference", ref_file);
    summary.parameters() = {{"correspondence", mode}};
    summary.metrics()["node_distance"] = st.to_json();
    Eigen::MatrixXd err(d.size(), 1);
    for (size_t i = 0; i < d.size(); ++i) err(i, 0) = d[i];
    write_mesh(out / "error.vtp", sim, nullptr, {{"Error_mm", err, false}});
    summary.write();
    if (!cl.has("quiet"))
      std::printf("valve-compare: %d nodes, mean %.3f mm, max %.3f mm, rms %.3f mm, p95 %.3f mm\n", st.count, st.mean,
                  st.max, st.rms, st.p95);
    return 0;
  });
}
