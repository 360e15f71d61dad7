// Coaptation analysis (seed 4.2.5) on hand-built parallel sheets whose overlap is known.
//
// Fixture: leaflet 0 is the sheet [0, 10] x [0, 10] (20 x 20 cells of 0.5 mm) in z = 0;
// leaflet 1 is the sheet [0.25, 9.75] x [6.75, 10] (19 x 13 cells of 0.5 x 0.25 mm) in z = s,
// wound the same way (normal +z), so that leaflet 0 is seen along +n and leaflet 1 along −n.
// Both free edges are the top row y = 10. The top row of each
// sheet is bent 0.05 mm towards the other sheet ("lips"), so that the rays from the free-edge
// nodes tilt away from the other sheet's free edge and land 0.02-0.04 mm inside it instead of
// exactly on its border, where a rotated copy could hit or miss by rounding. Every other
// overlap border lies half a cell (0.25 mm) from the nodes of the sheet that casts the rays.
#include <catch2/catch.hpp>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <string>

#include "valve/analysis/coaptation.hpp"
#include "valve/core/error.hpp"

using namespace valve;

namespace {

constexpr double kLip = 0.05;  // mm, the bend of each free-edge row towards the other sheet

struct Sheet {
  double x0, x1, y0, y1;
  int nx, ny;
  double z, lip_dz;  // plane height; z offset of the top row
  int leaflet;
  bool flip;  // wind with normal −z
};

// Structured sheet; top row = free edge (its two corners attached), rest of the border attached.
void add_sheet(TriMesh& m, const Sheet& s) {
  const int base = m.num_nodes();
  const int cols = s.nx + 1, rows = s.ny + 1;
  m.points.conservativeResize(base + cols * rows, 3);
  for (int j = 0; j < rows; ++j)
    for (int i = 0; i < cols; ++i) {
      const int v = base + j * cols + i;
      m.points.row(v) << s.x0 + (s.x1 - s.x0) * i / s.nx, s.y0 + (s.y1 - s.y0) * j / s.ny,
          s.z + (j == s.ny ? s.lip_dz : 0.0);
      const bool border = i == 0 || i == s.nx || j == 0 || j == s.ny;
      const bool free = j == s.ny && i > 0 && i < s.nx;
      m.boundary.push_back(free ? BoundaryType::free_edge : border ? BoundaryType::attached : BoundaryType::interior);
    }
  for (int j = 0; j < s.ny; ++j)
    for (int i = 0; i < s.nx; ++i) {
      const int a = base + j * cols + i, b = a + 1, c = a + cols + 1, d = a + cols;
      for (Tri t : {Tri(a, b, c), Tri(a, c, d)}) {
        if (s.flip) std::swap(t[1], t[2]);
        m.triangles.push_back(t);
        m.leaflet.push_back(s.leaflet);
      }
    }
}

Sheet lower_sheet() { return {0, 10, 0, 10, 20, 20, 0.0, kLip, 0, false}; }
Sheet upper_sheet(double separation, double x0 = 0.25, double x1 = 9.75, int leaflet = 1, bool flip = false) {
  return {x0, x1, 6.75, 10, static_cast<int>(std::lround((x1 - x0) / 0.5)), 13, separation, -kLip, leaflet, flip};
}

TriMesh overlap_pair(double separation) {
  TriMesh m;
  add_sheet(m, lower_sheet());
  add_sheet(m, upper_sheet(separation));
  m.fill_defaults();
  return m;
}

// Node of the lower sheet (leaflet 0) at grid (i, j); the upper sheet's nodes follow its 21 x 21.
int lower(int i, int j) { return j * 21 + i; }
int upper(int i, int j) { return 21 * 21 + j * 20 + i; }

void rigid_motion(TriMesh& m, const Mat3& R, const Vec3& t) {
  for (int i = 0; i < m.num_nodes(); ++i) m.points.row(i) = (R * m.points.row(i).transpose() + t).transpose();
}

// h of every sampled column of `l` whose rest arc length lies in [from, to] (mm). The lower
// sheet's free edge runs from x = 10 to x = 0 (arc length 10 - x); the ranges below are
// symmetric and keep to whole cells, where the interpolant's border is the grid row's.
void check_columns(const LeafletCoaptation& l, double from, double to, double height) {
  int checked = 0;
  for (std::size_t k = 0; k < l.column_arc_mm.size(); ++k)
    if (l.column_arc_mm[k] >= from && l.column_arc_mm[k] <= to) {
      INFO("column at " << l.column_arc_mm[k] << " mm");
      CHECK(l.column_height_mm[k] == Approx(height).margin(1e-9));
      ++checked;
    }
  CHECK(checked > 0);
}

// Expected numbers for the pair at separation 0.3 mm, derived from the geometry.
void check_overlap_pair(const CoaptationResult& r) {
  REQUIRE(r.leaflets.size() == 2);
  const LeafletCoaptation& l0 = r.leaflets[0];
  const LeafletCoaptation& l1 = r.leaflets[1];
  CHECK(l0.leaflet == 0);
  CHECK(l1.leaflet == 1);

  // Leaflet 0 coapts at the nodes over the upper sheet: columns x = 0.5..9.5, rows y = 7..10.
  for (int j = 0; j <= 20; ++j)
    for (int i = 0; i <= 20; ++i) {
      INFO("lower node " << i << ", " << j);
      CHECK(r.coapting[lower(i, j)] == (i >= 1 && i <= 19 && j >= 14 ? 1 : 0));
    }
  // ... and the upper sheet coapts everywhere (it lies wholly over the lower one).
  for (int v = upper(0, 0); v <= upper(19, 13); ++v) CHECK(r.coapting[v] == 1);
  // Flat part: the rays run along ±z, the gap is the separation.
  CHECK(r.gap_mm[lower(10, 16)] == Approx(0.3).margin(1e-9));
  CHECK(r.gap_mm[upper(10, 5)] == Approx(0.3).margin(1e-9));
  CHECK(r.gap_mm[lower(10, 4)] == kCoaptationNoHit);  // y = 2: nothing above or below

  // Area: overlap 9.5 x 3.25 mm. The overlap borders lie half a cell from the nodes, where the
  // interpolated indicator integrates exactly over the border strips; the two corner cells
  // of the lower sheet are off by at most h²/12 each (h = 0.5), and the lip strip is tilted
  // (area factor sqrt(1 + (0.05/0.5)²), +0.024 mm²): tolerance 0.1 mm².
  CHECK(l0.area_mm2 == Approx(9.5 * 3.25).margin(0.1));
  // The upper sheet coapts wholly: its area, 9.5 x (3 + lip row length).
  const double upper_depth = 3.0 + std::hypot(0.25, kLip);
  CHECK(l1.area_mm2 == Approx(9.5 * upper_depth).epsilon(1e-9));

  // Heights down the columns (x = const): lower sheet, the lip row sqrt(0.5² + 0.05²), then
  // down to y = 6.75, where the indicator passes 0.5 between the coapting row y = 7 and the
  // row y = 6.5 (the overlap's own border); upper sheet, its full depth. The lower sheet's
  // columns within 0.25 mm of its sides begin where the indicator, between a corner (0) and
  // the next free-edge node (1), is below 0.5: no band. (Between 0.25 and 0.5 mm from a side
  // the band's lower end depends on which way the cells' diagonals run.)
  const double lower_height = 2.75 + std::hypot(0.5, kLip);
  REQUIRE(l0.free_edge.size() == 21);
  REQUIRE(l1.free_edge.size() == 20);
  REQUIRE(l0.column_arc_mm.size() == l0.column_height_mm.size());
  check_columns(l0, 0.5, 9.5, lower_height);
  check_columns(l0, 0, 0.24, 0.0);
  check_columns(l0, 9.76, 10, 0.0);
  check_columns(l1, 0, 9.5, upper_depth);
  CHECK(l0.middle_node == lower(10, 20));
  CHECK(l0.midline_height_mm == Approx(lower_height).margin(1e-9));
  CHECK(l0.min_height_mm == Approx(lower_height).margin(1e-9));  // the corners lie in the 1 mm margins
  CHECK(l1.midline_height_mm == Approx(upper_depth).margin(1e-9));
  CHECK(l1.min_height_mm == Approx(upper_depth).margin(1e-9));
  CHECK(r.min_height_mm == Approx(std::min(lower_height, upper_depth)).margin(1e-9));  // the valve's: the lesser
  CHECK(l0.coapting_fraction_of_free_edge == Approx(0.9));  // x in [0.5, 9.5] of [0, 10]
  CHECK(l1.coapting_fraction_of_free_edge == Approx(1.0));
  CHECK(l0.closed);
  CHECK(l1.closed);
  CHECK(r.closed);
  CHECK_FALSE(r.central_gap);
}

}  // namespace

