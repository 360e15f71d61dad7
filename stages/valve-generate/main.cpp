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
// --graft-height-pct H], fibers at 25 deg by default, descending toward each leaflet's
// midline; a negative angle mirrors them). --count K writes K meshes with
// seeds S, S+1, ..., named NAME_<seed>.vtp.
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "valve/analysis/leaflet_metrics.hpp"
#include "valve/core/cli.hpp"
#include "valve/core/error.hpp"
#include "valve/core/progress.hpp"
#include "valve/io/mesh_io.hpp"
#include "valve/mesh/generators.hpp"
#include "valve/mesh/quality.hpp"
#include "stage_usage.hpp"

using namespace valve;
namespace fs = std::filesystem;

namespace {
double parse_number(const CommandLine& cl, const std::string& flag, double fallback, double lo, double hi) {
  const auto v = cl.get(flag);
  if (!v) return fallback;
  char* end = nullptr;
  const double x = std::strtod(v->c_str(), &end);
  // strtod also reads hexadecimal ("0x20") and "inf"; a flag value is a plain decimal.
  const bool plain = v->find_first_of("xXnN") == std::string::npos;
  if (!plain || end == v->c_str() || *end != '\0' || !(x >= lo && x <= hi))
    throw InputError("--" + flag + ": expected a number in [" + format_number(lo) + ", " + format_number(hi) + "], found \"" +
                     *v + "\"");
  return x;
}

long parse_integer(const CommandLine& cl, const std::string& flag, long fallback, long lo, long hi) {
  const double x = parse_number(cl, flag, static_cast<double>(fallback), static_cast<double>(lo), static_cast<double>(hi));
  if (x != std::floor(x))
    throw InputError("--" + flag + ": expected a whole number in [" + std::to_string(lo) + ", " + std::to_string(hi) +
                     "], found \"" + *cl.get(flag) + "\"");
  return static_cast<long>(x);
}
}  // namespace

