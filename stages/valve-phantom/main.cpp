// valve-phantom mitral --out DIR [--config FILE.json] [--name open] [--spacing 0.2] [--seed 1]
//               [--variation 0.08] [--thickness 1] [--chord-diameter 0.5] [--no-chordae]
//               [--blur 0.1] [--noise 40] [--tissue 1000] [--background 0] [--margin 2]
//               [--format nrrd|mha|nii|dicom] [--quiet]
// A digital phantom with known ground truth: the parametric open mitral valve of
// libvalve/imaging/mitral_phantom.hpp voxelized into a micro-CT-like volume (partial volume,
// Gaussian blur of --blur mm, Gaussian noise of standard deviation --noise grey values).
// Writes DIR/NAME.nrrd (or .mha, .nii.gz, a DICOM directory), the ground-truth mid-surface
// DIR/NAME.truth.vtp, the chordae DIR/NAME.chordae.json and phantom.summary.json.
#include <algorithm>
#include <cstdio>
#include <filesystem>

#include "valve/chordae/chordae_network.hpp"
#include "valve/core/atomic_file.hpp"
#include "valve/core/cli.hpp"
#include "valve/core/error.hpp"
#include "valve/core/progress.hpp"
#include "valve/core/stage_arguments.hpp"
#include "valve/imaging/mitral_phantom.hpp"
#include "valve/imaging/voxelize.hpp"
#include "valve/io/image_io.hpp"
#include "valve/io/mesh_io.hpp"

using namespace valve;
namespace fs = std::filesystem;

