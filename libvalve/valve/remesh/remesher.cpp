#include "valve/remesh/remesher.hpp"

#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/AABB_segment_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/angle_and_area_smoothing.h>
#include <CGAL/Polygon_mesh_processing/border.h>
#include <CGAL/Polygon_mesh_processing/compute_normal.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/remesh.h>
#include <CGAL/Polygon_mesh_processing/repair_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/tangential_relaxation.h>
#include <CGAL/Polygon_mesh_processing/triangulate_hole.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/Euler_operations.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/Count_stop_predicate.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/Edge_length_cost.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/Midpoint_placement.h>
#include <CGAL/Surface_mesh_simplification/edge_collapse.h>

#include <array>
#include <cmath>
#include <map>
#include <set>

#include "valve/core/error.hpp"
#include "valve/mesh/quality.hpp"

namespace valve {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = K::Point_3;
using Mesh = CGAL::Surface_mesh<Point>;
namespace PMP = CGAL::Polygon_mesh_processing;
namespace SMS = CGAL::Surface_mesh_simplification;

Mesh to_cgal(const TriMesh& in) {
  std::vector<Point> points;
  points.reserve(in.num_nodes());
  for (int i = 0; i < in.num_nodes(); ++i) points.emplace_back(in.points(i, 0), in.points(i, 1), in.points(i, 2));
  std::vector<std::array<std::size_t, 3>> polygons;
  polygons.reserve(in.triangles.size());
  for (const Tri& t : in.triangles) polygons.push_back({std::size_t(t[0]), std::size_t(t[1]), std::size_t(t[2])});
  PMP::repair_polygon_soup(points, polygons);
  PMP::orient_polygon_soup(points, polygons);  // duplicates points at non-manifold vertices
  Mesh m;
  PMP::polygon_soup_to_polygon_mesh(points, polygons, m);
  return m;
}

TriMesh from_cgal(const Mesh& m) {
  TriMesh out;
  std::map<Mesh::Vertex_index, int> index;
  out.points.resize(static_cast<Eigen::Index>(m.number_of_vertices()), 3);
  int n = 0;
  for (auto v : m.vertices()) {
    const Point& p = m.point(v);
    out.points.row(n) << p.x(), p.y(), p.z();
    index[v] = n++;
  }
  for (auto f : m.faces()) {
    Tri t;
    int k = 0;
    for (auto v : CGAL::vertices_around_face(m.halfedge(f), m)) t[k++] = index[v];
    out.triangles.push_back(t);
  }
  out.fill_defaults();
  return out;
}

// Fills holes whose border is shorter than `fraction` of the longest border.
int fill_small_holes(Mesh& m, double fraction) {
  std::vector<Mesh::Halfedge_index> cycles;
  PMP::extract_boundary_cycles(m, std::back_inserter(cycles));
  std::vector<double> lengths;
  double longest = 0;
  for (auto h : cycles) {
    double len = 0;
    for (auto e : CGAL::halfedges_around_face(h, m)) len += std::sqrt(CGAL::squared_distance(m.point(m.source(e)), m.point(m.target(e))));
    lengths.push_back(len);
    longest = std::max(longest, len);
  }
  int filled = 0;
  for (std::size_t c = 0; c < cycles.size(); ++c) {
    if (lengths[c] >= fraction * longest) continue;
    std::vector<Mesh::Face_index> faces;
    std::vector<Mesh::Vertex_index> vertices;
    PMP::triangulate_and_refine_hole(m, cycles[c], std::back_inserter(faces), std::back_inserter(vertices));
    ++filled;
  }
  return filled;
}

// Smooths every border polyline (weights 1/4, 1/2, 1/4 along the loop): the border of a
// membrane cut from a voxel surface zigzags at the voxel scale, and remeshing along a
// zigzag leaves slivers at the border.
void smooth_borders(Mesh& m, int iterations) {
  std::vector<Mesh::Halfedge_index> cycles;
  PMP::extract_boundary_cycles(m, std::back_inserter(cycles));
  for (auto h : cycles) {
    std::vector<Mesh::Vertex_index> loop;
    for (auto e : CGAL::halfedges_around_face(h, m)) loop.push_back(m.source(e));
    const std::size_t n = loop.size();
    if (n < 5) continue;
    for (int it = 0; it < iterations; ++it) {
      std::vector<Point> next(n);
      for (std::size_t i = 0; i < n; ++i) {
        const Point &a = m.point(loop[(i + n - 1) % n]), &b = m.point(loop[i]), &c = m.point(loop[(i + 1) % n]);
        next[i] = Point(0.25 * a.x() + 0.5 * b.x() + 0.25 * c.x(), 0.25 * a.y() + 0.5 * b.y() + 0.25 * c.y(),
                        0.25 * a.z() + 0.5 * b.z() + 0.25 * c.z());
      }
      for (std::size_t i = 0; i < n; ++i) m.point(loop[i]) = next[i];
    }
  }
}

// The quality of mesh/quality.hpp on CGAL points.
double triangle_quality(const Point& a, const Point& b, const Point& c) {
  auto v = [](const Point& p) { return Vec3(p.x(), p.y(), p.z()); };
  return valve::triangle_quality(v(a), v(b), v(c));
}

double face_quality(const Mesh& m, Mesh::Face_index f) {
  std::array<Point, 3> p;
  int k = 0;
  for (auto v : CGAL::vertices_around_face(m.halfedge(f), m)) p[k++] = m.point(v);
  return triangle_quality(p[0], p[1], p[2]);
}

// The worst quality of the triangles around vertex v.
double worst_quality_around(const Mesh& m, Mesh::Vertex_index v) {
  double q = 1;
  for (auto f : CGAL::faces_around_target(m.halfedge(v), m))
    if (f != Mesh::null_face()) q = std::min(q, face_quality(m, f));
  return q;
}

using Tree = CGAL::AABB_tree<CGAL::AABB_traits<K, CGAL::AABB_face_graph_triangle_primitive<Mesh>>>;

using Segments = std::vector<K::Segment_3>;
using SegmentTree = CGAL::AABB_tree<CGAL::AABB_traits<K, CGAL::AABB_segment_primitive<K, Segments::const_iterator>>>;

Segments border_segments(const Mesh& m) {
  Segments out;
  for (auto h : m.halfedges())
    if (m.is_border(h)) out.emplace_back(m.point(m.source(h)), m.point(m.target(h)));
  return out;
}

// Moves border vertices back onto the input's border (their closest point there), each as
// far as its triangles stay at or above min_quality + kSnapQualityHeadroom (or no worse than
// before): the whole way, or 3/4, 1/2, 1/4 of it. Returns the number of vertices moved. Isotropic remeshing relaxes border vertices along the coarse
// border it has made and projects only interior ones back onto the input, and the collapse
// route places border vertices at edge midpoints: on the Texas TriValve deck's mid-surface
// (0.5 mm border edges, 2.3 mm target) the border vertices ended 1.0-1.1 mm off the input
// surface, the interior ones 0.02 mm. Snapping them all the way left 0.1-0.4-quality
// slivers where the border turns within an edge length (notches between scallops). The
// headroom above min_quality is for the mid-surface offset that follows, which bends border
// triangles further (without it the closed TTV frame ended with a 0.35-quality triangle).
constexpr double kSnapQualityHeadroom = 0.1;
int snap_border_vertices(Mesh& m, const SegmentTree& border, double min_quality) {
  int moved = 0;
  for (auto v : m.vertices()) {
    if (!m.is_border(v)) continue;
    const Point old = m.point(v), target = border.closest_point(old);
    const double floor = std::min(min_quality + kSnapQualityHeadroom, worst_quality_around(m, v));
    for (double t : {1.0, 0.75, 0.5, 0.25}) {
      m.point(v) = old + t * (target - old);
      if (worst_quality_around(m, v) >= floor) break;
      m.point(v) = old;
    }
    moved += m.point(v) != old;
  }
  return moved;
}

// Moves the vertices of the remaining slivers to the centroid of their neighbours, projected
// back onto the input surface, where that raises the worst incident triangle.
int relax_sliver_vertices(Mesh& m, const Tree& surface, double min_quality) {
  int moved = 0;
  for (int pass = 0; pass < 5; ++pass) {
    int changed = 0;
    for (auto f : m.faces()) {
      if (face_quality(m, f) >= min_quality) continue;
      for (auto v : CGAL::vertices_around_face(m.halfedge(f), m)) {
        // Interior vertices go toward their neighbours' centroid, border vertices toward
        // the midpoint of their two border neighbours (sliding along the border).
        double x = 0, y = 0, z = 0;
        int n = 0;
        for (auto h : CGAL::halfedges_around_target(v, m)) {
          if (m.is_border(v) && !m.is_border(h) && !m.is_border(m.opposite(h))) continue;
          const Point& p = m.point(m.source(h));
          x += p.x(), y += p.y(), z += p.z(), ++n;
        }
        if (n == 0) continue;
        const Point old = m.point(v);
        const double before = worst_quality_around(m, v);
        m.point(v) = surface.closest_point(Point(x / n, y / n, z / n));
        if (worst_quality_around(m, v) > before) ++changed;
        else m.point(v) = old;
      }
    }
    moved += changed;
    if (changed == 0) break;
  }
  return moved;
}

// Removes the slivers isotropic remeshing leaves along a border, where it may not flip:
// an "ear" (two border edges, nearly straight angle) is cut off; an interior vertex almost on
// a border edge is merged into the nearer border vertex. Returns the number of repairs.
int repair_border_slivers(Mesh& m, double min_quality) {
  int repairs = 0;
  for (int pass = 0; pass < 10; ++pass) {
    std::vector<Mesh::Face_index> bad;
    for (auto f : m.faces())
      if (face_quality(m, f) < min_quality) bad.push_back(f);
    int changed = 0;
    for (auto f : bad) {
      if (m.is_removed(f) || face_quality(m, f) >= min_quality) continue;
      std::vector<Mesh::Halfedge_index> border;
      for (auto h : CGAL::halfedges_around_face(m.halfedge(f), m))
        if (m.is_border(m.opposite(h))) border.push_back(h);
      if (border.size() == 2) {
        CGAL::Euler::remove_face(m.halfedge(f), m);
        ++changed;
      } else if (border.size() == 1) {
        const auto hb = border[0];  // a -> b on the border; c the opposite vertex
        const auto to_a = m.next(m.next(hb)), to_b = m.opposite(m.next(hb));  // c -> a, c -> b
        const Point& c = m.point(m.source(to_a));
        const auto e = CGAL::squared_distance(c, m.point(m.target(to_a))) < CGAL::squared_distance(c, m.point(m.target(to_b))) ? to_a : to_b;
        if (m.is_border(m.opposite(e)) || !CGAL::Euler::does_satisfy_link_condition(m.edge(e), m)) continue;
        bool interior = true;  // merging a border vertex into another would pinch the border
        for (auto h : CGAL::halfedges_around_target(m.source(e), m)) interior = interior && !m.is_border(h) && !m.is_border(m.opposite(h));
        if (!interior) continue;
        const Point keep = m.point(m.target(e));
        const auto v = CGAL::Euler::collapse_edge(m.edge(e), m);
        m.point(v) = keep;
        ++changed;
      } else {
        // An interior edge bridging two border vertices (at a concave corner): flip the
        // face's longest edge if that raises the worse of the two triangles.
        Mesh::Halfedge_index longest;
        double best = -1;
        for (auto h : CGAL::halfedges_around_face(m.halfedge(f), m)) {
          const double len = CGAL::squared_distance(m.point(m.source(h)), m.point(m.target(h)));
          if (len > best) best = len, longest = h;
        }
        if (m.is_border(m.opposite(longest))) continue;
        const Point &a = m.point(m.source(longest)), &b = m.point(m.target(longest));
        const Point &c = m.point(m.target(m.next(longest))), &d = m.point(m.target(m.next(m.opposite(longest))));
        if (CGAL::Euler::does_satisfy_link_condition(m.edge(longest), m) == false) continue;
        bool exists = false;
        for (auto v : CGAL::vertices_around_target(m.target(m.next(longest)), m)) exists = exists || v == m.target(m.next(m.opposite(longest)));
        if (exists) continue;
        const double before = std::min(face_quality(m, f), face_quality(m, m.face(m.opposite(longest))));
        // After the flip the triangles are (c, d, b)... sharing edge c-d; orientation is kept by Euler::flip_edge.
        const double after = std::min(triangle_quality(c, d, b), triangle_quality(d, c, a));
        // Refuse flips that fold the surface: the new triangles' normals must agree.
        const auto n1 = CGAL::cross_product(d - c, b - c), n2 = CGAL::cross_product(c - d, a - d);
        if (after > before && n1 * n2 > 0) {
          CGAL::Euler::flip_edge(longest, m);
          ++changed;
        }
      }
    }
    repairs += changed;
    if (changed == 0) break;
  }
  m.collect_garbage();
  return repairs;
}

// Cuts off flaps: pieces of the membrane joined to the rest only through an interior edge
// whose two ends lie on the border and that is shorter than `max_neck`. Such necks come from
// slits in the extracted atrial face (two voxel-scale border points almost touching); no
// flip or collapse can make their triangles well shaped, and cutting the flap loses at most
// `max_flap_faces` triangles of membrane. Returns the number of triangles removed.
int cut_narrow_flaps(Mesh& m, double max_neck, std::size_t max_flap_faces) {
  int removed = 0;
  for (bool again = true; again;) {
    again = false;
    for (auto e : m.edges()) {
      const auto h = m.halfedge(e);
      if (m.is_border(h) || m.is_border(m.opposite(h)) || !m.is_border(m.source(h)) || !m.is_border(m.target(h))) continue;
      if (CGAL::squared_distance(m.point(m.source(h)), m.point(m.target(h))) >= max_neck * max_neck) continue;
      // Flood each side without crossing the neck; a side that stays small and never
      // reaches the other side is a flap.
      for (auto start : {h, m.opposite(h)}) {
        std::vector<Mesh::Face_index> flap{m.face(start)}, stack{m.face(start)};
        std::set<Mesh::Face_index> seen{m.face(start)};
        bool separated = true;
        while (!stack.empty() && separated && flap.size() <= max_flap_faces) {
          const auto f = stack.back();
          stack.pop_back();
          for (auto g : CGAL::halfedges_around_face(m.halfedge(f), m)) {
            if (m.edge(g) == e || m.is_border(m.opposite(g))) continue;
            const auto next = m.face(m.opposite(g));
            if (next == m.face(m.opposite(start))) separated = false;
            if (seen.insert(next).second) flap.push_back(next), stack.push_back(next);
          }
        }
        if (!separated || flap.size() > max_flap_faces) continue;
        for (auto f : flap) CGAL::Euler::remove_face(m.halfedge(f), m);
        removed += static_cast<int>(flap.size());
        again = true;
        break;
      }
      if (again) break;
    }
    m.collect_garbage();
  }
  return removed;
}

}  // namespace

