#include "valve/analysis/orifice.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "valve/core/error.hpp"

namespace valve {

namespace {

double cross2(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

// The x-range, at height y, of the points within r of segment (a, b) (a capsule: convex, so
// its section is one interval); false where the line misses it.
bool capsule_span(const Vec2& a, const Vec2& b, double r, double y, double& lo, double& hi) {
  lo = std::numeric_limits<double>::infinity(), hi = -lo;
  auto include = [&](double from, double to) {
    if (from <= to) lo = std::min(lo, from), hi = std::max(hi, to);
  };
  // The end discs.
  for (const Vec2& c : {a, b}) {
    const double dy = y - c.y(), h2 = r * r - dy * dy;
    if (h2 >= 0) include(c.x() - std::sqrt(h2), c.x() + std::sqrt(h2));
  }
  // The band between them: the projection onto the segment within [0, 1] and the distance
  // from its line within r, each linear in x (or constant along a row).
  const Vec2 d = b - a;
  const double length2 = d.squaredNorm();
  if (length2 > 0) {
    double from = -std::numeric_limits<double>::infinity(), to = -from;
    auto clip = [&](double slope, double offset, double low, double high) {  // low <= slope x + offset <= high
      if (slope == 0) {
        if (offset < low || offset > high) from = 1, to = 0;
        return;
      }
      double x0 = (low - offset) / slope, x1 = (high - offset) / slope;
      if (x0 > x1) std::swap(x0, x1);
      from = std::max(from, x0), to = std::min(to, x1);
    };
    // t = ((x − a.x) d.x + (y − a.y) d.y) / |d|², cross = d.x (y − a.y) − d.y (x − a.x).
    clip(d.x() / length2, (-a.x() * d.x() + (y - a.y()) * d.y()) / length2, 0.0, 1.0);
    const double length = std::sqrt(length2);
    clip(-d.y() / length, (d.x() * (y - a.y()) + d.y() * a.x()) / length, -r, r);
    include(from, to);
  }
  return lo <= hi;
}

// The x-range, at height y, of the points inside triangle (a, b, c) or within r of its edges
// (convex: one interval); false where the line misses it.
bool dilated_triangle_span(const Vec2& a, const Vec2& b, const Vec2& c, double r, double y, double& lo, double& hi) {
  lo = std::numeric_limits<double>::infinity(), hi = -lo;
  const Vec2* corners[3] = {&a, &b, &c};
  for (int k = 0; k < 3; ++k) {
    const Vec2 &p = *corners[k], &q = *corners[(k + 1) % 3];
    if ((p.y() <= y) != (q.y() <= y)) {  // the edge crosses the row: the triangle's own section
      const double x = p.x() + (y - p.y()) / (q.y() - p.y()) * (q.x() - p.x());
      lo = std::min(lo, x), hi = std::max(hi, x);
    }
    double from = 0, to = 0;
    if (capsule_span(p, q, r, y, from, to)) lo = std::min(lo, from), hi = std::max(hi, to);
  }
  return lo <= hi;
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
  // Each dilated triangle row by row: the pixels whose centres lie in its section of that row.
  for (const Tri& t : m.triangles) {
    const Vec2 &a = p[t[0]], &b = p[t[1]], &c = p[t[2]];
    const double tlo = std::min({a.y(), b.y(), c.y()}) - dilation_mm, thi = std::max({a.y(), b.y(), c.y()}) + dilation_mm;
    const int y0 = std::max(0, static_cast<int>(std::floor((tlo - lo.y()) / pixel - 0.5)));
    const int y1 = std::min(ny - 1, static_cast<int>(std::ceil((thi - lo.y()) / pixel - 0.5)));
    for (int iy = y0; iy <= y1; ++iy) {
      double from = 0, to = 0;
      if (!dilated_triangle_span(a, b, c, dilation_mm, centre(0, iy).y(), from, to)) continue;
      const int x0 = std::max(0, static_cast<int>(std::ceil((from - lo.x()) / pixel - 0.5)));
      const int x1 = std::min(nx - 1, static_cast<int>(std::floor((to - lo.x()) / pixel - 0.5)));
      if (x0 <= x1) std::fill(covered.begin() + static_cast<std::ptrdiff_t>(iy) * nx + x0,
                              covered.begin() + static_cast<std::ptrdiff_t>(iy) * nx + x1 + 1, 1);
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