TEST_CASE("coaptation: sheets 0.3 mm apart coapt over their overlap", "[analysis][coaptation]") {
  const TriMesh m = overlap_pair(0.3);
  const CoaptationResult r = analyze_coaptation(m, flatten(m.points));
  check_overlap_pair(r);
  for (double g : r.gap_mm) CHECK(std::isfinite(g));
  CHECK_FALSE(r.report().empty());
  // One CSV row per sampled column; the midline column of leaflet 0 (arc 5 mm) among them.
  const std::string csv = coaptation_columns_csv(r);
  CHECK(csv.rfind("leaflet,arc_mm,height_mm,band_top_mm\n", 0) == 0);
  CHECK(static_cast<std::size_t>(std::count(csv.begin(), csv.end(), '\n')) ==
        1 + r.leaflets[0].column_arc_mm.size() + r.leaflets[1].column_arc_mm.size());
  // The midline column of leaflet 0, parsed back: arc 5 mm, the lower sheet's height, top 0.
  const std::size_t row = csv.find("\n0,5,");
  REQUIRE(row != std::string::npos);
  const std::string fields = csv.substr(row + 5, csv.find('\n', row + 1) - row - 5);
  CHECK(std::stod(fields.substr(0, fields.find(','))) == Approx(2.75 + std::hypot(0.5, kLip)).margin(1e-8));
  CHECK(std::stod(fields.substr(fields.find(',') + 1)) == 0);
}

