// Chordae from a label map made by hand: a leaflet slab above, a papillary block below, and a
// chord that rises from the papillary block and splits into two branches that reach the
// slab. Every expected figure follows from the drawing.
#include <catch2/catch.hpp>
#include <cmath>

#include "valve/chordae/chordae_extraction.hpp"
#include "valve/core/error.hpp"

using namespace valve;

namespace {

// Labels every background voxel whose centre (mm) is `inside`.
template <class Inside>
void paint(LabelMap& m, const Inside& inside, std::uint8_t label) {
  const ImageGeometry& g = m.geometry;
  for (int k = 0; k < g.size[2]; ++k)
    for (int j = 0; j < g.size[1]; ++j)
      for (int i = 0; i < g.size[0]; ++i)
        if (m.labels[g.linear_index(i, j, k)] == label_background && inside(g.physical_point(Vec3(i, j, k))))
          m.labels[g.linear_index(i, j, k)] = label;
}

void paint_tube(LabelMap& m, const Vec3& a, const Vec3& b, double radius, std::uint8_t label) {
  paint(m, [&](const Vec3& p) {
    const Vec3 d = b - a;
    const double t = std::clamp((p - a).dot(d) / d.squaredNorm(), 0.0, 1.0);
    return (a + t * d - p).norm() <= radius;
  }, label);
}

// 0.2 mm voxels over 12 × 6 × 16 mm; leaflet slab z in [14, 15] mm, papillary block z in [0, 2] mm.
LabelMap drawing() {
  LabelMap m;
  m.geometry.size = {60, 30, 80};
  m.geometry.spacing = Vec3::Constant(0.2);
  m.labels.assign(m.geometry.voxel_count(), label_background);
  const ImageGeometry& g = m.geometry;
  for (int k = 0; k < g.size[2]; ++k)
    for (int j = 0; j < g.size[1]; ++j)
      for (int i = 0; i < g.size[0]; ++i) {
        const double z = k * 0.2;
        if (z >= 14 && z <= 15) m.labels[g.linear_index(i, j, k)] = label_leaflet;
        if (z <= 2 && i * 0.2 >= 4 && i * 0.2 <= 8) m.labels[g.linear_index(i, j, k)] = label_other_tissue;
      }
  // Trunk from the papillary block to a branch point at (6, 3, 8), two branches to the slab;
  // the segmentation's opening leaves each chord ~0.4 mm short of the tissue it joins.
  paint_tube(m, Vec3(6, 3, 2.4), Vec3(6, 3, 8), 0.35, label_chordae);
  paint_tube(m, Vec3(6, 3, 8), Vec3(2.5, 3, 13.6), 0.35, label_chordae);
  paint_tube(m, Vec3(6, 3, 8), Vec3(9.5, 3, 13.6), 0.35, label_chordae);
  return m;
}

}  // namespace

TEST_CASE("chordae from labels: a branching chord between papillary tissue and a leaflet", "[chordae][extraction]") {
  ChordaeExtractionSummary s;
  const ChordaeNetwork net = chordae_from_labels(drawing(), {}, "labels.nrrd", &s);
  CHECK(s.insertions == 2);
  CHECK(s.papillary_tips == 1);
  CHECK(s.tips_on_other_tissue == 1);
  CHECK(s.components_dropped == 0);
  REQUIRE(net.segments.size() == 3);
  REQUIRE(net.count(ChordPointKind::branch) == 1);
  for (const ChordPoint& p : net.points) {
    if (p.kind == ChordPointKind::branch) CHECK((p.position - Vec3(6, 3, 8)).norm() < 0.6);
    if (p.kind == ChordPointKind::papillary_tip) CHECK((p.position - Vec3(6, 3, 2.4)).norm() < 0.6);
    if (p.kind == ChordPointKind::insertion) CHECK(p.position.z() > 13.0);
  }
  // Drawn lengths: trunk 5.6 mm, branches |(3.5, 0, 5.6)| = 6.6 mm each; thinning may shorten
  // each end by up to a chord radius.
  CHECK(s.total_length_mm == Approx(5.6 + 2 * std::hypot(3.5, 5.6)).margin(1.2));
  // Segments run from the tip side toward the insertions.
  for (const ChordSegment& seg : net.segments) CHECK(net.points[seg.to].kind != ChordPointKind::papillary_tip);
}

