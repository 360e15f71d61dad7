// Columns of a leaflet (analysis/leaflet_columns.hpp) on flat sheets, where the across
// coordinate is known exactly (the distance along the straight free edge), and on the
// generated aortic valve, whose cusps are flat sheets wrapped onto a cylinder.
#include <catch2/catch.hpp>
#include <cmath>

#include "valve/analysis/coaptation.hpp"
#include "valve/analysis/leaflet_columns.hpp"
#include "valve/mesh/generators.hpp"

using namespace valve;

namespace {

// Square patch of `side` mm (unstructured, centred at the origin) with its top side y = side/2
// as the free edge (corners attached) and the rest of its border attached.
TriMesh patch_with_free_top(double side, int triangles, int leaflet = 0) {
  SquarePatchOptions o;
  o.side = side;
  o.mesh.target_triangles = triangles;
  TriMesh m = generate_square_patch(o);
  for (int v = 0; v < m.num_nodes(); ++v) {
    if (m.boundary[v] == BoundaryType::interior) continue;
    const double x = m.points(v, 0), y = m.points(v, 1);
    const bool corner = std::abs(std::abs(x) - side / 2) < 1e-9;
    m.boundary[v] = std::abs(y - side / 2) < 1e-9 && !corner ? BoundaryType::free_edge : BoundaryType::attached;
  }
  m.leaflet.assign(m.num_triangles(), leaflet);
  return m;
}

Vec3 rest_point(const TriMesh& m, const EdgePoint& e) {
  return (1 - e.t) * m.points.row(e.a).transpose() + e.t * m.points.row(e.b).transpose();
}

}  // namespace

TEST_CASE("leaflet columns: on a flat sheet they are the perpendiculars to the free edge",
          "[analysis][leaflet_columns]") {
  const double side = 10;
  const TriMesh m = patch_with_free_top(side, 400);
  const LeafletColumns columns(m, 0);
  REQUIRE(columns.free_edge().size() >= 3);
  CHECK(columns.free_edge_length() == Approx(side).epsilon(1e-12));
  // The free edge runs one way or the other: s = |x - x(first corner)|.
  const double x0 = m.points(columns.free_edge().front(), 0);
  const double sign = x0 < 0 ? 1.0 : -1.0;
  // Cotangent weights reproduce linear functions; the patch is a relaxed Delaunay-like mesh
  // whose few obtuse pairs, clamped at 0, perturb s by far less than a micrometre.
  for (int v = 0; v < m.num_nodes(); ++v) {
    INFO("node " << v);
    CHECK(columns.across()[v] == Approx(sign * (m.points(v, 0) - x0)).margin(1e-6));
  }
  for (double s : {0.5, 2.0, 5.0, 7.25, 9.5, 10.0}) {
    const std::vector<EdgePoint> path = columns.trace(s);
    INFO("column at " << s);
    REQUIRE(path.size() >= 2);
    for (const EdgePoint& e : path) CHECK(rest_point(m, e).x() == Approx(x0 + sign * s).margin(1e-6));
    CHECK(rest_point(m, path.front()).y() == Approx(side / 2).margin(1e-12));  // begins on the free edge
    CHECK(rest_point(m, path.back()).y() == Approx(-side / 2).margin(1e-6));   // ends on the far border
    for (std::size_t k = 1; k < path.size(); ++k) CHECK(rest_point(m, path[k]).y() <= rest_point(m, path[k - 1]).y() + 1e-9);
  }
  CHECK(columns.trace(0).empty());
  CHECK(columns.trace(side * 1.001).empty());
  CHECK(columns.trace(std::nan("")).empty());
}

TEST_CASE("leaflet columns: a leaflet without a free edge has none", "[analysis][leaflet_columns]") {
  TriMesh m = patch_with_free_top(10, 100);
  for (auto& b : m.boundary)
    if (b == BoundaryType::free_edge) b = BoundaryType::attached;
  const LeafletColumns columns(m, 0);
  CHECK(columns.free_edge().empty());
  CHECK(columns.free_edge_length() == 0);
  CHECK(columns.trace(1.0).empty());
  for (double s : columns.across()) CHECK(std::isnan(s));
}