void RemeshOptions::validate(const std::string& where) const {
  if (target_triangles < 8 || target_triangles > 10000000)
    throw_input_error(where, "triangles", "a target count in 8..1e7", std::to_string(target_triangles));
  if (method != "isotropic" && method != "collapse") throw_input_error(where, "method", "isotropic|collapse", "\"" + method + "\"");
  if (!(tolerance > 0 && tolerance < 1)) throw_input_error(where, "tolerance", "a fraction in (0, 1)", std::to_string(tolerance));
  if (iterations < 1 || iterations > 100) throw_input_error(where, "iterations", "1..100", std::to_string(iterations));
  if (relaxation_steps < 0 || relaxation_steps > 100) throw_input_error(where, "relaxation_steps", "0..100", std::to_string(relaxation_steps));
  if (!(max_neck >= 0 && max_neck < 1)) throw_input_error(where, "max_neck", "a fraction of the edge length in [0, 1)", std::to_string(max_neck));
  if (!(min_border_quality >= 0 && min_border_quality < 1)) throw_input_error(where, "min_border_quality", "a quality in [0, 1)", std::to_string(min_border_quality));
  if (max_attempts < 1 || max_attempts > 50) throw_input_error(where, "max_attempts", "1..50", std::to_string(max_attempts));
}

