// The parametric open mitral valve: annulus size, leaflet lengths, chordae and
// seeded variation, checked against the options they are built from.
#include <catch2/catch.hpp>
#include <cmath>
#include <numeric>

#include "valve/phantom/mitral_phantom.hpp"
#include "valve/mesh/quality.hpp"
#include "valve/mesh/topology.hpp"

using namespace valve;

TEST_CASE("nominal mitral phantom matches its options", "[imaging][phantom]") {
  MitralPhantomOptions o;
  o.variation = 0;
  const MitralPhantom ph = make_mitral_phantom(o);
  const TriMesh& m = ph.leaflets;
  // Annulus nodes: the D-shaped saddle, 30 × 25 mm nominal (y squeezed by the D profile).
  Vec3 lo = Vec3::Constant(1e9), hi = Vec3::Constant(-1e9);
  int annulus = 0;
  for (int i = 0; i < m.num_nodes(); ++i)
    if (m.boundary[i] == BoundaryType::attached) {
      lo = lo.cwiseMin(m.points.row(i).transpose());
      hi = hi.cwiseMax(m.points.row(i).transpose());
      ++annulus;
    }
  REQUIRE(annulus > 100);
  CHECK(hi.x() - lo.x() == Approx(30).margin(0.2));
  CHECK(hi.y() - lo.y() == Approx(25 * 0.9).margin(1.5));
  CHECK(hi.z() - lo.z() == Approx(4).margin(0.1));  // saddle height
  // The anterior leaflet reaches 22 mm from the annulus (slant length, bulge aside).
  double deepest = 0;
  for (int i = 0; i < m.num_nodes(); ++i) deepest = std::min(deepest, m.points(i, 2));
  CHECK(-deepest > 22 * std::cos(25 * 3.14159265358979 / 180) - 3);
  CHECK(-deepest < 22 + 2);
  // A usable ground truth: no degenerate triangle (the structured grid thins out toward the
  // commissures, so some are stretched), one boundary loop per border.
  const auto q = triangle_qualities(m.points, m.triangles);
  CHECK(*std::min_element(q.begin(), q.end()) > 0.01);
  CHECK(std::accumulate(q.begin(), q.end(), 0.0) / q.size() > 0.6);  // a reference surface, not a simulation mesh
  const MeshShapeReport shape = describe_mesh_shape(m);
  CHECK(shape.manifold());
  CHECK(shape.boundary_loops == 2);  // annulus and free edge
}

TEST_CASE("phantom chordae connect papillary tips to leaflet nodes", "[imaging][phantom]") {
  const MitralPhantom ph = make_mitral_phantom(MitralPhantomOptions{});
  const ChordaeNetwork& c = ph.chordae;
  CHECK(c.count(ChordPointKind::papillary_tip) == 2);
  CHECK(c.count(ChordType::strut) == 2);
  CHECK(c.count(ChordType::primary) >= 8);
  CHECK(c.count(ChordType::secondary) >= 4);
  for (const ChordPoint& p : c.points) {
    if (p.kind != ChordPointKind::insertion) continue;
    REQUIRE(p.mesh_node >= 0);
    REQUIRE(p.mesh_node < ph.leaflets.num_nodes());
    CHECK((ph.leaflets.points.row(p.mesh_node).transpose() - p.position).norm() < 1e-9);
  }
  // Primary chords end on the free edge.
  for (const ChordSegment& s : c.segments) {
    const ChordPoint& end = c.points[s.to];
    if (s.type == ChordType::primary && end.kind == ChordPointKind::insertion)
      CHECK(ph.leaflets.boundary[end.mesh_node] == BoundaryType::free_edge);
    CHECK((c.points[s.from].position - end.position).norm() > 0.5);  // no zero-length chord
  }
}

TEST_CASE("seeded variation makes distinct, reproducible valves", "[imaging][phantom]") {
  MitralPhantomOptions a;
  a.seed = 3;
  MitralPhantomOptions b = a;
  b.seed = 4;
  const MitralPhantom pa = make_mitral_phantom(a), pa2 = make_mitral_phantom(a), pb = make_mitral_phantom(b);
  CHECK(pa.options.commissural_diameter == pa2.options.commissural_diameter);
  CHECK(pa.leaflets.points.isApprox(pa2.leaflets.points, 0));
  CHECK(pa.options.commissural_diameter != pb.options.commissural_diameter);
  // Every size stays within ± variation of nominal.
  for (const MitralPhantom* p : {&pa, &pb}) {
    CHECK(std::abs(p->options.commissural_diameter / 30.0 - 1) <= 0.08 + 1e-12);
    CHECK(std::abs(p->options.anterior_length / 22.0 - 1) <= 0.08 + 1e-12);
  }
}