TEST_CASE("leaflet columns: on the aortic valve they run down the cusps", "[analysis][leaflet_columns]") {
  // Each cusp is a flat sheet wrapped onto radius R = 10 mm: its column at s is the vertical
  // line at angle φ0 + (s - L/2) / R (up to the direction of the free edge), from the free
  // edge (z = 0) down to the attachment curve. The wrapped triangles are chords of the
  // cylinder, so the cotangent weights are not exactly the flat ones: 0.05 mm.
  AorticValveOptions o;
  const TriMesh m = generate_aortic_valve(o);
  for (int leaflet = 0; leaflet < 3; ++leaflet) {
    const LeafletColumns columns(m, leaflet);
    REQUIRE(columns.free_edge().size() >= 3);
    const Vec3 first = m.points.row(columns.free_edge().front());
    const double phi_first = std::atan2(first.y(), first.x());
    const double L = columns.free_edge_length(), R = o.diameter / 2;
    for (double s : {0.2 * L, 0.5 * L, 0.8 * L}) {
      INFO("leaflet " << leaflet << ", column at " << s);
      const std::vector<EdgePoint> path = columns.trace(s);
      REQUIRE(path.size() >= 3);
      const Vec3 top = rest_point(m, path.front());
      const double phi_top = std::atan2(top.y(), top.x());
      CHECK(std::abs(std::remainder(phi_top - phi_first, 2 * M_PI)) * R == Approx(s).margin(0.05));
      for (const EdgePoint& e : path) {
        const Vec3 p = rest_point(m, e);
        CHECK(std::abs(std::remainder(std::atan2(p.y(), p.x()) - phi_top, 2 * M_PI)) * R < 0.05);
      }
      CHECK(rest_point(m, path.back()).z() < top.z() - 5);  // reaches the attachment, below the commissures
    }
  }
}

TEST_CASE("coaptation: every column of an unstructured sheet under a neighbour has a band",
          "[analysis][coaptation]") {
  // The lower leaflet is the unstructured patch, the upper one the same patch 0.3 mm above
  // it: every node lies 0.3 mm from the other leaflet, so every column coapts from the free
  // edge to the far border, 10 mm. (With columns made of nodes, a free-edge node that was
  // no other node's nearest read 0 on such a sheet.)
  TriMesh m = patch_with_free_top(10, 300, 0);
  TriMesh upper = patch_with_free_top(10, 300, 1);
  const int n = m.num_nodes();
  m.points.conservativeResize(n + upper.num_nodes(), 3);
  for (int v = 0; v < upper.num_nodes(); ++v) m.points.row(n + v) = upper.points.row(v) + Eigen::RowVector3d(0, 0, 0.3);
  for (const Tri& t : upper.triangles) m.triangles.emplace_back(t[0] + n, t[1] + n, t[2] + n);
  m.leaflet.insert(m.leaflet.end(), upper.leaflet.begin(), upper.leaflet.end());
  m.boundary.insert(m.boundary.end(), upper.boundary.begin(), upper.boundary.end());
  m.fill_defaults();
  CoaptationOptions o;
  o.gap = GapMeasure::nearest;
  o.commissure_margin = 0;
  const CoaptationResult r = analyze_coaptation(m, flatten(m.points), o);
  for (const LeafletCoaptation& l : r.leaflets) {
    REQUIRE(l.column_height_mm.size() > 100);
    for (std::size_t k = 0; k < l.column_height_mm.size(); ++k) {
      INFO("leaflet " << l.leaflet << ", column at " << l.column_arc_mm[k]);
      CHECK(l.column_height_mm[k] == Approx(10).margin(1e-6));
      CHECK(l.column_band_top_mm[k] == 0);
    }
    CHECK(l.min_height_mm == Approx(10).margin(1e-6));
  }
  CHECK(r.closed);
}
