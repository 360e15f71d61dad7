#include "valve/analysis/surface_distance.hpp"

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <cmath>

#include "valve/core/error.hpp"

namespace valve {

std::vector<double> distances_to_surface(const MatX3& points, const TriMesh& reference) {
  using K = CGAL::Exact_predicates_inexact_constructions_kernel;
  using Triangles = std::vector<K::Triangle_3>;
  using Primitive = CGAL::AABB_triangle_primitive<K, Triangles::const_iterator>;
  using Tree = CGAL::AABB_tree<CGAL::AABB_traits<K, Primitive>>;
  if (reference.num_triangles() == 0) throw_input_error("surface distance", "reference", "a surface with triangles", "none");
  auto point = [&](int i) { return K::Point_3(reference.points(i, 0), reference.points(i, 1), reference.points(i, 2)); };
  Triangles triangles;
  triangles.reserve(reference.triangles.size());
  for (const Tri& t : reference.triangles) triangles.emplace_back(point(t[0]), point(t[1]), point(t[2]));
  Tree tree(triangles.begin(), triangles.end());
  tree.accelerate_distance_queries();
  std::vector<double> d(points.rows());
  for (Eigen::Index i = 0; i < points.rows(); ++i)
    d[i] = std::sqrt(tree.squared_distance(K::Point_3(points(i, 0), points(i, 1), points(i, 2))));
  return d;
}

}  // namespace valve
