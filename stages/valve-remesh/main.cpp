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
#include <algorithm>
#include <cstdio>
#include <filesystem>

#include "valve/analysis/distance_stats.hpp"
#include "valve/analysis/surface_distance.hpp"
#include "valve/chordae/slicer_markups.hpp"
#include "valve/core/cli.hpp"
#include "valve/core/error.hpp"
#include "valve/core/progress.hpp"
#include "valve/core/stage_arguments.hpp"
#include "valve/io/mesh_io.hpp"
#include "valve/mesh/quality.hpp"
#include "valve/mesh/subdivide.hpp"
#include "valve/remesh/membrane_extraction.hpp"
#include "valve/remesh/remesher.hpp"
#include "stage_usage.hpp"

using namespace valve;
namespace fs = std::filesystem;

namespace {
nlohmann::json shape_json(const MeshShapeReport& r) {
  return {{"nodes", r.nodes},
          {"triangles", r.triangles},
          {"quality_mean", r.quality.mean},
          {"quality_min", r.quality.min},
          {"quality_min_away_from_boundary", r.quality_min_away_from_boundary},
          {"quality_below_0_6", r.quality.below_0_6},
          {"mean_interior_valence", r.mean_interior_valence},
          {"boundary_loops", r.boundary_loops},
          {"manifold", r.manifold()}};
}
}  // namespace

int main(int argc, char** argv) {
  return run_stage("valve-remesh", kStageUsage, [&] {
    const std::vector<std::string> keys = {"name", "triangles", "method", "atrial_direction", "viewpoint_height", "thickness", "subdivide", "reference", "annulus_from", "annulus_tolerance"};
    CommandLine cl(argc, argv, {"out", "config", "name", "triangles", "method", "atrial-direction", "viewpoint-height", "thickness", "subdivide", "reference", "annulus-from", "annulus-tolerance", "mesh-copies"},
                   {"no-offset", "input-is-membrane", "write-membrane", "quiet"});
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
    TriMesh membrane;
    if (membrane_input) {
      membrane = surface;
      ms.direction_estimated = !mo.atrial_direction;
      ms.atrial_direction = mo.atrial_direction ? mo.atrial_direction->normalized() : estimate_atrial_direction(surface.points);
      ms.faces_in = ms.faces_kept = surface.num_triangles();
    } else {
      membrane = extract_atrial_membrane(surface, mo, &ms);
    }
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
    nlohmann::json& m = summary.metrics();
    m["atrial_direction"] = {ms.atrial_direction.x(), ms.atrial_direction.y(), ms.atrial_direction.z()};
    m["atrial_direction_estimated"] = ms.direction_estimated;
    m["extraction"] = {{"faces_in", ms.faces_in}, {"faces_kept", ms.faces_kept}, {"pieces_kept", ms.pieces_kept},
                       {"pieces_dropped", ms.pieces_dropped}, {"area_mm2", ms.area_mm2}};
    m["remesh"] = {{"target_edge_length_mm", rs.target_edge_length}, {"attempts", rs.attempts}, {"holes_filled", rs.holes_filled}, {"border_repairs", rs.border_repairs}, {"border_vertices_snapped", rs.border_snapped}, {"flap_triangles_cut", rs.flaps_cut}};
    int annulus_nodes = 0, free_edge_nodes = 0;
    for (BoundaryType b : mesh.boundary) annulus_nodes += b == BoundaryType::attached, free_edge_nodes += b == BoundaryType::free_edge;
    m["boundary_loops"] = loops;
    m["annulus_nodes"] = annulus_nodes;
    m["free_edge_nodes"] = free_edge_nodes;

    nlohmann::json levels = nlohmann::json::array();
    TriMesh level = mesh;
    for (int s = 0; s <= subdivide; ++s) {
      if (s > 0) level = subdivide_midpoint(level);
      const std::string file = name + (s == 0 ? "" : s == 1 ? "_x4" : "_x16") + ".vtp";
      const auto q = triangle_qualities(level.points, level.triangles);
      Eigen::MatrixXd quality(q.size(), 1);
      for (std::size_t t = 0; t < q.size(); ++t) quality(t, 0) = q[t];
      std::vector<NamedArray> extra{{"Quality", quality, true}};
      nlohmann::json entry = shape_json(describe_mesh_shape(level));
      entry["file"] = file;
      if (!reference.empty()) {
        const auto d = distances_to_surface(level.points, reference_mesh);
        const DistanceStats st = summarize_distances(d);
        entry["distance_to_reference"] = st.to_json();
        std::vector<double> on_boundary, inside;
        for (std::size_t i = 0; i < d.size(); ++i) (level.boundary[i] == BoundaryType::interior ? inside : on_boundary).push_back(d[i]);
        entry["distance_to_reference"]["interior_nodes"] = summarize_distances(inside).to_json();
        entry["distance_to_reference"]["boundary_nodes"] = summarize_distances(on_boundary).to_json();
        Eigen::MatrixXd err(d.size(), 1);
        for (std::size_t i = 0; i < d.size(); ++i) err(i, 0) = d[i];
        extra.push_back({"Error_mm", err, false});
      }
      write_mesh(out / file, level, nullptr, extra);
      write_mesh_copies(out / file, mesh_copies, level, nullptr, extra);
      levels.push_back(entry);
    }
    m["meshes"] = levels;
    write_slicer_curves(out / (name + ".landmarks.mrk.json"), valve_landmark_curves(mesh, flatten(mesh.points)));
    m["landmarks_file"] = name + ".landmarks.mrk.json";
    if (!rs.count_within_tolerance)
      summary.set_status("not_converged", "no edge length gave a count within " + std::to_string(int(100 * ro.tolerance)) +
                                              " % of " + std::to_string(ro.target_triangles) + " triangles in " +
                                              std::to_string(rs.attempts) + " attempts; the closest (" +
                                              std::to_string(mesh.num_triangles()) + ") is written");
    if (cl.has("write-membrane")) {
      write_mesh(out / "membrane.vtp", membrane);
      m["membrane_file"] = "membrane.vtp";
    }
    summary.write();
    progress.finish("meshes written");
    if (!cl.has("quiet")) {
      const auto& e = levels[0];
      std::printf("valve-remesh: %d triangles, quality mean %.3f min %.3f, valence %.2f, %d boundary loop(s)%s -> %s\n",
                  e["triangles"].get<int>(), e["quality_mean"].get<double>(), e["quality_min"].get<double>(),
                  e["mean_interior_valence"].get<double>(), loops,
                  reference.empty() ? "" : (", mean distance to reference " + std::to_string(e["distance_to_reference"]["mean_mm"].get<double>()).substr(0, 5) + " mm").c_str(),
                  (out / e["file"].get<std::string>()).string().c_str());
    }
    return rs.count_within_tolerance ? 0 : 3;
  });
}
