// valve-segment IMAGE --out DIR [--config FILE.json] [--name labels]
//               [--crop-min x,y,z --crop-max x,y,z] [--denoise gaussian|median|none]
//               [--gaussian-sigma 0.15] [--median-radius 1] [--diffusion-iterations 0]
//               [--threshold otsu|VALUE] [--seed x,y,z ...] [--closing-radius 0.2]
//               [--chordae-method opening|hessian] [--chordae-opening-radius 0.3]
//               [--tube-scale 0.25] [--tube-ratio 0.5] [--tube-ridge-offset 0.35] [--sheet-ratio 0.1] [--tube-growth 2]
//               [--notch-closing-radius 0.75] [--min-component 0.5] [--max-memory GB] [--quiet]
// IMAGE: .nrrd .nhdr .mha .mhd .nii .nii.gz or a DICOM series directory. Writes the label
// map DIR/NAME.nrrd (1 leaflet, 2 chordae, 3 other tissue), the same labels as a 3D Slicer
// segmentation with named, coloured segments (DIR/NAME.seg.nrrd), and segment.summary.json
// with the threshold used, voxel counts and components. Chordae are told from leaflets by a
// morphological opening (chords thinner than leaflets) or by the Hessian's shape measure
// (tubes vs sheets; for chords as thick as the leaflets). Physical coordinates (LPS, mm) throughout.
#include <cstdio>
#include <filesystem>
#include <string>

#include "valve/core/cli.hpp"
#include "valve/core/error.hpp"
#include "valve/core/progress.hpp"
#include "valve/core/stage_arguments.hpp"
#include "valve/core/system_memory.hpp"
#include "valve/imaging/segmentation_report.hpp"
#include "valve/io/image_io.hpp"
#include "stage_usage.hpp"

using namespace valve;
namespace fs = std::filesystem;

int main(int argc, char** argv) {
  return run_stage("valve-segment", kStageUsage, [&] {
    const std::vector<std::string> keys = {"name", "crop_min", "crop_max", "denoise", "gaussian_sigma", "median_radius",
                                           "diffusion_iterations", "threshold", "seed", "closing_radius",
                                           "chordae_method", "chordae_opening_radius", "tube_scale", "tube_ratio", "tube_ridge_offset", "sheet_ratio",
                                           "tube_growth", "notch_closing_radius",
                                           "min_component", "max_memory"};
    CommandLine cl(argc, argv, stage_flags({"out", "config"}, keys), {"quiet"});
    if (cl.positional().size() != 1)
      throw InputError("valve-segment: IMAGE: expected one image file or DICOM directory, found " +
                       std::to_string(cl.positional().size()) + " arguments");
    const fs::path image_file = cl.positional()[0];
    const fs::path out = cl.require("out");
    StageArguments args(cl, keys);
    SegmentationOptions o;
    const std::string name = args.text("name", "labels");
    const auto crop_min = args.vector3("crop-min"), crop_max = args.vector3("crop-max");
    if (bool(crop_min) != bool(crop_max))
      throw InputError("valve-segment: --crop-min/--crop-max: expected both corners of the box, found one");
    if (crop_min) o.crop = true, o.crop_lo = *crop_min, o.crop_hi = *crop_max;
    o.denoise = args.choice("denoise", o.denoise, {"none", "gaussian", "median"});
    o.gaussian_sigma = args.length_mm("gaussian-sigma", o.gaussian_sigma, 0, 10);
    o.median_radius = static_cast<int>(args.integer("median-radius", o.median_radius, 0, 10));
    o.diffusion_iterations = static_cast<int>(args.integer("diffusion-iterations", 0, 0, 1000));
    const std::string threshold = args.text("threshold", "otsu");
    if (threshold != "otsu") {
      o.threshold_method = "explicit";
      o.threshold = args.number("threshold", 0, -1e30, 1e30);
    }
    o.seeds = args.points("seed");
    o.closing_radius = args.length_mm("closing-radius", o.closing_radius, 0, 20);
    o.chordae_method = args.choice("chordae-method", o.chordae_method, {"opening", "hessian"});
    o.chordae_opening_radius = args.length_mm("chordae-opening-radius", o.chordae_opening_radius, 0, 20);
    o.tube_scale = args.length_mm("tube-scale", o.tube_scale, 0.01, 20);
    o.tube_ratio = args.number("tube-ratio", o.tube_ratio, 0.01, 1);
    o.tube_ridge_offset = args.length_mm("tube-ridge-offset", o.tube_ridge_offset, 0, 20);
    o.sheet_ratio = args.number("sheet-ratio", o.sheet_ratio, 0, 1);
    o.tube_growth_voxels = static_cast<int>(args.integer("tube-growth", o.tube_growth_voxels, 0, 10));
    o.notch_closing_radius = args.length_mm("notch-closing-radius", o.notch_closing_radius, 0, 20);
    o.min_component_mm3 = args.number("min-component", o.min_component_mm3, 0, 1e9);
    ImageReadOptions read;
    // Half the available memory by default (0: unknown, no limit).
    read.max_bytes = args.number("max-memory", available_memory_bytes() / 2 / 1e9, 0.001, 1e6) * 1e9;
    read.working_copies = segmentation_working_copies(o);
    o.validate("valve-segment");

    Progress progress("valve-segment", cl.has("quiet"));
    const Volume volume = read_volume(image_file, read);
    progress.update(0.2, "image read");
    SegmentationSummary s;
    const LabelMap labels = segment_valve(volume, o, &s);
    progress.update(0.9, "segmented");
    fs::create_directories(out);
    write_label_map(out / (name + ".nrrd"), labels);
    write_slicer_segmentation(out / (name + ".seg.nrrd"), labels,
                              {{label_leaflet, "leaflet", Vec3(0.94, 0.82, 0.55)},
                               {label_chordae, "chordae", Vec3(0.85, 0.25, 0.25)},
                               {label_other_tissue, "other tissue", Vec3(0.55, 0.55, 0.60)}});

    StageSummary summary("segment", out);
    summary.add_input("image", image_file);
    summary.parameters() = args.used();
    summary.metrics() = segmentation_metrics(s, o, name);
    const nlohmann::json volume_mm3 = summary.metrics()["volume_mm3"];
    summary.write();
    progress.finish("labels written");
    if (!cl.has("quiet"))
      std::printf("valve-segment: threshold %.4g, leaflet %.1f mm3, chordae %.1f mm3 in %d pieces -> %s\n", s.threshold,
                  volume_mm3["leaflet"].get<double>(), volume_mm3["chordae"].get<double>(), s.chordae_pieces,
                  (out / (name + ".nrrd")).string().c_str());
    return 0;
  });
}
