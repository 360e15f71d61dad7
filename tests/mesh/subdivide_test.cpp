// Midpoint subdivision (seed 5.3.3 mesh-size study): ×4 triangles, same surface when flat,
// quality of each child equal to its parent's for the corner children.
#include <catch2/catch.hpp>

#include "valve/mesh/quality.hpp"
#include "valve/mesh/subdivide.hpp"
#include "valve/mesh/topology.hpp"

using namespace valve;

TEST_CASE("midpoint subdivision quadruples a flat mesh without changing it", "[mesh][subdivide]") {
  TriMesh m;
  m.points.resize(4, 3);
  m.points << 0, 0, 0, 2, 0, 0, 2, 1, 0, 0, 1.5, 0;
  m.triangles = {{0, 1, 2}, {0, 2, 3}};
  m.fill_defaults();
  m.roles[0] = NodeRole::fixed;
  m.roles[1] = NodeRole::fixed;
  m.boundary[0] = m.boundary[1] = BoundaryType::attached;
  const TriMesh s = subdivide_midpoint(m);
  CHECK(s.num_triangles() == 8);
  CHECK(s.num_nodes() == 4 + 5);  // one new node per edge
  double area = 0, area_s = 0;
  for (const Tri& t : m.triangles) area += triangle_area(m.points, t);
  for (const Tri& t : s.triangles) area_s += triangle_area(s.points, t);
  CHECK(area_s == Approx(area).epsilon(1e-12));
  // The midpoint of the fixed edge 0-1 is fixed too (a new node on a constrained border).
  int fixed = 0;
  for (NodeRole r : s.roles) fixed += r == NodeRole::fixed;
  CHECK(fixed == 3);
  // Orientation kept: every child's normal is +z.
  for (const Tri& t : s.triangles) CHECK(triangle_normal(s.points, t).z() > 0.99);
}
