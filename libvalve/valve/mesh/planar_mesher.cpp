#include "valve/mesh/planar_mesher.hpp"

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <algorithm>
#include <cmath>

#include "valve/core/error.hpp"
#include "valve/mesh/topology.hpp"

namespace valve {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Vb = CGAL::Triangulation_vertex_base_with_info_2<int, K>;
using Fb = CGAL::Constrained_triangulation_face_base_2<K>;
using Tds = CGAL::Triangulation_data_structure_2<Vb, Fb>;
using CDT = CGAL::Constrained_Delaunay_triangulation_2<K, Tds, CGAL::Exact_predicates_tag>;

std::vector<Tri> triangulate(const std::vector<Vec2>& pts, int num_boundary,
                             const PlanarDomain& domain) {
  CDT cdt;
  std::vector<CDT::Vertex_handle> handles(pts.size());
  for (size_t i = 0; i < pts.size(); ++i) {
    handles[i] = cdt.insert(K::Point_2(pts[i].x(), pts[i].y()));
    handles[i]->info() = static_cast<int>(i);
  }
  for (int i = 0; i < num_boundary; ++i)
    cdt.insert_constraint(handles[i], handles[(i + 1) % num_boundary]);
  std::vector<Tri> tris;
  for (auto f = cdt.finite_faces_begin(); f != cdt.finite_faces_end(); ++f) {
    Tri t(f->vertex(0)->info(), f->vertex(1)->info(), f->vertex(2)->info());
    const Vec2 c = (pts[t[0]] + pts[t[1]] + pts[t[2]]) / 3.0;
    if (domain.signed_distance(c) >= 0) continue;  // outside a non-convex boundary
    const Vec2 a = pts[t[1]] - pts[t[0]], b = pts[t[2]] - pts[t[0]];
    if (a.x() * b.y() - a.y() * b.x() < 0) std::swap(t[1], t[2]);
    tris.push_back(t);
  }
  return tris;
}

// Common spring rest length relative to the current rms edge length. 1.2 (DistMesh's value,
// for free boundaries) over-pressurises a domain whose boundary nodes are fixed: interior
// points jam along the boundary at 2,000+ triangles (mean quality 0.5). 1.1 gave the best
// quality over 229-20,000 triangles (mean 0.98-0.99; tests/mesh/generators_test.cpp).
constexpr double kRestFactor = 1.1;

double signed_area(const Vec2& a, const Vec2& b, const Vec2& c) {
  const Vec2 u = b - a, v = c - a;
  return 0.5 * (u.x() * v.y() - u.y() * v.x());
}

}  // namespace

void jitter_interior(PlanarMesh& m, double amplitude, SplitMix64& rng) {
  std::vector<std::vector<int>> incident(m.points.size());
  for (int t = 0; t < static_cast<int>(m.triangles.size()); ++t)
    for (int k = 0; k < 3; ++k) incident[m.triangles[t][k]].push_back(t);
  // Each interior node slides towards the far edge of one of its triangles, by a random
  // fraction of the way scaled by `amplitude` (in spacings, capped at 0.995 of the way):
  // triangles flatten into slivers but never flip.
  const double min_area = 1e-8 * amplitude * amplitude;
  for (int pass = 0; pass < 8; ++pass)
    for (int i = m.num_boundary; i < static_cast<int>(m.points.size()); ++i) {
      if (incident[i].empty()) continue;
      const Tri& pick = m.triangles[incident[i][static_cast<size_t>(rng.uniform() * incident[i].size()) % incident[i].size()]];
      int a = -1, b = -1;
      for (int k = 0; k < 3; ++k)
        if (pick[k] != i) (a < 0 ? a : b) = pick[k];
      const Vec2 old = m.points[i], target = 0.5 * (m.points[a] + m.points[b]);
      const double f = std::min(0.995, amplitude * rng.uniform() / std::max((target - old).norm(), 1e-300));
      m.points[i] = old + f * (target - old);
      for (int t : incident[i]) {
        const Tri& tri = m.triangles[t];
        if (signed_area(m.points[tri[0]], m.points[tri[1]], m.points[tri[2]]) < min_area) {
          m.points[i] = old;
          break;
        }
      }
    }
}

