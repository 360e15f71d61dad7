// Chordae told from leaflets by shape (segmentation "hessian" method): a sheet and tubes of
// the same 0.65 mm thickness, as in the Texas TriValve deck, where a morphological opening
// cannot tell them apart. Volumes are checked against the analytic ones of the voxelized
// objects; the tubes touch the sheet the way chords insert into a leaflet.
#include <catch2/catch.hpp>
#include <cmath>

#include "valve/imaging/segmentation.hpp"
#include "valve/imaging/voxelize.hpp"

using namespace valve;

namespace {
constexpr double pi = 3.14159265358979323846;
constexpr double thickness = 0.65;  // mm, leaflet and chord alike

struct LabelledVolumes {
  double leaflet = 0, chordae = 0, other = 0;
};

LabelledVolumes volumes(const LabelMap& m) {
  LabelledVolumes v;
  const double voxel = m.geometry.spacing.prod();
  for (std::uint8_t l : m.labels) {
    if (l == label_leaflet) v.leaflet += voxel;
    else if (l == label_chordae) v.chordae += voxel;
    else if (l == label_other_tissue) v.other += voxel;
  }
  return v;
}

std::uint8_t label_at(const LabelMap& m, const Vec3& p) {
  const Vec3 ci = m.geometry.continuous_index(p);
  return m.labels[m.geometry.linear_index(int(std::lround(ci.x())), int(std::lround(ci.y())), int(std::lround(ci.z())))];
}
}  // namespace

TEST_CASE("the Hessian method separates chords as thick as the leaflet", "[imaging][segmentation]") {
  // A 12 × 12 mm sheet in z = 0 (slightly tilted so that it cuts voxels obliquely) and three
  // 8 mm chords hanging from its underside: one straight down, two slanted.
  const double tilt = 0.1;
  MatX3 p(4, 3);
  p << 0, 0, 0, 12, 0, 12 * tilt, 12, 12, 12 * tilt, 0, 12, 0;
  const std::vector<Tri> tris{{0, 1, 2}, {0, 2, 3}};
  auto sheet_z = [&](double x) { return tilt * x; };
  const std::vector<std::pair<Vec3, Vec3>> chords{
      {Vec3(6, 6, sheet_z(6)), Vec3(6, 6, sheet_z(6) - 8)},
      {Vec3(3, 4, sheet_z(3)), Vec3(3 - 4, 4, sheet_z(3) - 6.9)},
      {Vec3(9, 8, sheet_z(9)), Vec3(9 + 3, 8 + 3, sheet_z(9) - 6.7)}};
  Voxelizer voxels(grid_covering(Vec3(-3, -1, -10), Vec3(14, 13, 3), 0.25));
  voxels.add_sheet(p, tris, thickness);
  voxels.add_tubes(chords, thickness);
  Volume volume = voxels.to_volume(0, 1000);
  add_gaussian_noise(volume, 50, 7);

  const double sheet_volume = 12 * std::sqrt(1 + tilt * tilt) * 12 * thickness;  // 94.0 mm³
  // Below the sheet each chord is a cylinder of 8 mm minus the half thickness it spends in the
  // sheet, plus its end cap's half sphere.
  const double radius = thickness / 2;
  const double chord_volume = 3 * (pi * radius * radius * (8 - radius) + 2.0 / 3 * pi * radius * radius * radius);

  SegmentationOptions o;
  o.chordae_method = "hessian";
  SegmentationSummary s;
  const LabelMap labels = segment_valve(volume, o, &s);
  const LabelledVolumes v = volumes(labels);
  INFO("leaflet " << v.leaflet << " mm3 (sheet " << sheet_volume << "), chordae " << v.chordae << " mm3 (chords "
                  << chord_volume << "), other " << v.other);
  CHECK(s.chordae_separated);
  CHECK(s.leaflet_components == 1);
  // Thresholding thickens both alike (Otsu on the blurred image, then the closing), so the
  // shares of the tissue are compared: the sheet, rim included, stays leaflet but for the
  // notches the chords leave at their insertions; most of each chord is found.
  const double tissue = s.voxels_tissue * volume.geometry.spacing.prod();
  const double sheet_share = sheet_volume / (sheet_volume + chord_volume);  // 0.923
  CHECK(v.leaflet / tissue == Approx(sheet_share).margin(0.03));
  CHECK(v.chordae / tissue > 0.7 * (1 - sheet_share));
  CHECK(v.chordae / tissue < 1.3 * (1 - sheet_share));
  CHECK(v.other == 0);
  CHECK(s.chordae_pieces == 3);
  CHECK(label_at(labels, Vec3(6, 6, sheet_z(6) - 4)) == label_chordae);
  CHECK(label_at(labels, Vec3(1, 10, sheet_z(1))) == label_leaflet);
  CHECK(label_at(labels, Vec3(11.5, 0.5, sheet_z(11.5))) == label_leaflet);
}

TEST_CASE("the Hessian method's options are checked", "[imaging][segmentation]") {
  SegmentationOptions o;
  o.chordae_method = "frangi";
  CHECK_THROWS_WITH(o.validate("test"), Catch::Contains("chordae_method"));
  o.chordae_method = "hessian";
  o.tube_ratio = 0;
  CHECK_THROWS_WITH(o.validate("test"), Catch::Contains("tube_ratio"));
  o.tube_ratio = 0.5;
  o.sheet_ratio = 0.6;
  CHECK_THROWS_WITH(o.validate("test"), Catch::Contains("sheet_ratio"));
}