TEST_CASE("coaptation: same numbers after a rigid motion", "[analysis][coaptation]") {
  TriMesh m = overlap_pair(0.3);
  const CoaptationResult ref = analyze_coaptation(m, flatten(m.points));
  const Mat3 R = Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()).toRotationMatrix() *
                 Eigen::AngleAxisd(-1.9, Vec3(0.3, -1, 0.2).normalized()).toRotationMatrix();
  rigid_motion(m, R, Vec3(12.5, -40, 7.25));
  const CoaptationResult r = analyze_coaptation(m, flatten(m.points));
  check_overlap_pair(r);
  REQUIRE(r.gap_mm.size() == ref.gap_mm.size());
  for (size_t i = 0; i < r.gap_mm.size(); ++i) {
    CHECK(r.gap_mm[i] == Approx(ref.gap_mm[i]).margin(1e-9));
    CHECK(r.coapting[i] == ref.coapting[i]);
  }
  for (size_t l = 0; l < 2; ++l) {
    CHECK(r.leaflets[l].area_mm2 == Approx(ref.leaflets[l].area_mm2).epsilon(1e-12));
    CHECK(r.leaflets[l].min_height_mm == Approx(ref.leaflets[l].min_height_mm).epsilon(1e-12));
  }
}

TEST_CASE("coaptation: sheets 0.8 mm apart do not coapt", "[analysis][coaptation]") {
  const TriMesh m = overlap_pair(0.8);
  const CoaptationResult r = analyze_coaptation(m, flatten(m.points));
  for (int c : r.coapting) CHECK(c == 0);
  CHECK(r.gap_mm[lower(10, 16)] == Approx(0.8).margin(1e-9));  // seen, but beyond 0.5 mm
  CHECK(r.gap_mm[upper(10, 5)] == Approx(0.8).margin(1e-9));
  for (const auto& l : r.leaflets) {
    CHECK(l.area_mm2 == 0);
    CHECK(l.midline_height_mm == 0);
    CHECK(l.min_height_mm == 0);
    CHECK(l.coapting_fraction_of_free_edge == 0);
    CHECK_FALSE(l.closed);
  }
  CHECK_FALSE(r.closed);
  CHECK(r.central_gap);
  // A larger threshold makes the same flat overlap coapt again.
  CoaptationOptions wide;
  wide.threshold_mm = 0.85;
  CHECK(analyze_coaptation(m, flatten(m.points), wide).closed);
}

