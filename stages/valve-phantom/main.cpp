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

#include "valve/core/atomic_file.hpp"
#include "valve/core/cli.hpp"
#include "valve/core/error.hpp"
#include "valve/core/stage_arguments.hpp"
#include "valve/imaging/voxelize.hpp"
#include "valve/io/image_io.hpp"
#include "valve/io/mesh_io.hpp"
#include "valve/phantom/phantom_geometry.hpp"
#include "stage_usage.hpp"

using namespace valve;
namespace fs = std::filesystem;

int main(int argc, char** argv) {
  return run_stage("valve-phantom", kStageUsage, [&] {
    const std::vector<std::string> keys = {"name", "spacing", "seed", "variation", "thickness", "chord_diameter", "blur",
                                           "noise", "tissue", "background", "margin", "format", "inp", "frame", "mesh", "lines"};
    CommandLine cl(argc, argv, stage_flags({}, keys, {"out", "config", "mesh-copies"}), {"no-chordae", "quiet"});
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

    // The Texas TriValve deck's sections: 0.65 mm shells, 0.27-0.36 mm² trusses.
    const double thickness = args.length_mm("thickness", kind == "ttv" ? 0.65 : 1, 0.05, 10);
    const double chord_diameter = args.length_mm("chord-diameter", kind == "ttv" ? 0.65 : 0.5, 0.05, 5);
    PhantomGeometry ph;
    std::vector<std::pair<std::string, std::string>> inputs;  // summary role, file
    if (kind == "mitral") {
      MitralPhantomOptions o;
      o.seed = seed, o.thickness = thickness, o.chord_diameter = chord_diameter, o.edge_length = std::min(0.4, 2 * spacing);
      o.variation = args.number("variation", o.variation, 0, 0.45);
      ph = mitral_phantom_geometry(o, chordae);
    } else if (kind == "ttv") {
      const ModelPhantomOptions o{args.text("inp", ""), args.text("frame", ""), thickness, chord_diameter, chordae};
      if (o.model_file.empty()) throw InputError("valve-phantom ttv: --inp: expected the Abaqus model (.inp), found nothing");
      AbaqusModel model = read_abaqus_inp(o.model_file);
      inputs = {{"model", o.model_file}, {"frame", o.frame_file}};
      ph = model_phantom_geometry(std::move(model), o, o.frame_file.empty() ? std::nullopt : std::optional(read_point_positions(o.frame_file)));
    } else {
      const std::string mesh = args.text("mesh", ""), lines = args.text("lines", "");
      if (mesh.empty()) throw InputError("valve-phantom surface: --mesh: expected a membrane mesh (.vtp), found nothing");
      inputs = {{"mesh", mesh}, {"lines", lines}};
      TriMesh membrane = read_mesh(mesh);
      ph = surface_phantom_geometry(std::move(membrane), lines.empty() ? std::vector<std::pair<Vec3, Vec3>>{} : read_line_segments(lines),
                                    thickness, chord_diameter, mesh);
    }
    const ImageGeometry grid = phantom_grid(ph, spacing, margin);
    const double bytes = double(grid.voxel_count()) * 8;
    if (bytes > 8e9) throw InputError("valve-phantom: --spacing: expected a grid under 8 GB, found " + std::to_string(bytes / 1e9) + " GB");
    Volume volume = voxelize_phantom(ph, grid, background, tissue, progress);
    gaussian_blur(volume, blur);
    add_gaussian_noise(volume, noise, seed);

    fs::create_directories(out);
    const std::string image_file = phantom_image_file(name, format);
    if (format == "dicom") write_dicom_series(out / image_file, volume);
    else write_volume(out / image_file, volume);
    write_mesh(out / (name + ".truth.vtp"), ph.leaflets);
    write_mesh_copies(out / (name + ".truth.vtp"), mesh_copies, ph.leaflets);
    if (ph.chordae) write_file_atomic(out / (name + ".chordae.json"), to_json(*ph.chordae).dump(1) + "\n");
    if (ph.has_leaflet_materials()) write_file_atomic(out / (name + ".leaflet_materials.json"), ph.leaflet_materials.dump(1) + "\n");
    progress.update(1.0, "written");

    StageSummary summary("phantom", out);
    for (const auto& [role, file] : inputs)
      if (!file.empty()) summary.add_input(role, file);
    summary.parameters() = args.used();
    summary.parameters()["kind"] = kind;
    summary.parameters()["chordae"] = chordae;
    summary.metrics() = phantom_metrics(ph, grid, name, format);
    summary.write();
    if (!cl.has("quiet"))
      std::printf("valve-phantom: %d x %d x %d voxels at %.3g mm -> %s\n", grid.size[0], grid.size[1], grid.size[2], spacing,
                  (out / image_file).string().c_str());
    return 0;
  });
}
