// valve-phantom mitral --out DIR [--config FILE.json] [--name open] [--spacing 0.2] [--seed 1]
//               [--variation 0.08] [--thickness 1] [--chord-diameter 0.5] [--no-chordae]
//               [--blur 0.1] [--noise 40] [--tissue 1000] [--background 0] [--margin 2]
//               [--format nrrd|mha|nii|dicom] [--quiet]
// valve-phantom ttv --inp MODEL.inp [--frame FRAME.vtu] --out DIR [same imaging options;
//               --thickness 0.65 --chord-diameter 0.65 by default]
// valve-phantom surface --mesh MEMBRANE.vtp [--lines CHORDAE.vtp] --out DIR [same imaging
//               options] (e.g. a simulated closed valve: the synthetic closed scan)
// --mesh-copies stl,ply,obj,vtk: the result mesh also in those formats beside its .vtp (same
// stem, LPS mm; .stl, .ply and .obj hold the geometry only, for printing and CAD).
// A digital phantom with known ground truth: the parametric open mitral valve of
// libvalve/phantom/mitral_phantom.hpp, or a finite element valve model from an Abaqus deck
// (Texas TriValve: S4R leaflet shells split into triangles, T3D2 chordae; --frame takes the
// node positions of a .vtu frame, e.g. frame 20 = closed), voxelized into a micro-CT-like
// volume (partial volume, Gaussian blur of --blur mm, Gaussian noise of standard deviation
// --noise grey values). TTV's defaults: 0.65 mm leaflet thickness (the deck's shell
// section) and 0.65 mm chordae (its truss sections, 0.27-0.36 mm²).
// Writes DIR/NAME.nrrd (or .mha, .nii.gz, a DICOM directory), the ground-truth mid-surface
// DIR/NAME.truth.vtp (TTV: with the deck's element fiber directions), the chordae
// DIR/NAME.chordae.json (mitral: the phantom's; TTV: the deck's trusses, papillary tips = held
// truss nodes, each truss with its section area and its group's law from the deck's
// *Material, see truss_chordae), for TTV DIR/NAME.leaflet_materials.json (each leaflet's law
// and thickness read from the deck's *Shell Section and *Material, for a scene's
// "leaflet_materials"; a material kind valve does not model is refused, exit 2) and
// phantom.summary.json.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <optional>

#include "valve/chordae/chordae_network.hpp"
#include "valve/core/atomic_file.hpp"
#include "valve/core/cli.hpp"
#include "valve/core/error.hpp"
#include "valve/core/progress.hpp"
#include "valve/core/stage_arguments.hpp"
#include "valve/phantom/mitral_phantom.hpp"
#include "valve/imaging/voxelize.hpp"
#include "valve/analysis/annulus_targets.hpp"
#include "valve/io/abaqus_inp.hpp"
#include "valve/io/image_io.hpp"
#include "valve/io/mesh_io.hpp"
#include "stage_usage.hpp"

using namespace valve;
namespace fs = std::filesystem;