TEST_CASE("coaptation: a neighbour too narrow leaves a central gap", "[analysis][coaptation]") {
  // Two narrow leaflets over x in [0.25, 3.75] and [6.25, 9.75]: the middle of leaflet 0's
  // free edge (x = 4..6) has nothing to meet. Leaflet 2 is wound the other way (normal −z).
  TriMesh m;
  add_sheet(m, lower_sheet());
  add_sheet(m, upper_sheet(0.3, 0.25, 3.75, 1));
  add_sheet(m, upper_sheet(0.3, 6.25, 9.75, 2, true));
  m.fill_defaults();
  const CoaptationResult r = analyze_coaptation(m, flatten(m.points));
  REQUIRE(r.leaflets.size() == 3);
  const LeafletCoaptation& l0 = r.leaflets[0];
  const double lower_height = 2.75 + std::hypot(0.5, kLip);
  for (int i = 0; i <= 20; ++i) {
    const bool covered = (i >= 1 && i <= 7) || (i >= 13 && i <= 19);
    INFO("free-edge node " << i);
    CHECK(r.coapting[lower(i, 20)] == (covered ? 1 : 0));
  }
  // Full bands over the covered cells (x in [0.5, 3.5] and [6.5, 9.5]), none over the bare
  // ones (x in [4, 6]).
  check_columns(l0, 0.5, 3.5, lower_height);
  check_columns(l0, 4.0, 6.0, 0.0);
  check_columns(l0, 6.5, 9.5, lower_height);
  CHECK(l0.midline_height_mm == 0);
  CHECK(l0.min_height_mm == 0);
  CHECK(l0.coapting_fraction_of_free_edge == Approx(0.6));  // [0.5, 3.5] and [6.5, 9.5]
  CHECK_FALSE(l0.closed);
  CHECK(r.leaflets[1].closed);
  CHECK(r.leaflets[2].closed);
  CHECK(r.central_gap);
  CHECK_FALSE(r.closed);
}

TEST_CASE("coaptation: contact not connected to the free edge adds area but no height", "[analysis][coaptation]") {
  // A third leaflet touches leaflet 0 lower down, over [0.25, 9.75] x [1.25, 3.75]
  // (a belly contact); rows y = 4..6.5 of leaflet 0 do not coapt and separate it from the strip.
  TriMesh m;
  add_sheet(m, lower_sheet());
  add_sheet(m, upper_sheet(0.3));
  add_sheet(m, {0.25, 9.75, 1.25, 3.75, 19, 10, 0.3, 0.0, 2, false});
  m.fill_defaults();
  const CoaptationResult r = analyze_coaptation(m, flatten(m.points));
  for (int i = 1; i <= 19; ++i) {
    CHECK(r.coapting[lower(i, 5)] == 1);  // y = 2.5, in the lower patch
    CHECK(r.coapting[lower(i, 10)] == 0);  // y = 5, between the patches
  }
  const LeafletCoaptation& l0 = r.leaflets[0];
  // Heights as without the patch (its nodes are 6.5-8.5 mm from the free edge).
  CHECK(l0.min_height_mm == Approx(2.75 + std::hypot(0.5, kLip)).margin(1e-9));
  CHECK(l0.midline_height_mm == Approx(2.75 + std::hypot(0.5, kLip)).margin(1e-9));
  // Area: both overlaps; six corner cells off by at most h²/12 each plus the lip tilt.
  CHECK(l0.area_mm2 == Approx(9.5 * 3.25 + 9.5 * 2.5).margin(0.15));
  CHECK(r.closed);
}

