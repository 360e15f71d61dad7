// valve-segment's memory estimate and summary metrics.
#include <catch2/catch.hpp>

#include "valve/imaging/segmentation_report.hpp"

using namespace valve;

TEST_CASE("segmentation report: working copies by method, volumes from voxel counts", "[imaging][segmentation]") {
  SegmentationOptions o;
  CHECK(segmentation_working_copies(o) == 6);
  o.chordae_method = "hessian";
  CHECK(segmentation_working_copies(o) == 18);

  SegmentationSummary s;
  s.cropped.size = {10, 20, 30};
  s.cropped.spacing = Vec3(0.1, 0.2, 0.5);  // 0.01 mm³ voxels
  s.voxels_leaflet = 1000, s.voxels_chordae = 50, s.voxels_other = 7, s.voxels_tissue = 1057;
  s.chordae_pieces = 3;
  const nlohmann::json m = segmentation_metrics(s, o, "labels");
  CHECK(m["labels"] == "labels.nrrd");
  CHECK(m["slicer_segmentation"] == "labels.seg.nrrd");
  CHECK(m["size"] == nlohmann::json{10, 20, 30});
  CHECK(m["volume_mm3"]["leaflet"].get<double>() == Approx(10));
  CHECK(m["volume_mm3"]["chordae"].get<double>() == Approx(0.5));
  CHECK(m["volume_mm3"]["other"].get<double>() == Approx(0.07));
  CHECK(m["voxels"]["tissue"] == 1057);
  CHECK(m["chordae_method"] == "hessian");
  CHECK(m["threshold_method"] == "otsu");
  CHECK(m["chordae_pieces"] == 3);
}
