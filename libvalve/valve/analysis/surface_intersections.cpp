#include "valve/analysis/surface_intersections.hpp"

#include <CGAL/Box_intersection_d/Box_with_info_d.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/box_intersection_d.h>
#include <CGAL/intersections.h>

#include <algorithm>

#include "valve/core/error.hpp"
#include "valve/mesh/topology.hpp"

namespace valve {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Box = CGAL::Box_intersection_d::Box_with_info_d<double, 3, int>;

}  // namespace

SurfaceIntersections find_surface_intersections(const std::vector<Tri>& triangles, const VecX& x,
                                                const std::vector<int>& leaflet, const std::vector<char>& anchored) {
  const Eigen::Index n = x.size() / 3;
  if (x.size() % 3 != 0 || !x.allFinite())
    throw_input_error("surface intersections", "positions", "3N finite coordinates",
                      std::to_string(x.size()) + " entries" + (x.allFinite() ? "" : " with NaN or inf"));
  if (!leaflet.empty() && leaflet.size() != triangles.size())
    throw_input_error("surface intersections", "leaflet", std::to_string(triangles.size()) + " values (one per triangle)",
                      std::to_string(leaflet.size()));
  if (!anchored.empty() && static_cast<Eigen::Index>(anchored.size()) != n)
    throw_input_error("surface intersections", "anchored", std::to_string(n) + " values (one per node)",
                      std::to_string(anchored.size()));
  auto has_anchored_node = [&](const Tri& t) {
    return !anchored.empty() && (anchored[t[0]] || anchored[t[1]] || anchored[t[2]]);
  };
  std::vector<K::Triangle_3> geometry;
  std::vector<Box> boxes;
  geometry.reserve(triangles.size());
  boxes.reserve(triangles.size());
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    K::Point_3 p[3];
    for (int k = 0; k < 3; ++k) {
      const int v = triangles[t][k];
      if (v < 0 || v >= n)
        throw_input_error("surface intersections", "triangles", "node indices below " + std::to_string(n), std::to_string(v));
      p[k] = K::Point_3(x[3 * v], x[3 * v + 1], x[3 * v + 2]);
    }
    geometry.emplace_back(p[0], p[1], p[2]);
    boxes.emplace_back(geometry.back().bbox(), static_cast<int>(t));
  }
  // Node adjacency (sorted lists) for the one-edge-apart test.
  std::vector<std::vector<int>> neighbours(n);
  for (const auto& [a, b] : unique_edges(triangles)) {
    neighbours[a].push_back(b);
    neighbours[b].push_back(a);
  }
  for (auto& list : neighbours) std::sort(list.begin(), list.end());
  auto one_edge_apart = [&](const Tri& a, const Tri& b) {
    for (int i : a)
      for (int j : b)
        if (std::binary_search(neighbours[i].begin(), neighbours[i].end(), j)) return true;
    return false;
  };
  SurfaceIntersections out;
  // The longest edge of a degenerate (flat) triangle: it covers the whole triangle.
  auto longest_edge = [&](int t) {
    const K::Triangle_3& g = geometry[t];
    K::Segment_3 best(g[0], g[1]);
    for (int k = 1; k < 3; ++k) {
      const K::Segment_3 e(g[k], g[(k + 1) % 3]);
      if (e.squared_length() > best.squared_length()) best = e;
    }
    return best;
  };
  auto intersect = [&](int s, int t) {
    const bool ds = geometry[s].is_degenerate(), dt = geometry[t].is_degenerate();
    if (!ds && !dt) return CGAL::do_intersect(geometry[s], geometry[t]);
    const K::Segment_3 es = ds ? longest_edge(s) : K::Segment_3(), et = dt ? longest_edge(t) : K::Segment_3();
    if ((ds && es.is_degenerate()) || (dt && et.is_degenerate())) {
      ++out.degenerate_skipped;
      return false;
    }
    if (ds && dt) return CGAL::do_intersect(es, et);
    return ds ? CGAL::do_intersect(es, geometry[t]) : CGAL::do_intersect(et, geometry[s]);
  };
  auto test = [&](const Box& a, const Box& b) {
    const int s = a.info(), t = b.info();
    if (share_vertex(triangles[s], triangles[t])) return;
    if (!intersect(s, t)) return;
    ++out.pairs;
    if (!leaflet.empty() && leaflet[s] != leaflet[t]) ++out.between_leaflets;
    if (one_edge_apart(triangles[s], triangles[t])) ++out.one_edge_apart;
    if (has_anchored_node(triangles[s]) && has_anchored_node(triangles[t])) ++out.both_anchored;
    if (out.first_pairs.size() < 10) out.first_pairs.emplace_back(std::min(s, t), std::max(s, t));
  };
  // Closed boxes: two triangles that touch have touching boxes.
  CGAL::box_self_intersection_d(boxes.begin(), boxes.end(), test, std::ptrdiff_t(10),
                                CGAL::Box_intersection_d::CLOSED);
  std::sort(out.first_pairs.begin(), out.first_pairs.end());
  return out;
}

}  // namespace valve