double SplitMix64::uniform() {
  std::uint64_t z = (state_ += 0x9e3779b97f4a7c15ULL);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  z ^= z >> 31;
  return static_cast<double>(z >> 11) * 0x1.0p-53;
}

PlanarMesh mesh_planar_domain(const PlanarDomain& domain, const PlanarMeshOptions& opt) {
  if (opt.target_triangles < 2)
    throw InputError("mesh generator: target_triangles: expected >= 2, found " +
                     std::to_string(opt.target_triangles));
  // Equilateral triangles of side s tile the area A with T = A / (√3/4 s²) triangles.
  // A triangulated polygon with Nb boundary and Ni interior nodes has T = 2 Ni + Nb - 2.
  const double s = std::sqrt(4.0 * domain.area / (std::sqrt(3.0) * opt.target_triangles));
  PlanarMesh out;
  out.points = domain.boundary(s);
  out.num_boundary = static_cast<int>(out.points.size());
  const int num_interior =
      std::max(0, static_cast<int>(std::lround((opt.target_triangles - out.num_boundary + 2) / 2.0)));

  // Bounding box of the boundary for rejection sampling.
  Vec2 lo = out.points[0], hi = out.points[0];
  for (const auto& p : out.points) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  SplitMix64 rng(opt.seed);
  const double margin = 0.3 * s;
  int guard = 0;
  while (static_cast<int>(out.points.size()) < out.num_boundary + num_interior) {
    const Vec2 p(lo.x() + (hi.x() - lo.x()) * rng.uniform(), lo.y() + (hi.y() - lo.y()) * rng.uniform());
    if (domain.signed_distance(p) < -margin) out.points.push_back(p);
    if (++guard > 1000 * (num_interior + 10))
      throw InputError("mesh generator: the domain is too thin for the requested triangle count");
  }

  const int n = static_cast<int>(out.points.size());
  std::vector<Vec2> force(n);
  for (out.iterations = 1; out.iterations <= opt.max_iterations; ++out.iterations) {
    out.triangles = triangulate(out.points, out.num_boundary, domain);
    const auto edges = unique_edges(out.triangles);
    // Relax with the connectivity fixed, then re-triangulate.
    double largest_move = 0;
    for (int inner = 0; inner < 20; ++inner) {
      double sum_l2 = 0;
      for (const auto& e : edges) sum_l2 += (out.points[e.first] - out.points[e.second]).squaredNorm();
      const double rest = kRestFactor * std::sqrt(sum_l2 / edges.size());
      std::fill(force.begin(), force.end(), Vec2::Zero());
      for (const auto& e : edges) {
        const Vec2 d = out.points[e.first] - out.points[e.second];
        const double l = d.norm();
        if (l <= 0 || l >= rest) continue;
        const Vec2 f = (rest - l) / l * d;
        force[e.first] += f;
        force[e.second] -= f;
      }
      largest_move = 0;
      for (int i = out.num_boundary; i < n; ++i) {
        const Vec2 step = 0.2 * force[i];
        Vec2 moved = out.points[i] + step;
        // A point pushed into the band along the fixed boundary is projected back onto the
        // band's inner edge along the distance gradient (as DistMesh projects onto the
        // boundary), so the spring pressure cannot jam points against the boundary.
        const double d = domain.signed_distance(moved);
        if (d > -margin) {
          const double e = 1e-6 * s;
          const Vec2 g((domain.signed_distance(moved + Vec2(e, 0)) - domain.signed_distance(moved - Vec2(e, 0))) / (2 * e),
                       (domain.signed_distance(moved + Vec2(0, e)) - domain.signed_distance(moved - Vec2(0, e))) / (2 * e));
          if (g.squaredNorm() > 1e-12) moved -= (d + margin) * g / g.squaredNorm();
          if (domain.signed_distance(moved) > -0.5 * margin) continue;  // a corner: keep the point
        }
        largest_move = std::max(largest_move, (moved - out.points[i]).norm());
        out.points[i] = moved;
      }
    }
    if (largest_move < opt.move_tolerance * s) break;
  }
  out.iterations = std::min(out.iterations, opt.max_iterations);
  out.triangles = triangulate(out.points, out.num_boundary, domain);
  if (opt.jitter > 0) jitter_interior(out, opt.jitter * s, rng);
  return out;
}

}  // namespace valve