int main(int argc, char** argv) {
  return run_stage("valve-generate", kStageUsage, [&] {
    CommandLine cl(argc, argv,
                   {"out", "triangles", "seed", "count", "fiber-angle", "side", "diameter", "circumference", "name", "jitter",
                    "relax-iterations", "gamma", "commissure-height", "graft-leaflet", "graft-width-pct", "graft-height-pct", "mesh-copies"},
                   {"quiet"});
    const std::vector<std::string> mesh_copies = parse_mesh_copies(cl.get("mesh-copies"));
    if (cl.positional().size() != 1)
      throw InputError("valve-generate: KIND: expected one of square_patch|aortic_leaflet|three_leaflet_valve|aortic_valve, found " +
                       std::to_string(cl.positional().size()) + " positional arguments");
    const std::string kind = cl.positional()[0];
    if (kind != "square_patch" && kind != "clamped_disk" && kind != "aortic_leaflet" && kind != "three_leaflet_valve" &&
        kind != "aortic_valve")
      throw InputError("valve-generate: KIND: expected square_patch|clamped_disk|aortic_leaflet|three_leaflet_valve|aortic_valve, found \"" +
                       kind + "\"");
    const fs::path out = cl.require("out");
    const bool valve = kind == "three_leaflet_valve" || kind == "aortic_valve";
    const int default_triangles =
        kind == "square_patch" ? 229 : kind == "clamped_disk" ? 300 : (kind == "aortic_leaflet" ? 221 : 663);
    // A valve's leaflets take a third each, and each needs at least two triangles.
    const int triangles = static_cast<int>(parse_integer(cl, "triangles", default_triangles, valve ? 6 : 2, 5000000));
    const auto seed = static_cast<std::uint64_t>(parse_integer(cl, "seed", 1, 0, 1000000000000000L));
    const int count = static_cast<int>(parse_integer(cl, "count", 1, 1, 10000));
    const double fiber = parse_number(cl, "fiber-angle", kind == "aortic_valve" ? 25 : 0, -360, 360);
    const std::string name = cl.get("name").value_or(kind);
    if (name.empty() || name.find('/') != std::string::npos || name == "." || name == "..")
      throw InputError("--name: expected a file name without '/', found \"" + name + "\"");

    StageSummary summary("generate", out);
    summary.parameters() = {{"kind", kind}, {"triangles", triangles}, {"seed", seed}, {"count", count},
                            {"fiber_angle_deg", fiber}, {"name", name}};
    nlohmann::json meshes = nlohmann::json::array();
    Progress progress("valve-generate", cl.has("quiet"));
    for (int k = 0; k < count; ++k) {
      TriMesh mesh;
      PlanarMeshOptions mo{triangles / (valve ? 3 : 1), seed + k};
      mo.jitter = parse_number(cl, "jitter", 0.0, 0.0, 100.0);
      mo.max_iterations = static_cast<int>(parse_integer(cl, "relax-iterations", mo.max_iterations, 0, 100000));
      if (kind == "square_patch") {
        SquarePatchOptions o;
        o.side = parse_number(cl, "side", 15.0, 1e-6, 1e6);
        o.fiber_angle_deg = fiber;
        o.mesh = mo;
        mesh = generate_square_patch(o);
        summary.parameters()["side_mm"] = o.side;
      } else if (kind == "clamped_disk") {
        DiskOptions o;
        o.diameter = parse_number(cl, "diameter", 20.0, 1e-6, 1e6);
        o.fiber_angle_deg = fiber;
        o.mesh = mo;
        mesh = generate_clamped_disk(o);
        summary.parameters()["diameter_mm"] = o.diameter;
      } else if (kind == "aortic_valve") {
        AorticValveOptions o;
        o.diameter = parse_number(cl, "diameter", 20.0, 1e-6, 1e6);
        o.gamma_deg = parse_number(cl, "gamma", 22.0, 1, 89);
        o.commissure_height = parse_number(cl, "commissure-height", 5.0, 1e-6, 1e6);
        o.fiber_angle_deg = fiber;
        const int graft = static_cast<int>(parse_integer(cl, "graft-leaflet", 0, 0, 2));
        const double wpct = parse_number(cl, "graft-width-pct", 0, 0, 99), hpct = parse_number(cl, "graft-height-pct", 0, -49, 99);
        o.width_scale[graft] = 1 + wpct / 100;
        o.height_scale[graft] = 1 + hpct / 100;
        o.mesh = mo;
        mesh = generate_aortic_valve(o);
        summary.parameters()["diameter_mm"] = o.diameter;
        summary.parameters()["gamma_deg"] = o.gamma_deg;
        summary.parameters()["commissure_height_mm"] = o.commissure_height;
        summary.parameters()["graft_leaflet"] = graft;
        summary.parameters()["graft_width_pct"] = wpct;
        summary.parameters()["graft_height_pct"] = hpct;
      } else {
        LeafletOptions o;
        o.diameter = parse_number(cl, "diameter", 20.0, 1e-6, 1e6);
        // Each leaflet is one diameter wide at the cylinder (seed 3.2.2.1): a single one needs
        // that much of the circumference.
        o.cylinder_circumference = parse_number(cl, "circumference", 3 * o.diameter, o.diameter, 1e7);
        o.fiber_angle_deg = fiber;
        o.mesh = mo;
        mesh = kind == "aortic_leaflet" ? generate_aortic_leaflet(o) : generate_three_leaflet_valve(o);
        summary.parameters()["diameter_mm"] = o.diameter;
        summary.parameters()["circumference_mm"] = kind == "aortic_leaflet" ? o.cylinder_circumference : 3 * o.diameter;
      }
      const auto q = summarize_quality(triangle_qualities(mesh.points, mesh.triangles));
      const std::string file = count == 1 ? name + ".vtp" : name + "_" + std::to_string(seed + k) + ".vtp";
      write_mesh(out / file, mesh);
      write_mesh_copies(out / file, mesh_copies, mesh);
      nlohmann::json entry = {{"file", file}, {"seed", seed + k}, {"nodes", mesh.num_nodes()},
                              {"triangles", mesh.num_triangles()}, {"quality_mean", q.mean},
                              {"quality_min", q.min}, {"quality_below_0_6", q.below_0_6}};
      if (kind != "square_patch" && kind != "clamped_disk") entry["free_edge_middle_node"] = free_edge_middle_node(mesh, 0);
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