namespace {
// What gets voxelized, whichever kind of phantom it comes from.
struct PhantomGeometry {
  TriMesh leaflets;  // mid-surface (the ground truth)
  double thickness = 1;
  std::vector<std::pair<Vec3, Vec3>> chord_segments;
  double chord_diameter = 0.5;
  std::vector<PapillaryMuscle> papillary;
  nlohmann::json description;  // for the summary
  nlohmann::json leaflet_materials;  // TTV: the deck's leaflet laws in the scene's leaflet_materials form
};

PhantomGeometry mitral_geometry(StageArguments& args, double spacing, std::uint64_t seed, bool chordae,
                                std::optional<ChordaeNetwork>* network) {
  MitralPhantomOptions o;
  o.seed = seed;
  o.variation = args.number("variation", o.variation, 0, 0.45);
  o.thickness = args.length_mm("thickness", o.thickness, 0.05, 10);
  o.chord_diameter = args.length_mm("chord-diameter", o.chord_diameter, 0.05, 5);
  o.edge_length = std::min(0.4, 2 * spacing);
  const MitralPhantom ph = make_mitral_phantom(o);
  PhantomGeometry g;
  g.leaflets = ph.leaflets;
  g.thickness = ph.options.thickness;
  g.chord_diameter = ph.chordae.diameter;
  if (chordae) {
    for (const auto& s : ph.chordae.segments) g.chord_segments.emplace_back(ph.chordae.points[s.from].position, ph.chordae.points[s.to].position);
    g.papillary = {ph.papillary[0], ph.papillary[1]};
    *network = ph.chordae;
  }
  const auto& v = ph.options;
  g.description = {
      {"atrial_direction", {ph.atrial_direction.x(), ph.atrial_direction.y(), ph.atrial_direction.z()}},
      {"valve", {{"commissural_diameter_mm", v.commissural_diameter}, {"septal_lateral_diameter_mm", v.septal_lateral_diameter},
                 {"saddle_height_mm", v.saddle_height}, {"anterior_length_mm", v.anterior_length},
                 {"posterior_length_mm", v.posterior_length}, {"thickness_mm", v.thickness}}},
      {"chordae", {{"segments", chordae ? int(ph.chordae.segments.size()) : 0},
                   {"primary", chordae ? ph.chordae.count(ChordType::primary) : 0},
                   {"secondary", chordae ? ph.chordae.count(ChordType::secondary) : 0},
                   {"strut", chordae ? ph.chordae.count(ChordType::strut) : 0},
                   {"insertions", chordae ? ph.chordae.count(ChordPointKind::insertion) : 0}}}};
  return g;
}

PhantomGeometry model_geometry(StageArguments& args, bool chordae, std::optional<ChordaeNetwork>* network) {
  const std::string inp = args.text("inp", "");
  if (inp.empty()) throw InputError("valve-phantom ttv: --inp: expected the Abaqus model (.inp), found nothing");
  const std::string frame = args.text("frame", "");
  AbaqusModel model = read_abaqus_inp(inp);
  if (!frame.empty()) {
    const MatX3 x = read_point_positions(frame);
    if (x.rows() != model.points.rows())
      throw InputError(frame + ": expected " + std::to_string(model.points.rows()) + " points (one per node of " + inp +
                       "), found " + std::to_string(x.rows()));
    model.points = x;
  }
  PhantomGeometry g;
  std::vector<int> model_rows;
  g.leaflets = shell_mesh(model, "Annular_Nodes", "Free_Edge_Nodes", &model_rows);
  g.thickness = args.length_mm("thickness", 0.65, 0.05, 10);
  double tip_motion = 0;
  if (chordae && !line_elements(model).empty()) *network = truss_chordae(model, model_rows, g.leaflets, inp, &tip_motion);
  g.leaflet_materials = leaflet_materials_json(model, inp);
  g.chord_diameter = args.length_mm("chord-diameter", 0.65, 0.05, 5);
  const auto lines = line_elements(model);
  if (chordae)
    for (const auto& [a, b] : lines) g.chord_segments.emplace_back(model.points.row(a).transpose(), model.points.row(b).transpose());
  int annulus = 0, free_edge = 0;
  for (BoundaryType b : g.leaflets.boundary) annulus += b == BoundaryType::attached, free_edge += b == BoundaryType::free_edge;
  const Vec3 atrial = annulus_atrial_direction(g.leaflets);
  g.description = {{"model", inp},
                   {"atrial_direction", {atrial.x(), atrial.y(), atrial.z()}},
                   {"frame", frame.empty() ? std::string("(the .inp coordinates)") : frame},
                   {"leaflet_nodes", g.leaflets.num_nodes()},
                   {"annulus_nodes", annulus},
                   {"free_edge_nodes", free_edge},
                   {"chordae", {{"segments", chordae ? int(lines.size()) : 0}}}};
  if (*network) {
    const ChordaeNetwork& net = **network;
    g.description["chordae"]["papillary_tips"] = net.count(ChordPointKind::papillary_tip);
    g.description["chordae"]["branch_points"] = net.count(ChordPointKind::branch);
    g.description["chordae"]["insertions"] = net.count(ChordPointKind::insertion);
    g.description["chordae"]["primary"] = net.count(ChordType::primary);
    g.description["chordae"]["secondary"] = net.count(ChordType::secondary);
    g.description["chordae"]["diameter_mm"] = net.diameter;
    g.description["chordae"]["papillary_tip_motion_not_applied_mm"] = tip_motion;
  }
  return g;
}

// Any membrane mesh (e.g. a simulated closed valve, closed.sim.vtp) voxelized as a sheet of
// --thickness, with an optional line set (closed.chordae.vtp) as tubes of --chord-diameter.
PhantomGeometry surface_geometry(StageArguments& args) {
  const std::string mesh = args.text("mesh", "");
  if (mesh.empty()) throw InputError("valve-phantom surface: --mesh: expected a membrane mesh (.vtp), found nothing");
  PhantomGeometry g;
  g.leaflets = read_mesh(mesh);
  g.thickness = args.length_mm("thickness", 1, 0.05, 10);
  g.chord_diameter = args.length_mm("chord-diameter", 0.5, 0.05, 5);
  const std::string lines = args.text("lines", "");
  if (!lines.empty()) g.chord_segments = read_line_segments(lines);
  const Vec3 atrial = annulus_atrial_direction(g.leaflets);
  g.description = {{"mesh", mesh},
                   {"atrial_direction", {atrial.x(), atrial.y(), atrial.z()}},
                   {"leaflet_nodes", g.leaflets.num_nodes()},
                   {"chordae", {{"segments", int(g.chord_segments.size())}}}};
  return g;
}
}  // namespace