TEST_CASE("coaptation: a band that begins below a free edge that does not touch", "[analysis][coaptation]") {
  // The upper sheet ends at y = 9.25, so the lower sheet coapts on rows y = 7..9 only: its
  // free edge (y = 10) and the row y = 9.5 do not touch. Down a column the indicator passes
  // 0.5 at y = 9.25, hypot(0.5, lip) + 0.25 below the free edge, and again at y = 6.75:
  // height 2.5 mm.
  TriMesh m;
  add_sheet(m, lower_sheet());
  add_sheet(m, {0.25, 9.75, 6.75, 9.25, 19, 10, 0.3, -kLip, 1, false});
  m.fill_defaults();
  const double top = std::hypot(0.5, kLip) + 0.25;
  const CoaptationResult r = analyze_coaptation(m, flatten(m.points));
  for (int i = 1; i <= 19; ++i) {
    INFO("column " << i);
    CHECK(r.coapting[lower(i, 14)] == 1);
    CHECK(r.coapting[lower(i, 18)] == 1);
    CHECK(r.coapting[lower(i, 19)] == 0);
    CHECK(r.coapting[lower(i, 20)] == 0);
  }
  const LeafletCoaptation& l0 = r.leaflets[0];
  for (std::size_t k = 0; k < l0.column_arc_mm.size(); ++k) {
    const double s = l0.column_arc_mm[k];
    INFO("column at " << s << " mm");
    if ((s >= 0.25 && s < 0.5) || (s > 9.5 && s <= 9.75)) continue;  // cells beside the sides
    const bool covered = s >= 0.5 && s <= 9.5;
    CHECK(l0.column_band_top_mm[k] == (covered ? Approx(top).margin(1e-9) : Approx(-1)));
    CHECK(l0.column_height_mm[k] == Approx(covered ? 2.5 : 0.0).margin(1e-9));
  }
  CHECK(l0.midline_height_mm == Approx(2.5).margin(1e-9));
  CHECK(l0.midline_band_top_mm == Approx(top).margin(1e-9));
  CHECK(l0.min_height_mm == Approx(2.5).margin(1e-9));
  CHECK(l0.closed);
  CHECK(r.central_gap);  // the free edge itself does not touch
  // Closed needs a band at least closed_min_height_mm tall everywhere between the margins.
  CoaptationOptions tall;
  tall.closed_min_height_mm = 2.49;
  CHECK(analyze_coaptation(m, flatten(m.points), tall).leaflets[0].closed);
  tall.closed_min_height_mm = 2.51;
  CHECK_FALSE(analyze_coaptation(m, flatten(m.points), tall).leaflets[0].closed);
  // A band beginning deeper than the offset is not coaptation from the free edge.
  CoaptationOptions o;
  o.free_edge_offset_mm = 0.7;
  const CoaptationResult deep = analyze_coaptation(m, flatten(m.points), o);
  CHECK(deep.leaflets[0].min_height_mm == 0);
  CHECK(deep.leaflets[0].midline_band_top_mm == -1);
  CHECK_FALSE(deep.leaflets[0].closed);
}