int main(int argc, char** argv) {
  return run_stage("valve-phantom", [&] {
    const std::vector<std::string> keys = {"name", "spacing", "seed", "variation", "thickness", "chord_diameter", "blur",
                                           "noise", "tissue", "background", "margin", "format", "chordae"};
    std::vector<std::string> flags;
    for (std::string k : keys) {
      std::replace(k.begin(), k.end(), '_', '-');
      if (k != "chordae") flags.push_back(k);
    }
    flags.push_back("out");
    flags.push_back("config");
    CommandLine cl(argc, argv, flags, {"no-chordae", "quiet"});
    if (cl.positional().size() != 1 || cl.positional()[0] != "mitral")
      throw InputError("valve-phantom: KIND: expected mitral, found " +
                       (cl.positional().empty() ? std::string("nothing") : "\"" + cl.positional()[0] + "\""));
    StageArguments args(cl, keys);
    const fs::path out = cl.require("out");
    const std::string name = args.text("name", "open");
    MitralPhantomOptions o;
    o.seed = static_cast<std::uint64_t>(args.integer("seed", 1, 0, 1LL << 52));
    o.variation = args.number("variation", o.variation, 0, 0.45);
    o.thickness = args.length_mm("thickness", o.thickness, 0.05, 10);
    o.chord_diameter = args.length_mm("chord-diameter", o.chord_diameter, 0.05, 5);
    const double spacing = args.length_mm("spacing", 0.2, 0.02, 5);
    const double blur = args.length_mm("blur", 0.1, 0, 5);
    const double noise = args.number("noise", 40, 0, 1e6);
    const double tissue = args.number("tissue", 1000, -1e4, 3e4), background = args.number("background", 0, -1e4, 3e4);
    const double margin = args.length_mm("margin", 2, 0, 100);
    const std::string format = args.choice("format", "nrrd", {"nrrd", "mha", "nii", "dicom"});
    const bool chordae = !cl.has("no-chordae");
    if (!(tissue > background)) throw InputError("valve-phantom: --tissue: expected a grey value above --background, found " + std::to_string(tissue));
    o.edge_length = std::min(0.4, 2 * spacing);
    Progress progress("valve-phantom", cl.has("quiet"));

    const MitralPhantom ph = make_mitral_phantom(o);
    Vec3 lo = ph.leaflets.points.colwise().minCoeff().transpose(), hi = ph.leaflets.points.colwise().maxCoeff().transpose();
    for (const auto& pm : ph.papillary) {
      lo = lo.cwiseMin(pm.centre - pm.semi_axes);
      hi = hi.cwiseMax(pm.centre + pm.semi_axes);
    }
    const Vec3 pad = Vec3::Constant(margin + o.thickness);
    const ImageGeometry grid = grid_covering(lo - pad, hi + pad, spacing);
    const double bytes = double(grid.voxel_count()) * 8;
    if (bytes > 8e9) throw InputError("valve-phantom: --spacing: expected a grid under 8 GB, found " + std::to_string(bytes / 1e9) + " GB");

    Voxelizer vox(grid);
    vox.add_sheet(ph.leaflets.points, ph.leaflets.triangles, ph.options.thickness);
    progress.update(0.5, "leaflets voxelized");
    if (chordae) {
      std::vector<std::pair<Vec3, Vec3>> segments;
      for (const auto& s : ph.chordae.segments) segments.emplace_back(ph.chordae.points[s.from].position, ph.chordae.points[s.to].position);
      vox.add_tubes(segments, ph.chordae.diameter);
      for (const auto& pm : ph.papillary) vox.add_ellipsoid(pm.centre, pm.semi_axes);
    }
    progress.update(0.8, "chordae voxelized");
    Volume volume = vox.to_volume(static_cast<float>(background), static_cast<float>(tissue));
    gaussian_blur(volume, blur);
    add_gaussian_noise(volume, noise, o.seed);

    fs::create_directories(out);
    std::string image_file = name + (format == "nrrd" ? ".nrrd" : format == "mha" ? ".mha" : format == "nii" ? ".nii.gz" : "");
    if (format == "dicom") {
      image_file = name + ".dicom";
      write_dicom_series(out / image_file, volume);
    } else {
      write_volume(out / image_file, volume);
    }
    write_mesh(out / (name + ".truth.vtp"), ph.leaflets);
    if (chordae) write_file_atomic(out / (name + ".chordae.json"), to_json(ph.chordae).dump(1) + "\n");
    progress.update(1.0, "written");

    StageSummary summary("phantom", out);
    summary.parameters() = args.used();
    summary.parameters()["kind"] = "mitral";
    summary.parameters()["chordae"] = chordae;
    const auto& v = ph.options;
    summary.metrics() = {
        {"image", image_file},
        {"truth", name + ".truth.vtp"},
        {"size", {grid.size[0], grid.size[1], grid.size[2]}},
        {"spacing_mm", spacing},
        {"origin_mm", {grid.origin.x(), grid.origin.y(), grid.origin.z()}},
        {"atrial_direction", {ph.atrial_direction.x(), ph.atrial_direction.y(), ph.atrial_direction.z()}},
        {"valve", {{"commissural_diameter_mm", v.commissural_diameter}, {"septal_lateral_diameter_mm", v.septal_lateral_diameter},
                   {"saddle_height_mm", v.saddle_height}, {"anterior_length_mm", v.anterior_length},
                   {"posterior_length_mm", v.posterior_length}, {"thickness_mm", v.thickness}}},
        {"truth_triangles", ph.leaflets.num_triangles()},
        {"chordae", {{"segments", chordae ? int(ph.chordae.segments.size()) : 0},
                     {"primary", chordae ? ph.chordae.count(ChordType::primary) : 0},
                     {"secondary", chordae ? ph.chordae.count(ChordType::secondary) : 0},
                     {"strut", chordae ? ph.chordae.count(ChordType::strut) : 0},
                     {"insertions", chordae ? ph.chordae.count(ChordPointKind::insertion) : 0}}}};
    if (chordae) summary.metrics()["chordae_file"] = name + ".chordae.json";
    summary.write();
    if (!cl.has("quiet"))
      std::printf("valve-phantom: %d x %d x %d voxels at %.3g mm -> %s\n", grid.size[0], grid.size[1], grid.size[2], spacing,
                  (out / image_file).string().c_str());
    return 0;
  });
}
