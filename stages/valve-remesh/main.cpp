// valve-remesh SURFACE --out DIR [--config FILE.json] [--name leaflets] [--triangles 650]
//              [--method isotropic|collapse] [--atrial-direction x,y,z] [--thickness 1]
//              [--no-offset] [--input-is-membrane] [--subdivide 0|1|2] [--reference TRUTH.vtp]
//              [--write-membrane] [--quiet]
// --mesh-copies stl,ply,obj,vtk: the result mesh also in those formats beside its .vtp (same
// stem, LPS mm; .stl, .ply and .obj hold the geometry only, for printing and CAD).
// From the closed surface of the leaflet tissue (valve-triangulate) to the membrane the
// simulation uses (seed 5.2.2): keep the atrial face, move it half the thickness toward the
// mid-surface, remesh to ~650 near-equilateral triangles, mark the annulus (fixed, attached)
// and the free edge, circumferential fibers. --input-is-membrane skips the extraction (the
// input is already a mid-surface, e.g. a finite element model). --subdivide 1 also writes
// NAME_x4.vtp, 2 also NAME_x16.vtp (seed 5.3.3). --reference measures the distance of every
// node to a ground-truth surface. --write-membrane also writes the extracted face before
// remeshing (membrane.vtp), to see what the remesher was given. NAME.landmarks.mrk.json holds
// the annulus ring and the free edges as 3D Slicer markup curves. Writes remesh.summary.json with the quality table.
#include <cstdio>
#include <filesystem>

#include "valve/chordae/slicer_markups.hpp"
#include "valve/core/cli.hpp"
#include "valve/core/error.hpp"
#include "valve/core/progress.hpp"
#include "valve/core/stage_arguments.hpp"
#include "valve/io/mesh_io.hpp"
#include "valve/remesh/remesh_report.hpp"
#include "stage_usage.hpp"

using namespace valve;
namespace fs = std::filesystem;

int main(int argc, char** argv) {
  return run_stage("valve-remesh", kStageUsage, [&] {
    const std::vector<std::string> keys = {"name", "triangles", "method", "atrial_direction", "viewpoint_height", "thickness", "subdivide", "reference", "annulus_from", "annulus_tolerance"};
    CommandLine cl(argc, argv, stage_flags({"out", "config"}, keys, {"mesh-copies"}), {"no-offset", "input-is-membrane", "write-membrane", "quiet"});
    const std::vector<std::string> mesh_copies = parse_mesh_copies(cl.get("mesh-copies"));
    if (cl.positional().size() != 1)
      throw InputError("valve-remesh: SURFACE: expected one surface mesh, found " + std::to_string(cl.positional().size()) + " arguments");
    const fs::path surface_file = cl.positional()[0];
    const fs::path out = cl.require("out");
    StageArguments args(cl, keys);
    const std::string name = args.text("name", "leaflets");
    RemeshOptions ro;
    ro.target_triangles = static_cast<int>(args.integer("triangles", ro.target_triangles, 8, 10000000));
    ro.method = args.choice("method", ro.method, {"isotropic", "collapse"});
    MembraneOptions mo;
    mo.atrial_direction = args.vector3("atrial-direction");
    mo.viewpoint_height = args.number("viewpoint-height", mo.viewpoint_height, 0.05, 100);
    if (mo.atrial_direction && mo.atrial_direction->norm() == 0)
      throw InputError("valve-remesh: --atrial-direction: expected a non-zero vector, found 0,0,0");
    const double thickness = args.length_mm("thickness", 1.0, 0, 20);
    const bool offset = !cl.has("no-offset");
    const bool membrane_input = cl.has("input-is-membrane");
    ro.mid_surface_offset = offset && !membrane_input ? thickness / 2 : 0;
    const int subdivide = static_cast<int>(args.integer("subdivide", 0, 0, 2));
    const std::string reference = args.text("reference", "");
    const std::string annulus_from = args.text("annulus-from", "");
    const double annulus_tolerance = args.length_mm("annulus-tolerance", 2.0, 0, 50);

    Progress progress("valve-remesh", cl.has("quiet"));
    const TriMesh surface = read_mesh(surface_file);
    TriMesh reference_mesh;
    if (!reference.empty()) reference_mesh = read_mesh(reference);  // fail early, before the work
    std::vector<std::pair<Vec3, Vec3>> annulus_landmark;
    if (!annulus_from.empty()) annulus_landmark = annulus_segments(read_mesh(annulus_from), annulus_from);
    MembraneSummary ms;
    const TriMesh membrane = membrane_input ? surface : extract_atrial_membrane(surface, mo, &ms);
    if (membrane_input) ms = describe_given_membrane(surface, mo.atrial_direction);
    RemeshSummary rs;
    TriMesh mesh = remesh_membrane(membrane, ro, &rs);
    const int loops = annulus_landmark.empty() ? mark_annulus_and_free_edge(mesh, ms.atrial_direction)
                                               : mark_annulus_near(mesh, annulus_landmark, annulus_tolerance, ms.atrial_direction, annulus_from);

    fs::create_directories(out);
    StageSummary summary("remesh", out);
    summary.add_input("surface", surface_file);
    if (!reference.empty()) summary.add_input("reference", reference);
    if (!annulus_from.empty()) summary.add_input("annulus", annulus_from);
    summary.parameters() = args.used();
    summary.parameters()["offset"] = offset;
    summary.parameters()["input_is_membrane"] = membrane_input;
    nlohmann::json& m = summary.metrics() = remesh_metrics(ms, rs, mesh, loops);
    const std::vector<RemeshLevel> levels = remesh_levels(mesh, subdivide, name, reference.empty() ? nullptr : &reference_mesh);
    for (const RemeshLevel& level : levels) {
      write_mesh(out / level.file, level.mesh, nullptr, level.arrays);
      write_mesh_copies(out / level.file, mesh_copies, level.mesh, nullptr, level.arrays);
      m["meshes"].push_back(level.entry);
    }
    write_slicer_curves(out / (name + ".landmarks.mrk.json"), valve_landmark_curves(mesh, flatten(mesh.points)));
    m["landmarks_file"] = name + ".landmarks.mrk.json";
    if (!rs.count_within_tolerance) summary.set_status("not_converged", remesh_not_converged_reason(ro, rs, mesh.num_triangles()));
    if (cl.has("write-membrane")) {
      write_mesh(out / "membrane.vtp", membrane);
      m["membrane_file"] = "membrane.vtp";
    }
    summary.write();
    progress.finish("meshes written");
    if (!cl.has("quiet"))
      std::printf("valve-remesh: %s -> %s\n", remesh_report_line(levels[0], loops).c_str(), (out / levels[0].file).string().c_str());
    return rs.count_within_tolerance ? 0 : 3;
  });
}
