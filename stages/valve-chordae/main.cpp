// valve-chordae --mesh LEAFLETS.vtp (--from CHORDAE.json | --markups CURVE.mrk.json ... |
//               --labels LABELS.nrrd) --out DIR [--snap-tolerance 1.5] [--merge-distance 0.3]
//               [--insertion-distance 1] [--min-spur 0.75] [--convergence-clearance 5]
//               [--scale SEGMENT=FACTOR ...] [--name chordae] [--quiet]
// Puts a chordae network on a leaflet mesh (seed 5.2.2): every insertion is snapped to the
// nearest mesh node (an insertion farther than --snap-tolerance mm is an error naming the
// chord), rest lengths come from the open geometry times a per-chord scale (--scale i=f on
// segment i, e.g. 0.9 to shorten a chord by 10 % as a repair does). From Slicer markup curves
// (.mrk.json) each curve runs from a papillary tip to an insertion; chords landing on the
// free edge are primary, the others secondary, curves named "strut" struts.
// Writes DIR/chordae.json (the form valve-simulate's chordae.file reads), DIR/chordae.vtp
// (lines for ParaView) and DIR/chordae.summary.json.
// From a segmentation (valve-segment's labels.nrrd) the chordae label is thinned to curves and
// read as a graph (chordae/chordae_extraction.hpp): ends within --insertion-distance mm of
// leaflet tissue are insertions, other ends papillary tips, branches shorter than --min-spur
// mm thinning noise; a junction at least --convergence-clearance mm from leaflet tissue and
// farther from it than every vertex it joins is a tip too (chords of one muscle meeting; 0
// turns this off); chords are typed by where their insertions land, as for markups.
#include <cstdio>
#include <filesystem>

#include "valve/chordae/chordae_placement.hpp"
#include "valve/chordae/slicer_markups.hpp"
#include "valve/config/json_reader.hpp"
#include "valve/core/atomic_file.hpp"
#include "valve/core/cli.hpp"
#include "valve/core/error.hpp"
#include "valve/core/stage_arguments.hpp"
#include "valve/io/chordae_io.hpp"
#include "valve/io/image_io.hpp"
#include "valve/io/mesh_io.hpp"
#include "stage_usage.hpp"

using namespace valve;
namespace fs = std::filesystem;

int main(int argc, char** argv) {
  return run_stage("valve-chordae", kStageUsage, [&] {
    const std::vector<std::string> keys{"mesh", "from", "markups", "labels", "snap-tolerance", "merge-distance",
                                        "insertion-distance", "min-spur", "convergence-clearance", "scale", "name"};
    CommandLine cl(argc, argv, stage_flags({"out", "config"}, keys), {"quiet"});
    const fs::path out = cl.require("out");
    StageArguments args(cl, keys);
    const fs::path mesh_file = args.text("mesh", "");
    if (mesh_file.empty()) throw InputError("valve-chordae: --mesh: expected the leaflet mesh (.vtp), found nothing");
    const std::string from = args.text("from", "");
    const std::vector<std::string> markups = cl.get_all("markups");
    const std::string labels = args.text("labels", "");
    const int sources = !from.empty() + !markups.empty() + !labels.empty();
    if (sources != 1)
      throw InputError("valve-chordae: expected exactly one source, --from CHORDAE.json, --markups CURVE.mrk.json or --labels "
                       "LABELS.nrrd, found " + std::to_string(sources));
    ChordaeExtractionOptions extraction;
    extraction.insertion_distance_mm = args.length_mm("insertion-distance", extraction.insertion_distance_mm, 0, 20);
    extraction.min_spur_mm = args.length_mm("min-spur", extraction.min_spur_mm, 0, 20);
    extraction.convergence_clearance_mm = args.length_mm("convergence-clearance", extraction.convergence_clearance_mm, 0, 50);
    ChordaePlacementOptions placement;
    placement.snap_tolerance_mm = args.length_mm("snap-tolerance", placement.snap_tolerance_mm, 0, 100);
    const double merge = args.length_mm("merge-distance", 0.3, 0, 10);
    const std::string name = args.text("name", "chordae");

    const TriMesh mesh = read_mesh(mesh_file);
    ChordaeNetwork net;
    ChordaeExtractionSummary extracted;
    const std::string source = !from.empty() ? from : !labels.empty() ? labels : markups.front();
    if (!from.empty()) {
      net = read_chordae_json(load_json_file(from), from);
      for (ChordPoint& p : net.points) p.mesh_node = -1;  // snapped to this mesh, whatever they were
    } else if (!labels.empty()) {
      net = chordae_from_labels(read_label_map(labels), extraction, labels, &extracted);
    } else {
      net = read_slicer_curves(std::vector<fs::path>(markups.begin(), markups.end()), merge);
    }
    placement.type_by_insertion = from.empty();
    placement.segment_scales = cl.get_all("scale");
    net = place_chordae(std::move(net), mesh, placement, source);

    fs::create_directories(out);
    write_file_atomic(out / (name + ".json"), to_json(net).dump(1) + "\n");
    write_chordae_vtp(out / (name + ".vtp"), net);
    StageSummary summary("chordae", out);
    summary.add_input("mesh", mesh_file);
    summary.add_input("source", source);
    for (std::size_t k = 1; k < markups.size(); ++k) summary.add_input("markups_" + std::to_string(k), markups[k]);
    summary.parameters() = args.used();
    summary.parameters()["scale"] = cl.get_all("scale");
    summary.metrics() = chordae_metrics(net);
    if (!labels.empty()) summary.metrics()["extraction"] = to_json(extracted);
    summary.write();
    if (!cl.has("quiet"))
      std::printf("valve-chordae: %zu segments (%d primary, %d secondary, %d strut), %d insertions on %s -> %s\n",
                  net.segments.size(), net.count(ChordType::primary), net.count(ChordType::secondary), net.count(ChordType::strut),
                  net.count(ChordPointKind::insertion), mesh_file.string().c_str(), (out / (name + ".json")).string().c_str());
    return 0;
  });
}
