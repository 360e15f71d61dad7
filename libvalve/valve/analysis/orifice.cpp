#include "valve/analysis/orifice.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "valve/core/error.hpp"
#include "valve/mesh/closest_point.hpp"

namespace valve {

namespace {

double cross2(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

double segment_distance2(const Vec2& q, const Vec2& a, const Vec2& b) {
  return (a + point_segment_parameter(q, a, b) * (b - a) - q).squaredNorm();
}

// q inside the triangle (either winding; a degenerate triangle contains nothing) or within
// `r` of its edges.
bool near_triangle(const Vec2& q, const Vec2& a, const Vec2& b, const Vec2& c, double r2) {
  const double s0 = cross2(b - a, q - a), s1 = cross2(c - b, q - b), s2 = cross2(a - c, q - c);
  if ((s0 > 0 && s1 > 0 && s2 > 0) || (s0 < 0 && s1 < 0 && s2 < 0)) return true;
  return segment_distance2(q, a, b) <= r2 || segment_distance2(q, b, c) <= r2 || segment_distance2(q, c, a) <= r2;
}

// A grid over the cross-section's bounding box larger than this many pixels gets coarser
// pixels (a 20 mm root at 0.02 mm has about a million).
constexpr double kMaxPixels = 2e7;

}  // namespace

OrificeResult projected_orifice(const TriMesh& m, const VecX& x, const ValveAxis& axis, double dilation_mm,
                                double pixel_mm) {
  if (!(pixel_mm > 0) || !std::isfinite(pixel_mm))
    throw_input_error("orifice", "pixel_mm", "a finite size > 0 mm", std::to_string(pixel_mm));
  if (!(dilation_mm >= 0) || !std::isfinite(dilation_mm))
    throw_input_error("orifice", "dilation_mm", "a finite distance >= 0 mm", std::to_string(dilation_mm));
  if (!axis.valid()) throw_input_error("orifice", "axis", "a finite point and a non-zero finite direction", "a degenerate axis");
  const int n = m.num_nodes();
  if (x.size() != 3 * static_cast<Eigen::Index>(n))
    throw_input_error("orifice", "positions", std::to_string(3 * n) + " entries (3 per node)", std::to_string(x.size()));
  if (!x.allFinite()) throw_input_error("orifice", "positions", "finite coordinates", "NaN or inf");
  if (static_cast<int>(m.boundary.size()) != n)
    throw_input_error("orifice", "BoundaryType", std::to_string(n) + " values", std::to_string(m.boundary.size()));
  const Vec3 u = axis.unit_direction();
  const Vec3 e1 = u.unitOrthogonal(), e2 = u.cross(e1);
  std::vector<Vec2> p(n);
  for (int i = 0; i < n; ++i) {
    const Vec3 d = node3(x, i) - axis.point;
    p[i] = Vec2(d.dot(e1), d.dot(e2));
  }

  // Cross-section: attached nodes of some triangle, by angle about the axis.
  std::vector<char> used(n, 0);
  for (const Tri& t : m.triangles)
    for (int k = 0; k < 3; ++k) used[t[k]] = 1;
  std::vector<std::pair<double, int>> ring;
  for (int i = 0; i < n; ++i)
    if (used[i] && m.boundary[i] == BoundaryType::attached) ring.push_back({std::atan2(p[i].y(), p[i].x()), i});
  if (ring.size() < 3) return {};
  std::sort(ring.begin(), ring.end());
  // The polygon is the ring in angular order only if the axis passes inside it: then no two
  // neighbouring attached nodes are half a turn or more apart, seen from the axis.
  double widest = 2 * M_PI + ring.front().first - ring.back().first;
  for (std::size_t k = 1; k < ring.size(); ++k) widest = std::max(widest, ring[k].first - ring[k - 1].first);
  if (widest >= M_PI) return {};
  std::vector<Vec2> polygon;
  for (const auto& [angle, i] : ring) polygon.push_back(p[i]);
  const int np = static_cast<int>(polygon.size());
  OrificeResult r;
  double twice_area = 0;
  Vec2 lo = polygon[0], hi = polygon[0];
  for (int k = 0; k < np; ++k) {
    twice_area += cross2(polygon[k], polygon[(k + 1) % np]);
    lo = lo.cwiseMin(polygon[k]);
    hi = hi.cwiseMax(polygon[k]);
  }
  r.cross_section_mm2 = 0.5 * std::abs(twice_area);

  const Vec2 size = hi - lo;
  // Both the area and each side are capped (a ring seen edge-on has a long, thin box).
  const double pixel = std::max({pixel_mm, std::sqrt(size.x() * size.y() / kMaxPixels), size.maxCoeff() / std::sqrt(kMaxPixels)});
  const int nx = std::max(1, static_cast<int>(std::ceil(size.x() / pixel)));
  const int ny = std::max(1, static_cast<int>(std::ceil(size.y() / pixel)));
  const auto centre = [&](int ix, int iy) { return Vec2(lo.x() + (ix + 0.5) * pixel, lo.y() + (iy + 0.5) * pixel); };

  std::vector<char> covered(static_cast<std::size_t>(nx) * ny, 0);
  const double r2 = dilation_mm * dilation_mm;
  for (const Tri& t : m.triangles) {
    const Vec2 &a = p[t[0]], &b = p[t[1]], &c = p[t[2]];
    const Vec2 tlo = a.cwiseMin(b).cwiseMin(c).array() - dilation_mm, thi = a.cwiseMax(b).cwiseMax(c).array() + dilation_mm;
    const int x0 = std::max(0, static_cast<int>(std::floor((tlo.x() - lo.x()) / pixel - 0.5)));
    const int x1 = std::min(nx - 1, static_cast<int>(std::ceil((thi.x() - lo.x()) / pixel - 0.5)));
    const int y0 = std::max(0, static_cast<int>(std::floor((tlo.y() - lo.y()) / pixel - 0.5)));
    const int y1 = std::min(ny - 1, static_cast<int>(std::ceil((thi.y() - lo.y()) / pixel - 0.5)));
    for (int iy = y0; iy <= y1; ++iy)
      for (int ix = x0; ix <= x1; ++ix) {
        char& cell = covered[static_cast<std::size_t>(iy) * nx + ix];
        if (!cell && near_triangle(centre(ix, iy), a, b, c, r2)) cell = 1;
      }
  }

  // Uncovered pixel centres inside the polygon, row by row (even-odd spans).
  long open = 0;
  std::vector<double> xs;
  for (int iy = 0; iy < ny; ++iy) {
    const double y = lo.y() + (iy + 0.5) * pixel;
    xs.clear();
    for (int k = 0; k < np; ++k) {
      const Vec2 &a = polygon[k], &b = polygon[(k + 1) % np];
      if ((a.y() <= y) != (b.y() <= y)) xs.push_back(a.x() + (y - a.y()) / (b.y() - a.y()) * (b.x() - a.x()));
    }
    std::sort(xs.begin(), xs.end());
    for (std::size_t k = 0; k + 1 < xs.size(); k += 2) {
      const int from = std::max(0, static_cast<int>(std::ceil((xs[k] - lo.x()) / pixel - 0.5)));
      const int to = std::min(nx - 1, static_cast<int>(std::floor((xs[k + 1] - lo.x()) / pixel - 0.5)));
      for (int ix = from; ix <= to; ++ix) open += !covered[static_cast<std::size_t>(iy) * nx + ix];
    }
  }
  r.area_mm2 = static_cast<double>(open) * pixel * pixel;
  return r;
}

}  // namespace valve
