#include <catch2/catch.hpp>

#include "valve/analysis/leaflet_metrics.hpp"
#include "valve/core/error.hpp"

using namespace valve;

namespace {

// A vertical 4 x 4 mm cusp stand-in in the x-z plane: 5 x 5 nodes 1 mm apart, the top row
// (z = 4) the free edge, the other border nodes attached (fixed), as a cusp hangs from its
// root; leaflet 0. Leaflet 1 is one triangle 10 mm below it, attached nowhere.
TriMesh hanging_sheet() {
  TriMesh m;
  m.points.resize(28, 3);
  for (int j = 0; j < 5; ++j)
    for (int i = 0; i < 5; ++i) m.points.row(5 * j + i) << i, 0, j;
  m.points.row(25) << 0, 1, -10;
  m.points.row(26) << 1, 1, -10;
  m.points.row(27) << 0, 2, -10;
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i) {
      const int a = 5 * j + i;
      m.triangles.emplace_back(a, a + 1, a + 6);
      m.triangles.emplace_back(a, a + 6, a + 5);
    }
  m.triangles.emplace_back(25, 26, 27);
  m.fill_defaults();
  m.leaflet.assign(m.num_triangles(), 0);
  m.leaflet.back() = 1;
  for (int k = 0; k < 25; ++k) {
    const int i = k % 5, j = k / 5;
    const bool border = i == 0 || i == 4 || j == 0 || j == 4;
    m.boundary[k] = !border ? BoundaryType::interior : (j == 4 && i > 0 && i < 4 ? BoundaryType::free_edge : BoundaryType::attached);
    m.roles[k] = border && m.boundary[k] == BoundaryType::attached ? NodeRole::fixed : NodeRole::free;
  }
  return m;
}

}  // namespace

TEST_CASE("belly drop: how far a cusp hangs below its attachment, whichever way the axis points", "[analysis][leaflet]") {
  const TriMesh m = hanging_sheet();
  REQUIRE(free_edge_middle_node(m, 0) == 22);
  VecX x = flatten(m.points);
  // At rest nothing lies below the attachment's lowest row; the other leaflet, 10 mm down,
  // is not this leaflet's belly.
  CHECK(belly_drop(m, x, 0, Vec3(0, 0, 1)) == Approx(0).margin(1e-12));
  // The centre node pushed 1.5 mm below the bottom row (z = 0), the whole cusp then moved
  // 3 mm down and 2 mm sideways: the drop is relative to the deformed attachment.
  node3(x, 12) = Vec3(2, 0.7, -1.5);
  for (int i = 0; i < 25; ++i) node3(x, i) += Vec3(2, 0, -3);
  CHECK(belly_drop(m, x, 0, Vec3(0, 0, 1)) == Approx(1.5).epsilon(1e-12));
  CHECK(belly_drop(m, x, 0, Vec3(0, 0, -2.5)) == Approx(1.5).epsilon(1e-12));  // flipped, not unit
  // Along a tilted axis the same displacement counts by its component.
  const Vec3 tilted(0, std::sin(0.3), std::cos(0.3));
  const double expected = (node3(x, 0) - node3(x, 12)).dot(tilted);
  CHECK(belly_drop(m, x, 0, tilted) == Approx(std::max(expected, (node3(x, 4) - node3(x, 12)).dot(tilted))).epsilon(1e-12));
  // A leaflet without attached nodes, an axis without direction: 0; a wrong size throws.
  CHECK(belly_drop(m, x, 1, Vec3(0, 0, 1)) == 0);
  CHECK(belly_drop(m, x, 0, Vec3::Zero()) == 0);
  CHECK_THROWS_AS(belly_drop(m, VecX::Zero(6), 0, Vec3(0, 0, 1)), InputError);
}
