// valve-triangulate LABELS.nrrd --out DIR [--config FILE.json] [--name surface] [--labels 1]
//                   [--smoothing-iterations 20] [--pass-band 0.1] [--largest-only] [--quiet]
// --mesh-copies stl,ply,obj,vtk: the result mesh also in those formats beside its .vtp (same
// stem, LPS mm; .stl, .ply and .obj hold the geometry only, for printing and CAD).
// Label map -> closed surface of the chosen labels (VTK discrete flying edges + windowed-sinc
// smoothing), outward normals, physical LPS coordinates. Writes DIR/NAME.vtp and
// triangulate.summary.json (triangles, regions, area, enclosed volume).
#include <cstdio>
#include <filesystem>

#include "valve/core/cli.hpp"
#include "valve/core/error.hpp"
#include "valve/core/stage_arguments.hpp"
#include "valve/imaging/triangulation.hpp"
#include "valve/io/image_io.hpp"
#include "valve/io/mesh_io.hpp"
#include "valve/mesh/quality.hpp"
#include "stage_usage.hpp"

using namespace valve;
namespace fs = std::filesystem;

int main(int argc, char** argv) {
  return run_stage("valve-triangulate", kStageUsage, [&] {
    const std::vector<std::string> keys = {"name", "labels", "smoothing_iterations", "pass_band", "largest_only"};
    CommandLine cl(argc, argv, {"out", "config", "name", "labels", "smoothing-iterations", "pass-band", "mesh-copies"}, {"largest-only", "quiet"});
    const std::vector<std::string> mesh_copies = parse_mesh_copies(cl.get("mesh-copies"));
    if (cl.positional().size() != 1)
      throw InputError("valve-triangulate: LABELS: expected one label map, found " + std::to_string(cl.positional().size()) + " arguments");
    const fs::path labels_file = cl.positional()[0];
    const fs::path out = cl.require("out");
    StageArguments args(cl, keys);
    TriangulationOptions o;
    const std::string name = args.text("name", "surface");
    o.labels = args.integers("labels", o.labels);
    o.smoothing_iterations = static_cast<int>(args.integer("smoothing-iterations", o.smoothing_iterations, 0, 1000));
    o.pass_band = args.number("pass-band", o.pass_band, 1e-6, 1.999);
    o.largest_only = cl.has("largest-only");

    const LabelMap labels = read_label_map(labels_file);
    TriangulationSummary s;
    const TriMesh surface = triangulate_labels(labels, o, &s);
    fs::create_directories(out);
    write_mesh(out / (name + ".vtp"), surface);
    write_mesh_copies(out / (name + ".vtp"), mesh_copies, surface);
    const MeshShapeReport shape = describe_mesh_shape(surface);

    StageSummary summary("triangulate", out);
    summary.add_input("labels", labels_file);
    summary.parameters() = args.used();
    summary.parameters()["largest_only"] = o.largest_only;
    summary.metrics() = {{"surface", name + ".vtp"},       {"nodes", surface.num_nodes()},
                         {"triangles", surface.num_triangles()}, {"regions", s.regions},
                         {"area_mm2", s.area_mm2},          {"enclosed_volume_mm3", s.enclosed_volume_mm3},
                         {"boundary_loops", shape.boundary_loops}, {"manifold", shape.manifold()}};
    summary.write();
    if (!cl.has("quiet"))
      std::printf("valve-triangulate: %d triangles in %d region(s), %.1f mm2 -> %s\n", surface.num_triangles(), s.regions,
                  s.area_mm2, (out / (name + ".vtp")).string().c_str());
    return 0;
  });
}