TEST_CASE("chordae from labels: no chordae, or none reaching a leaflet, is an error naming the file", "[chordae][extraction]") {
  LabelMap empty = drawing();
  for (auto& l : empty.labels)
    if (l == label_chordae) l = label_background;
  CHECK_THROWS_WITH(chordae_from_labels(empty, {}, "labels.nrrd"), Catch::Contains("labels.nrrd") && Catch::Contains("chordae"));
  LabelMap floating = drawing();
  for (auto& l : floating.labels)
    if (l == label_leaflet) l = label_background;
  CHECK_THROWS_AS(chordae_from_labels(floating, {}, "labels.nrrd"), InputError);
}

TEST_CASE("chordae from labels: chords meeting below the leaflet without a muscle are tethered where they meet", "[chordae][extraction]") {
  // Three chords rise from one point 10 mm below the slab, with no papillary tissue. Thinning
  // leaves a 1 mm stub below their meeting; the many chords of a scanned muscle leave none,
  // which pruning spurs up to 1.5 mm reproduces. The meeting point is then a junction without
  // an end, farther from the leaflet than the insertions it joins, so it is the tip.
  LabelMap m = drawing();
  for (auto& l : m.labels)
    if (l == label_chordae || l == label_other_tissue) l = label_background;
  const Vec3 meeting(6, 3, 4);
  for (const Vec3& end : {Vec3(2.5, 1.5, 13.6), Vec3(9.5, 1.5, 13.6), Vec3(6, 4.5, 13.6)}) paint_tube(m, meeting, end, 0.35, label_chordae);
  ChordaeExtractionOptions options;
  options.min_spur_mm = 1.5;
  ChordaeExtractionSummary s;
  const ChordaeNetwork net = chordae_from_labels(m, options, "labels.nrrd", &s);
  CHECK(s.convergence_tips == 1);
  CHECK(s.papillary_tips == 1);
  CHECK(s.insertions == 3);
  REQUIRE(net.segments.size() == 3);
  // The tubes overlap for about a millimetre above the point where their axes meet.
  for (const ChordPoint& p : net.points)
    if (p.kind == ChordPointKind::papillary_tip) CHECK((p.position - meeting).norm() < 1.0);
  for (const ChordSegment& seg : net.segments) CHECK(net.points[seg.from].kind == ChordPointKind::papillary_tip);

  // The meeting point is 9.6 mm from the slab: a clearance above that, or 0, finds no tip, and
  // chords that join leaflet to leaflet only are refused.
  ChordaeExtractionOptions strict = options;
  strict.convergence_clearance_mm = 10;
  CHECK_THROWS_AS(chordae_from_labels(m, strict, "labels.nrrd"), InputError);
  strict.convergence_clearance_mm = 0;
  CHECK_THROWS_AS(chordae_from_labels(m, strict, "labels.nrrd"), InputError);
}

TEST_CASE("chordae from labels: a branch point is not a tip because the open leaflet hangs near its muscle", "[chordae][extraction]") {
  // The drawing's chord, with a piece of leaflet hanging 1.5 mm beside its papillary end: the
  // branch point at (6, 3, 8) is then farther from leaflet tissue (4.7 mm) than the tip end and
  // both insertions, but it is joined to that tip end, so it stays a branch.
  LabelMap m = drawing();
  paint(m, [](const Vec3& p) { return p.x() >= 7.5 && p.x() <= 8 && p.z() >= 2.6 && p.z() <= 3.4; }, label_leaflet);
  ChordaeExtractionOptions options;
  options.convergence_clearance_mm = 4;
  ChordaeExtractionSummary s;
  const ChordaeNetwork net = chordae_from_labels(m, options, "labels.nrrd", &s);
  CHECK(s.convergence_tips == 0);
  CHECK(s.papillary_tips == 1);
  CHECK(net.count(ChordPointKind::branch) == 1);
}