TriMesh remesh_membrane(const TriMesh& membrane, const RemeshOptions& o, RemeshSummary* summary) {
  o.validate("remesh");
  RemeshSummary s;
  s.input_triangles = membrane.num_triangles();
  if (membrane.num_triangles() == 0) throw_input_error("remesh", "membrane", "a surface with triangles", "none");
  Mesh input = to_cgal(membrane);
  s.holes_filled = fill_small_holes(input, o.max_hole_fraction);
  smooth_borders(input, o.border_smoothing);
  const double area = PMP::area(input);
  Tree tree(faces(input).first, faces(input).second, input);
  tree.accelerate_distance_queries();
  const Segments input_border = border_segments(input);
  SegmentTree border_tree(input_border.begin(), input_border.end());
  border_tree.accelerate_distance_queries();
  const int target = o.target_triangles;
  // What remeshing leaves at the border, in order: narrow-necked flaps, slivers, and slivers'
  // vertices that can still move. Returns the triangles cut; counts repairs in s.
  auto clean_up = [&](Mesh& m, double edge_length) {
    s.border_snapped = input_border.empty() ? 0 : snap_border_vertices(m, border_tree, o.min_border_quality);
    PMP::angle_and_area_smoothing(faces(m), m, PMP::parameters::number_of_iterations(5).use_area_smoothing(false));
    const int cut = cut_narrow_flaps(m, o.max_neck * edge_length, 8);
    s.border_repairs = repair_border_slivers(m, o.min_border_quality);
    s.border_repairs += relax_sliver_vertices(m, tree, o.min_border_quality);
    return cut;
  };

  Mesh best;
  std::size_t best_error = std::size_t(-1);
  int repairs = 0, flaps = 0, snapped = 0;
  if (o.method == "isotropic") {
    double length = std::sqrt(4 * area / (std::sqrt(3.0) * target));
    for (int attempt = 0; attempt < o.max_attempts; ++attempt) {
      Mesh m = input;
      PMP::isotropic_remeshing(faces(m), length, m,
                               PMP::parameters::number_of_iterations(static_cast<unsigned>(o.iterations))
                                   .number_of_relaxation_steps(static_cast<unsigned>(o.relaxation_steps))
                                   .relax_constraints(true));
      m.collect_garbage();
      s.flaps_cut = clean_up(m, length);
      ++s.attempts;
      const std::size_t found = m.number_of_faces();
      const std::size_t error = found > std::size_t(target) ? found - target : target - found;
      if (error < best_error) best_error = error, best = m, s.target_edge_length = length, repairs = s.border_repairs, flaps = s.flaps_cut,
                                  snapped = s.border_snapped;
      if (error <= o.tolerance * target || found == 0) break;
      length *= std::sqrt(double(found) / target);
    }
    s.border_repairs = repairs;
    s.flaps_cut = flaps;
    s.border_snapped = snapped;
    s.count_within_tolerance = best_error <= o.tolerance * target;
  } else {
    // Collapse to the edge count of the target: 3F = 2E − B, with the border count B
    // shrinking with the edge length.
    Mesh m = input;
    std::size_t border = 0;
    for (auto h : m.halfedges()) border += m.is_border(h);
    const double shrink = std::sqrt(double(target) / std::max<std::size_t>(1, m.number_of_faces()));
    const auto edges = static_cast<std::size_t>(std::lround((3.0 * target + border * shrink) / 2));
    SMS::Count_stop_predicate<Mesh> stop(edges);
    SMS::edge_collapse(m, stop, CGAL::parameters::get_cost(SMS::Edge_length_cost<Mesh>()).get_placement(SMS::Midpoint_placement<Mesh>()));
    m.collect_garbage();
    PMP::tangential_relaxation(m, PMP::parameters::number_of_iterations(static_cast<unsigned>(10 * o.relaxation_steps)).relax_constraints(true));
    s.flaps_cut = clean_up(m, std::sqrt(4 * area / (std::sqrt(3.0) * target)));
    s.attempts = 1;
    best = m;
  }
  if (best.number_of_faces() == 0) throw NumericalError("remesh: no triangles left after remeshing (the membrane is too small or too thin for the target)");
  if (o.mid_surface_offset != 0) {
    auto normals = best.add_property_map<Mesh::Vertex_index, K::Vector_3>("v:normal").first;
    PMP::compute_vertex_normals(best, normals);
    for (auto v : best.vertices()) best.point(v) = best.point(v) - o.mid_surface_offset * normals[v];
    const Mesh offset = best;
    Tree offset_tree(faces(offset).first, faces(offset).second, offset);
    offset_tree.accelerate_distance_queries();
    s.border_repairs += repair_border_slivers(best, o.min_border_quality);
    s.border_repairs += relax_sliver_vertices(best, offset_tree, o.min_border_quality);
  }
  if (summary) *summary = s;
  return from_cgal(best);
}

}  // namespace valve