int main(int argc, char** argv) {
  return run_stage("valve-phantom", kStageUsage, [&] {
    const std::vector<std::string> keys = {"name", "spacing", "seed", "variation", "thickness", "chord_diameter", "blur",
                                           "noise", "tissue", "background", "margin", "format", "inp", "frame", "mesh", "lines"};
    std::vector<std::string> flags;
    for (std::string k : keys) {
      std::replace(k.begin(), k.end(), '_', '-');
      flags.push_back(k);
    }
    flags.push_back("out");
    flags.push_back("config");
    flags.push_back("mesh-copies");
    CommandLine cl(argc, argv, flags, {"no-chordae", "quiet"});
    const std::vector<std::string> mesh_copies = parse_mesh_copies(cl.get("mesh-copies"));
    const std::string kind = cl.positional().size() == 1 ? cl.positional()[0] : "";
    if (kind != "mitral" && kind != "ttv" && kind != "surface")
      throw InputError("valve-phantom: KIND: expected mitral, ttv or surface, found " +
                       (cl.positional().empty() ? std::string("nothing") : "\"" + cl.positional()[0] + "\""));
    StageArguments args(cl, keys);
    const fs::path out = cl.require("out");
    const std::string name = args.text("name", "open");
    const double spacing = args.length_mm("spacing", 0.2, 0.02, 5);
    const auto seed = static_cast<std::uint64_t>(args.integer("seed", 1, 0, 1LL << 52));  // variation (mitral) and noise
    const double blur = args.length_mm("blur", 0.1, 0, 5);
    const double noise = args.number("noise", 40, 0, 1e6);
    const double tissue = args.number("tissue", 1000, -1e4, 3e4), background = args.number("background", 0, -1e4, 3e4);
    const double margin = args.length_mm("margin", 2, 0, 100);
    const std::string format = args.choice("format", "nrrd", {"nrrd", "mha", "nii", "dicom"});
    const bool chordae = !cl.has("no-chordae");
    if (!(tissue > background)) throw InputError("valve-phantom: --tissue: expected a grey value above --background, found " + std::to_string(tissue));
    Progress progress("valve-phantom", cl.has("quiet"));

    std::optional<ChordaeNetwork> network;
    const PhantomGeometry ph = kind == "mitral" ? mitral_geometry(args, spacing, seed, chordae, &network)
                               : kind == "ttv"  ? model_geometry(args, chordae, &network)
                                                : surface_geometry(args);
    Vec3 lo = ph.leaflets.points.colwise().minCoeff().transpose(), hi = ph.leaflets.points.colwise().maxCoeff().transpose();
    for (const auto& [a, b] : ph.chord_segments) lo = lo.cwiseMin(a).cwiseMin(b), hi = hi.cwiseMax(a).cwiseMax(b);
    for (const auto& pm : ph.papillary) {
      lo = lo.cwiseMin(pm.centre - pm.semi_axes);
      hi = hi.cwiseMax(pm.centre + pm.semi_axes);
    }
    const Vec3 pad = Vec3::Constant(margin + ph.thickness);
    const ImageGeometry grid = grid_covering(lo - pad, hi + pad, spacing);
    const double bytes = double(grid.voxel_count()) * 8;
    if (bytes > 8e9) throw InputError("valve-phantom: --spacing: expected a grid under 8 GB, found " + std::to_string(bytes / 1e9) + " GB");

    Voxelizer vox(grid);
    vox.add_sheet(ph.leaflets.points, ph.leaflets.triangles, ph.thickness);
    progress.update(0.5, "leaflets voxelized");
    if (!ph.chord_segments.empty()) vox.add_tubes(ph.chord_segments, ph.chord_diameter);
    for (const auto& pm : ph.papillary) vox.add_ellipsoid(pm.centre, pm.semi_axes);
    progress.update(0.8, "chordae voxelized");
    Volume volume = vox.to_volume(static_cast<float>(background), static_cast<float>(tissue));
    gaussian_blur(volume, blur);
    add_gaussian_noise(volume, noise, seed);

    fs::create_directories(out);
    std::string image_file = name + (format == "nrrd" ? ".nrrd" : format == "mha" ? ".mha" : format == "nii" ? ".nii.gz" : "");
    if (format == "dicom") {
      image_file = name + ".dicom";
      write_dicom_series(out / image_file, volume);
    } else {
      write_volume(out / image_file, volume);
    }
    write_mesh(out / (name + ".truth.vtp"), ph.leaflets);
    write_mesh_copies(out / (name + ".truth.vtp"), mesh_copies, ph.leaflets);
    if (network) write_file_atomic(out / (name + ".chordae.json"), to_json(*network).dump(1) + "\n");
    const bool has_materials = ph.leaflet_materials.is_array() && !ph.leaflet_materials.empty();
    if (has_materials) write_file_atomic(out / (name + ".leaflet_materials.json"), ph.leaflet_materials.dump(1) + "\n");
    progress.update(1.0, "written");

    StageSummary summary("phantom", out);
    if (kind == "ttv") {
      summary.add_input("model", args.text("inp", ""));
      if (!args.text("frame", "").empty()) summary.add_input("frame", args.text("frame", ""));
    }
    if (kind == "surface") {
      summary.add_input("mesh", args.text("mesh", ""));
      if (!args.text("lines", "").empty()) summary.add_input("lines", args.text("lines", ""));
    }
    summary.parameters() = args.used();
    summary.parameters()["kind"] = kind;
    summary.parameters()["chordae"] = chordae;
    summary.metrics() = ph.description;
    summary.metrics()["image"] = image_file;
    summary.metrics()["truth"] = name + ".truth.vtp";
    summary.metrics()["size"] = {grid.size[0], grid.size[1], grid.size[2]};
    summary.metrics()["spacing_mm"] = spacing;
    summary.metrics()["origin_mm"] = {grid.origin.x(), grid.origin.y(), grid.origin.z()};
    summary.metrics()["truth_triangles"] = ph.leaflets.num_triangles();
    if (network) summary.metrics()["chordae_file"] = name + ".chordae.json";
    if (has_materials) summary.metrics()["leaflet_materials_file"] = name + ".leaflet_materials.json";
    summary.write();
    if (!cl.has("quiet"))
      std::printf("valve-phantom: %d x %d x %d voxels at %.3g mm -> %s\n", grid.size[0], grid.size[1], grid.size[2], spacing,
                  (out / image_file).string().c_str());
    return 0;
  });
}
