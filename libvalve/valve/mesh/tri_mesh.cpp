#include "valve/mesh/tri_mesh.hpp"

#include <Eigen/Geometry>

namespace valve {

Vec3 triangle_normal(const MatX3& x, const Tri& t) {
  const Vec3 a = x.row(t[0]), b = x.row(t[1]), c = x.row(t[2]);
  return (b - a).cross(c - a).normalized();
}

double triangle_area(const MatX3& x, const Tri& t) {
  const Vec3 a = x.row(t[0]), b = x.row(t[1]), c = x.row(t[2]);
  return 0.5 * (b - a).cross(c - a).norm();
}

void TriMesh::fill_defaults() {
  const int n = num_nodes(), m = num_triangles();
  if (static_cast<int>(roles.size()) != n) roles.assign(n, NodeRole::free);
  if (static_cast<int>(boundary.size()) != n) boundary.assign(n, BoundaryType::interior);
  if (static_cast<int>(leaflet.size()) != m) leaflet.assign(m, 0);
  if (fiber.rows() != m) {
    fiber.resize(m, 3);
    for (int t = 0; t < m; ++t) {
      const Vec3 e = points.row(triangles[t][1]) - points.row(triangles[t][0]);
      fiber.row(t) = e.normalized();
    }
  }
}

}  // namespace valve