TEST_CASE("coaptation: free edges side by side at different heights (ray against nearest)", "[analysis][coaptation]") {
  // No lips. Leaflet 0 is the lower sheet, leaflet 1 lies 0.25 mm above it (the penalty
  // contact's separation) over x in [0.25, 9.75], y in [6, 9.9]: its free edge stops
  // 0.1 mm short of leaflet 0's. The rays from leaflet 0's free edge (y = 10, along ±z) pass
  // beside leaflet 1; the nearest point of leaflet 1 is on its free edge, hypot(0.1, 0.25) away.
  TriMesh m;
  add_sheet(m, {0, 10, 0, 10, 20, 20, 0.0, 0.0, 0, false});
  add_sheet(m, {0.25, 9.75, 6.0, 9.9, 19, 13, 0.25, 0.0, 1, false});
  m.fill_defaults();
  const VecX x = flatten(m.points);
  const double edge_gap = std::hypot(0.1, 0.25);

  const CoaptationResult ray = analyze_coaptation(m, x);
  CHECK(ray.gap_mm[lower(10, 20)] == kCoaptationNoHit);
  CHECK(ray.gap_mm[lower(10, 16)] == Approx(0.25).margin(1e-9));
  CHECK(ray.leaflets[0].coapting_fraction_of_free_edge == 0);
  // Band from y = 9.75 (half way to the coapting row y = 9.5) down to y = 5.75 (half way
  // from the row y = 6 to the bare row y = 5.5): 4 mm.
  CHECK(ray.leaflets[0].min_height_mm == Approx(4.0).margin(1e-9));
  CHECK(ray.central_gap);

  CoaptationOptions o;
  o.gap = GapMeasure::nearest;
  const CoaptationResult near = analyze_coaptation(m, x, o);
  for (int i = 1; i <= 19; ++i) {
    INFO("free-edge node " << i);
    CHECK(near.gap_mm[lower(i, 20)] == Approx(edge_gap).margin(1e-9));
    CHECK(near.coapting[lower(i, 20)] == 1);
  }
  CHECK(near.gap_mm[lower(10, 16)] == Approx(0.25).margin(1e-9));  // flat part: as the ray
  CHECK(near.gap_mm[lower(10, 12)] == Approx(0.25).margin(1e-9));  // y = 6, on the border
  CHECK(near.gap_mm[lower(10, 11)] == Approx(std::hypot(0.5, 0.25)).margin(1e-9));  // y = 5.5
  CHECK(near.coapting[lower(10, 11)] == 0);
  // The rim: x = 0 lies 0.25 mm beside leaflet 1's side border, within the 0.5 mm threshold.
  CHECK(near.gap_mm[lower(0, 16)] == Approx(std::hypot(0.25, 0.25)).margin(1e-9));
  CHECK(near.coapting[lower(0, 16)] == 1);
  CHECK(ray.coapting[lower(0, 16)] == 0);
  // Corners (x = 0, 10) are also within the threshold of leaflet 1's free-edge corners.
  CHECK(near.leaflets[0].coapting_fraction_of_free_edge == Approx(1.0));
  CHECK(near.leaflets[0].min_height_mm == Approx(4.25).margin(1e-9));  // y = 10 down to y = 5.75
  CHECK_FALSE(near.central_gap);
  // Leaflet 1 lies wholly over leaflet 0: every node 0.25 mm from it either way.
  for (int v = upper(0, 0); v < m.num_nodes(); ++v) CHECK(near.gap_mm[v] == Approx(0.25).margin(1e-9));

  // A leaflet alone has nothing to be near.
  TriMesh alone;
  add_sheet(alone, lower_sheet());
  alone.fill_defaults();
  for (double g : analyze_coaptation(alone, flatten(alone.points), o).gap_mm) CHECK(g == kCoaptationNoHit);
}

TEST_CASE("coaptation: the commissure margin excludes the free-edge ends", "[analysis][coaptation]") {
  const TriMesh m = overlap_pair(0.3);
  CoaptationOptions o;
  o.commissure_margin = 0;  // the lower sheet's corners (x = 0, 10) do not coapt
  const CoaptationResult r = analyze_coaptation(m, flatten(m.points), o);
  CHECK(r.leaflets[0].min_height_mm == 0);
  CHECK_FALSE(r.leaflets[0].closed);
  CHECK(r.leaflets[1].min_height_mm == Approx(3.0 + std::hypot(0.25, kLip)).margin(1e-9));
  o.commissure_margin = 0.05;  // 0.5 mm: the columns over whole covered cells only
  CHECK(analyze_coaptation(m, flatten(m.points), o).leaflets[0].min_height_mm ==
        Approx(2.75 + std::hypot(0.5, kLip)).margin(1e-9));
}

