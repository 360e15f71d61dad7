// valve-compare SIMULATED.vtp REFERENCE.vtp --out DIR [--correspondence nodes|nearest]
//               [--register none|annulus|all] [--sections N] [--quiet]
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
// Writes DIR/error.vtp (SIMULATED, registered, with Error_mm and for nearest NodeError_mm)
// and DIR/compare.summary.json (mean, max, RMS, 95th percentile; registration).
#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include "valve/analysis/annulus_targets.hpp"
#include "valve/analysis/distance_stats.hpp"
#include "valve/analysis/rigid_registration.hpp"
#include "valve/analysis/sections.hpp"
#include "valve/analysis/surface_distance.hpp"
#include "valve/core/cli.hpp"
#include "valve/core/error.hpp"
#include "valve/core/progress.hpp"
#include "valve/io/mesh_io.hpp"
#include "valve/mesh/closest_point.hpp"
#include "stage_usage.hpp"

using namespace valve;
namespace fs = std::filesystem;

namespace {

MatX3 rows(const MatX3& p, const std::vector<int>& idx) {
  MatX3 out(static_cast<int>(idx.size()), 3);
  for (std::size_t k = 0; k < idx.size(); ++k) out.row(k) = p.row(idx[k]);
  return out;
}

Eigen::MatrixXd column(const std::vector<double>& d) {
  Eigen::MatrixXd c(d.size(), 1);
  for (std::size_t i = 0; i < d.size(); ++i) c(i, 0) = d[i];
  return c;
}

}  // namespace

int main(int argc, char** argv) {
  return run_stage("valve-compare", kStageUsage, [&] {
    CommandLine cl(argc, argv, {"out", "correspondence", "register", "sections"}, {"quiet"});
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
    int sections = 0;
    if (const auto v = cl.get("sections")) {
      char* end = nullptr;
      const long n = std::strtol(v->c_str(), &end, 10);
      if (end == v->c_str() || *end != '\0' || n < 1 || n > 50)
        throw InputError("valve-compare: --sections: expected an integer in [1, 50], found \"" + *v + "\"");
      sections = static_cast<int>(n);
    }
    if (mode == "nodes" && !same_numbering)
      throw_input_error(ref_file.string(), "points", std::to_string(sim.num_nodes()) + " nodes (--correspondence nodes)",
                        std::to_string(ref.num_nodes()));

    IcpResult icp;
    MatX3 moved = sim.points;
    if (reg != "none") {
      MatX3 source = sim.points, target = ref.points;
      if (reg == "annulus") {
        const std::vector<int> a = annulus_ring(sim), b = annulus_ring(ref);
        if (a.size() < 3)
          throw_input_error(sim_file.string(), "NodeRole", "an annulus (boundary loop with fixed or attached nodes) to register",
                            std::to_string(a.size()) + " such nodes");
        if (b.size() < 3)
          throw_input_error(ref_file.string(), "NodeRole", "an annulus (boundary loop with fixed or attached nodes) to register",
                            std::to_string(b.size()) + " such nodes");
        source = resample_ring(rows(sim.points, a), 360);
        target = resample_ring(rows(ref.points, b), 1440);
      }
      icp = icp_point_to_point(source, target);
      moved = icp.transform.apply(sim.points);
    }

    StageSummary summary("compare", out);
    summary.add_input("simulated", sim_file);
    summary.add_input("reference", ref_file);
    summary.parameters() = {{"correspondence", mode}, {"register", reg}};
    if (reg != "none")
      summary.metrics()["registration"] = {{"rms_mm", icp.rms},
                                           {"iterations", icp.iterations},
                                           {"converged", icp.converged},
                                           {"rotation_deg", icp.transform.rotation_angle_deg()},
                                           {"translation_mm", icp.transform.translation.norm()}};
    std::vector<NamedArray> arrays;
    DistanceStats headline, node_stats;
    if (mode == "nodes") {
      const auto d = corresponding_node_distances(moved, ref.points);
      headline = summarize_distances(d);
      summary.metrics()["node_distance"] = headline.to_json();
      arrays.push_back({"Error_mm", column(d), false});
    } else {
      std::vector<double> node_d(moved.rows());
      for (int i = 0; i < moved.rows(); ++i) nearest_point_index(ref.points, moved.row(i).transpose(), &node_d[i]);
      const std::vector<double> surf_d = distances_to_surface(moved, ref);
      headline = summarize_distances(surf_d);
      node_stats = summarize_distances(node_d);
      summary.metrics()["surface_distance"] = headline.to_json();
      summary.metrics()["nearest_node_distance"] = node_stats.to_json();
      arrays.push_back({"Error_mm", column(surf_d), false});
      arrays.push_back({"NodeError_mm", column(node_d), false});
    }
    if (sections > 0) {
      const std::vector<int> ring = annulus_ring(ref);
      if (ring.size() < 3)
        throw_input_error(ref_file.string(), "NodeRole", "an annulus (boundary loop with fixed or attached nodes) for --sections",
                          std::to_string(ring.size()) + " such nodes");
      const MatX3 ring_points = rows(ref.points, ring);
      const Vec3 up = ring_points.colwise().mean().transpose() - ref.points.colwise().mean().transpose();
      const SectionFrame frame = section_frame(ring_points, sections, up);
      nlohmann::json j = to_json(frame);
      j["segments"] = nlohmann::json::array();
      auto add = [&](const char* name, const TriMesh& mesh, const MatX3& pts) {
        for (const SectionSegment& g : cut_sections(mesh, pts, frame))
          j["segments"].push_back({{"plane", g.plane}, {"offset_mm", frame.offsets[g.plane]}, {"mesh", name},
                                   {"u0", g.u0}, {"v0", g.v0}, {"u1", g.u1}, {"v1", g.v1}});
      };
      add("simulated", sim, moved);
      add("reference", ref, ref.points);
      summary.metrics()["sections"] = j;
    }
    write_mesh(out / "error.vtp", sim, &moved, arrays);
    summary.write();
    progress.finish("distances written");
    if (!cl.has("quiet")) {
      std::printf("valve-compare: %d nodes, %s distance: mean %.3f mm, max %.3f mm, rms %.3f mm, p95 %.3f mm\n", headline.count,
                  mode == "nodes" ? "node-to-node" : "surface", headline.mean, headline.max, headline.rms, headline.p95);
      if (mode == "nearest")
        std::printf("  nearest node (seed metric): mean %.3f mm, max %.3f mm\n", node_stats.mean, node_stats.max);
      if (reg != "none") std::printf("  registration (%s): rms %.3f mm, rotation %.2f deg, translation %.3f mm\n", reg.c_str(), icp.rms,
                                     icp.transform.rotation_angle_deg(), icp.transform.translation.norm());
    }
    return 0;
  });
}
