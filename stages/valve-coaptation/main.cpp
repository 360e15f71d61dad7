// valve-coaptation CLOSED.vtp --out DIR [--gap ray|nearest] [--threshold MM]
//                  [--free-edge-offset MM] [--commissure-margin F] [--closed-min-height MM]
//                  [--axis-point X,Y,Z --axis-direction X,Y,Z] [--config FILE.json] [--quiet]
// --mesh-copies stl,ply,obj,vtk: the result mesh also in those formats beside its .vtp (same
// stem, LPS mm; .stl, .ply and .obj hold the geometry only, for printing and CAD).
// Measures the coaptation of a closed valve of several leaflets (seed 4.2.5) again, without
// simulating it again: another gap measure or threshold on a closure that took minutes, or a
// valve closed elsewhere. The analysis is valve-simulate's (analysis/coaptation.hpp):
//   --gap ray (default; the seed's: along each node's normal) | nearest (to the nearest point
//     of another leaflet; see docs/methods/coaptation.md);
//   --threshold 0.5 (mm; a node coapts when its gap is at most this), --free-edge-offset 3
//     (mm; how far below a free edge a band may begin), --commissure-margin 0.1 (fraction of
//     each free edge left out of the minimum height at both ends), --closed-min-height 0.5
//     (mm; a leaflet is closed when its minimum height is at least this);
//   --axis-point / --axis-direction: the valve's axis (the aortic root's: 0,0,0 and 0,0,1 for
//     valve-generate aortic_valve); with it, each free edge's distance from the axis and the
//     projected orifice (the cross-section no leaflet covers, seen along the axis).
// CLOSED.vtp needs the Leaflet and BoundaryType arrays (valve-simulate's closed.sim.vtp has
// them). Its points are the closed shape; the rest shape, which sets the columns down each
// leaflet and the commissure margins along each free edge, is points minus its Displacement
// array, or the points themselves when it has none.
// Writes DIR/coaptation.vtp (CLOSED.vtp's mesh with CoaptationGap_mm and Coapting),
// DIR/coaptation_columns.csv (per leaflet the band height down each sampled column of the
// free edge: leaflet,arc_mm,height_mm,band_top_mm) and DIR/coaptation.summary.json
// (metrics.coaptation as valve-simulate writes it).
// Exit 0 ok, 2 bad input (one leaflet only, a bad flag; nothing written).
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <set>

#include "valve/analysis/coaptation.hpp"
#include "valve/core/atomic_file.hpp"
#include "valve/core/cli.hpp"
#include "valve/core/error.hpp"
#include "valve/core/stage_arguments.hpp"
#include "valve/io/mesh_io.hpp"
#include "valve/mesh/validate.hpp"
#include "stage_usage.hpp"

using namespace valve;
namespace fs = std::filesystem;

int main(int argc, char** argv) {
  return run_stage("valve-coaptation", kStageUsage, [&] {
    const std::vector<std::string> keys = {"gap", "threshold", "free_edge_offset", "commissure_margin",
                                           "closed_min_height", "axis_point", "axis_direction"};
    CommandLine cl(argc, argv, {"out", "config", "gap", "threshold", "free-edge-offset", "commissure-margin",
                                "closed-min-height", "axis-point", "axis-direction", "mesh-copies"},
                   {"quiet"});
    const std::vector<std::string> mesh_copies = parse_mesh_copies(cl.get("mesh-copies"));
    if (cl.positional().size() != 1)
      throw InputError("valve-coaptation: expected one CLOSED.vtp, found " + std::to_string(cl.positional().size()) +
                       " file arguments");
    const fs::path file = cl.positional()[0];
    const fs::path out = cl.require("out");
    StageArguments args(cl, keys);
    CoaptationOptions options;
    options.gap = args.choice("gap", to_string(options.gap), {"ray", "nearest"}) == "nearest" ? GapMeasure::nearest
                                                                                             : GapMeasure::ray;
    options.threshold_mm = args.length_mm("threshold", options.threshold_mm, 1e-6, 100);
    options.free_edge_offset_mm = args.length_mm("free-edge-offset", options.free_edge_offset_mm, 0, 1e3);
    options.commissure_margin = args.number("commissure-margin", options.commissure_margin, 0, 0.499);
    options.closed_min_height_mm = args.length_mm("closed-min-height", options.closed_min_height_mm, 1e-6, 1e3);
    const auto axis_point = args.vector3("axis-point"), axis_direction = args.vector3("axis-direction");
    if (axis_point.has_value() != axis_direction.has_value())
      throw InputError("valve-coaptation: --axis-point/--axis-direction: expected both or neither, found only --" +
                       std::string(axis_point ? "axis-point" : "axis-direction"));
    if (axis_direction) options.axis = ValveAxis{*axis_point, *axis_direction};
    if (options.axis && !options.axis->valid())  // named by its flag here; validate() is the library's guard
      throw InputError("valve-coaptation: --axis-direction: expected a non-zero finite x,y,z, found " +
                       std::to_string((*axis_direction)[0]) + "," + std::to_string((*axis_direction)[1]) + "," +
                       std::to_string((*axis_direction)[2]));
    options.validate();

    std::vector<NamedArray> extra;
    TriMesh mesh = read_mesh(file, &extra);
    validate_mesh(mesh, file.string());
    // Without it every node is interior: no free edge, so every height would read 0.
    if (std::none_of(extra.begin(), extra.end(), [](const NamedArray& a) { return !a.per_cell && a.name == "BoundaryType"; }))
      throw_input_error(file.string(), "BoundaryType", "a point array (0 interior, 1 attached, 2 free edge)", "none");
    const std::set<int> leaflets(mesh.leaflet.begin(), mesh.leaflet.end());
    if (leaflets.size() < 2)
      throw_input_error(file.string(), "Leaflet", "a mesh of at least two leaflets", std::to_string(leaflets.size()) + " leaflet id(s)");
    const MatX3 closed = mesh.points;
    for (const auto& a : extra)
      if (a.name == "Displacement" && !a.per_cell && a.values.rows() == mesh.num_nodes() && a.values.cols() == 3) {
        if (!a.values.allFinite()) throw_input_error(file.string(), "Displacement", "finite values", "NaN or infinity");
        mesh.points = closed - a.values;
      }
    const CoaptationResult result = analyze_coaptation(mesh, flatten(closed), options);

    Eigen::MatrixXd gap(mesh.num_nodes(), 1), flag(mesh.num_nodes(), 1);
    for (int i = 0; i < mesh.num_nodes(); ++i) gap(i, 0) = result.gap_mm[i], flag(i, 0) = result.coapting[i];
    StageSummary summary("coaptation", out);
    summary.add_input("closed", file);
    summary.parameters() = args.used();
    summary.metrics()["coaptation"] = coaptation_metrics(result, options);
    write_mesh(out / "coaptation.vtp", mesh, &closed, {{kCoaptationGapArray, gap, false}, {kCoaptingArray, flag, false}});
    write_mesh_copies(out / "coaptation.vtp", mesh_copies, mesh, &closed, {{kCoaptationGapArray, gap, false}, {kCoaptingArray, flag, false}});
    write_file_atomic(out / "coaptation_columns.csv", coaptation_columns_csv(result));
    summary.write();
    if (!cl.has("quiet")) std::printf("valve-coaptation: %s\n", result.report().c_str());
    return 0;
  });
}