TEST_CASE("coaptation: a node shared by two leaflets has gap 0 and no height", "[analysis][coaptation]") {
  // Two coplanar triangles meeting at node 0 (a commissure corner): no ray from the others
  // hits the other leaflet.
  TriMesh m;
  m.points.resize(5, 3);
  m.points << 0, 0, 0, 1, 0, 0, 0, 1, 0, -1, 0, 0, 0, -1, 0;
  m.triangles = {Tri(0, 1, 2), Tri(0, 3, 4)};
  m.leaflet = {0, 1};
  m.boundary = {BoundaryType::attached, BoundaryType::free_edge, BoundaryType::attached, BoundaryType::free_edge,
                BoundaryType::attached};
  m.fill_defaults();
  const CoaptationResult r = analyze_coaptation(m, flatten(m.points));
  CHECK(r.gap_mm == std::vector<double>{0, kCoaptationNoHit, kCoaptationNoHit, kCoaptationNoHit, kCoaptationNoHit});
  CHECK(r.coapting == std::vector<int>{1, 0, 0, 0, 0});
  // One coapting node of three: a third of the triangle's area (0.5 mm²).
  CHECK(r.leaflets[0].area_mm2 == Approx(0.5 / 3));
  REQUIRE_FALSE(r.leaflets[0].column_height_mm.empty());
  for (double h : r.leaflets[0].column_height_mm) CHECK(h == 0);
  CHECK_FALSE(r.closed);
}

TEST_CASE("coaptation: free-edge distance to a given axis", "[analysis][coaptation]") {
  // Free edges: lower sheet y = 10, z = kLip, x = 0, 0.5, ..., 10; upper sheet (0.3 mm above)
  // y = 10, z = 0.3 - kLip, x = 0.25, 0.75, ..., 9.75.
  const TriMesh m = overlap_pair(0.3);
  const VecX x = flatten(m.points);
  CHECK(analyze_coaptation(m, x).max_free_edge_axis_distance_mm == -1);  // no axis, no measure
  CHECK(analyze_coaptation(m, x).leaflets[0].free_edge_axis_distance_mm == -1);

  // Vertical axis through (5, 13): both free edges (the straight lines y = 10) pass 3 mm from
  // it, the upper one between its nodes at x = 4.75 and 5.25 (which lie sqrt(0.25² + 3²) mm
  // away). A non-unit direction.
  CoaptationOptions vertical;
  vertical.axis = ValveAxis{Vec3(5, 13, 7), Vec3(0, 0, 2)};
  const CoaptationResult r = analyze_coaptation(m, x, vertical);
  CHECK(r.leaflets[0].free_edge_axis_distance_mm == Approx(3.0).margin(1e-12));
  CHECK(r.leaflets[1].free_edge_axis_distance_mm == Approx(3.0).margin(1e-12));
  CHECK(r.max_free_edge_axis_distance_mm == Approx(3.0).margin(1e-12));
  // An axis beyond the free edge's end (x = 12, y = 13): the end node (10, 10) is nearest.
  CoaptationOptions beyond;
  beyond.axis = ValveAxis{Vec3(12, 13, 0), Vec3(0, 0, 1)};
  CHECK(analyze_coaptation(m, x, beyond).leaflets[0].free_edge_axis_distance_mm ==
        Approx(std::hypot(2.0, 3.0)).margin(1e-12));
  // A tilted axis: only the part of each point normal to it counts. Along (1, 0, 0) through
  // (0, 13, kLip) the whole lower free edge lies 3 mm away.
  CoaptationOptions along;
  along.axis = ValveAxis{Vec3(0, 13, kLip), Vec3(1, 0, 0)};
  CHECK(analyze_coaptation(m, x, along).leaflets[0].free_edge_axis_distance_mm == Approx(3.0).margin(1e-12));
  CHECK(r.report().find("mm from the axis") != std::string::npos);
  // The axis lies beside the sheets: no cross-section to measure an orifice in. Through
  // them, the lower sheet covers its whole square: no opening.
  CHECK(r.orifice_area_mm2 == -1);
  CoaptationOptions through;
  through.axis = ValveAxis{Vec3(5, 5, 0), Vec3(0, 0, 1)};
  CHECK(analyze_coaptation(m, x, through).orifice_area_mm2 == 0);
  CHECK(analyze_coaptation(m, x).orifice_area_mm2 == -1);  // no axis
  CoaptationOptions huge = vertical;
  huge.axis->direction = Vec3(0, 0, 1e200);  // would overflow a plain norm
  CHECK(analyze_coaptation(m, x, huge).leaflets[0].free_edge_axis_distance_mm == Approx(3.0).margin(1e-12));

  // An axis along x at y = 12, z = kLip: the distance is measured across the axis only.
  CoaptationOptions along_x;
  along_x.axis = ValveAxis{Vec3(-40, 12, kLip), Vec3(1, 0, 0)};
  const CoaptationResult q = analyze_coaptation(m, x, along_x);
  CHECK(q.leaflets[0].free_edge_axis_distance_mm == Approx(2.0).margin(1e-12));
  CHECK(q.leaflets[1].free_edge_axis_distance_mm == Approx(std::hypot(2.0, 0.3 - 2 * kLip)).margin(1e-12));
  // The heights do not depend on the axis.
  const CoaptationResult plain = analyze_coaptation(m, x);
  for (std::size_t l = 0; l < 2; ++l) CHECK(q.leaflets[l].min_height_mm == plain.leaflets[l].min_height_mm);
}

