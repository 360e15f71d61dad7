#include "valve/mesh/validate.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "valve/core/error.hpp"
#include "valve/mesh/topology.hpp"

namespace valve {

void validate_mesh(const TriMesh& m, const std::string& source) {
  const int n = m.num_nodes();
  if (n == 0) throw_input_error(source, "points", "at least 3 points", "none");
  if (m.triangles.empty()) throw_input_error(source, "cells", "triangles", "none");
  for (int i = 0; i < n; ++i)
    if (!m.points.row(i).allFinite())
      throw_input_error(source, "point " + std::to_string(i), "finite coordinates", "NaN or inf");
  double extent = (m.points.colwise().maxCoeff() - m.points.colwise().minCoeff()).norm();
  std::vector<std::array<int, 3>> sorted;
  sorted.reserve(m.triangles.size());
  for (int t = 0; t < m.num_triangles(); ++t) {
    const Tri& tri = m.triangles[t];
    for (int k = 0; k < 3; ++k)
      if (tri[k] < 0 || tri[k] >= n)
        throw_input_error(source, "triangle " + std::to_string(t), "node indices in [0, " + std::to_string(n - 1) + "]",
                          std::to_string(tri[k]));
    if (tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2])
      throw_input_error(source, "triangle " + std::to_string(t), "three distinct nodes", "a repeated node");
    // Relative threshold: a sliver is fine, a triangle with no area has no normal.
    if (triangle_area(m.points, tri) <= 1e-14 * extent * extent)
      throw_input_error(source, "triangle " + std::to_string(t), "a positive area", "zero area");
    std::array<int, 3> s{tri[0], tri[1], tri[2]};
    std::sort(s.begin(), s.end());
    sorted.push_back(s);
  }
  std::vector<size_t> order(sorted.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return sorted[a] < sorted[b]; });
  for (size_t i = 1; i < order.size(); ++i)
    if (sorted[order[i]] == sorted[order[i - 1]])
      throw_input_error(source, "triangle " + std::to_string(std::max(order[i], order[i - 1])),
                        "no duplicate triangles", "a duplicate of triangle " + std::to_string(std::min(order[i], order[i - 1])));
  const Topology topo = build_topology(m.triangles, n);
  if (topo.non_manifold_edges > 0)
    throw_input_error(source, "cells", "a manifold mesh (each edge in at most two triangles)",
                      std::to_string(topo.non_manifold_edges) + " non-manifold edges");
  if (m.fiber.rows() == m.num_triangles())
    for (int t = 0; t < m.num_triangles(); ++t)
      if (!m.fiber.row(t).allFinite() || m.fiber.row(t).norm() < 1e-12)
        throw_input_error(source, "FiberDirection of triangle " + std::to_string(t), "a nonzero finite vector", "zero or NaN");
}

}  // namespace valve