TEST_CASE("coaptation: invalid options and inputs throw InputError", "[analysis][coaptation]") {
  const double nan = std::nan("");
  for (double t : {0.0, -0.5, nan, HUGE_VAL}) {
    CoaptationOptions o;
    o.threshold_mm = t;
    CHECK_THROWS_AS(o.validate(), InputError);
  }
  for (double margin : {-0.01, 0.5, 0.7, nan}) {
    CoaptationOptions o;
    o.commissure_margin = margin;
    CHECK_THROWS_AS(o.validate(), InputError);
  }
  for (double height : {0.0, -1.0, nan, HUGE_VAL}) {
    CoaptationOptions o;
    o.closed_min_height_mm = height;
    CHECK_THROWS_AS(o.validate(), InputError);
  }
  for (double offset : {-0.1, nan, HUGE_VAL}) {
    CoaptationOptions o;
    o.free_edge_offset_mm = offset;
    CHECK_THROWS_AS(o.validate(), InputError);
  }
  for (const ValveAxis& axis : {ValveAxis{Vec3(0, 0, 0), Vec3(0, 0, 0)}, ValveAxis{Vec3(nan, 0, 0), Vec3(0, 0, 1)},
                                ValveAxis{Vec3(0, 0, 0), Vec3(0, HUGE_VAL, 1)}}) {
    CoaptationOptions o;
    o.axis = axis;
    CHECK_THROWS_AS(o.validate(), InputError);
  }
  for (const Vec3& direction : {Vec3(1e-170, 0, 0), Vec3(1e200, 1e200, 0)}) {  // any finite size is a direction
    CoaptationOptions o;
    o.axis = ValveAxis{Vec3(0, 0, 0), direction};
    CHECK_NOTHROW(o.validate());
  }
  CoaptationOptions ok;
  ok.commissure_margin = 0;
  CHECK_NOTHROW(ok.validate());

  const TriMesh m = overlap_pair(0.3);
  CoaptationOptions bad;
  bad.threshold_mm = -1;
  CHECK_THROWS_AS(analyze_coaptation(m, flatten(m.points), bad), InputError);
  CHECK_THROWS_AS(analyze_coaptation(m, VecX::Zero(6)), InputError);
  VecX x = flatten(m.points);
  x[7] = nan;
  CHECK_THROWS_AS(analyze_coaptation(m, x), InputError);
}
