#include "valve/analysis/coaptation.hpp"

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <map>
#include <sstream>

#include "valve/analysis/leaflet_columns.hpp"
#include "valve/analysis/leaflet_metrics.hpp"
#include "valve/analysis/orifice.hpp"
#include "valve/core/error.hpp"

namespace valve {

namespace {

// Exact predicates (rather than Simple_cartesian<double>) make the ray/triangle tests
// watertight: a ray through an edge or vertex shared by two triangles hits at least one of
// them, so a node never looks uncovered because its ray passed exactly between triangles.
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = K::Point_3;
using Segment = K::Segment_3;
using Triangles = std::vector<K::Triangle_3>;
using Primitive = CGAL::AABB_triangle_primitive<K, Triangles::const_iterator>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<K, Primitive>>;

constexpr double kInf = std::numeric_limits<double>::infinity();

// Distance from the ray source to the first hit: a point, or a segment when the ray runs
// inside the triangle's plane (its nearer end is the entry point).
struct HitDistance {
  using result_type = double;
  Point source;
  double operator()(const Point& p) const { return std::sqrt(CGAL::to_double(CGAL::squared_distance(source, p))); }
  double operator()(const Segment& s) const { return std::min((*this)(s.source()), (*this)(s.target())); }
};

// The gap queries, with the CGAL state kept out of the header. Only the trees `measure`
// needs are built: for rays one tree over every triangle (the rays skip their own
// leaflet's hits), for nearest points one per leaflet (CGAL's closest-point query has no skip).
class LeafletSurfaces {
 public:
  LeafletSurfaces(const LeafletSurfaces&) = delete;  // the trees point into the triangle vectors
  LeafletSurfaces& operator=(const LeafletSurfaces&) = delete;
  LeafletSurfaces(const TriMesh& m, const std::vector<int>& tri_leaflet, const VecX& x, GapMeasure measure) {
    for (int t = 0; t < m.num_triangles(); ++t) {
      const Tri& tri = m.triangles[t];
      K::Triangle_3 T(to_point(node3(x, tri[0])), to_point(node3(x, tri[1])), to_point(node3(x, tri[2])));
      if (T.is_degenerate()) continue;  // no area to hit; CGAL's intersection requires a proper triangle
      if (measure == GapMeasure::nearest) {
        per_leaflet_[tri_leaflet[t]].triangles.push_back(T);
      } else {
        triangles_.push_back(T);
        leaflet_.push_back(tri_leaflet[t]);
      }
    }
    tree_.insert(triangles_.begin(), triangles_.end());
    tree_.build();
    for (auto& [id, s] : per_leaflet_) {
      s.tree.insert(s.triangles.begin(), s.triangles.end());
      s.tree.build();
      s.tree.accelerate_distance_queries();
    }
  }

  /// Distance along the ray (p, dir) to the nearest triangle not of leaflet `own`; inf if none.
  double cast(const Vec3& p, const Vec3& dir, int own) const {
    if (triangles_.empty()) return kInf;
    const K::Ray_3 ray(to_point(p), K::Vector_3(dir[0], dir[1], dir[2]));
    const auto skip = [&](const Triangles::const_iterator& id) { return leaflet_[id - triangles_.begin()] == own; };
    const auto hit = tree_.first_intersection(ray, skip);
    if (!hit) return kInf;
#if CGAL_VERSION_NR >= 1060000000
    return std::visit(HitDistance{ray.source()}, hit->first);
#else
    return boost::apply_visitor(HitDistance{ray.source()}, hit->first);
#endif
  }

  /// Distance from p to the nearest point of a triangle not of leaflet `own`; inf if none.
  double nearest(const Vec3& p, int own) const {
    double d2 = kInf;
    for (const auto& [id, s] : per_leaflet_)
      if (id != own) d2 = std::min(d2, CGAL::to_double(s.tree.squared_distance(to_point(p))));
    return std::sqrt(d2);
  }

 private:
  static Point to_point(const Vec3& v) { return Point(v[0], v[1], v[2]); }
  struct Surface {
    Triangles triangles;
    Tree tree;
  };
  Triangles triangles_;
  std::vector<int> leaflet_;  // per entry of triangles_
  Tree tree_;
  std::map<int, Surface> per_leaflet_;
};

// Columns sampled per free edge (plus the two margins and the middle): 0.1 mm apart on the
// aortic valve's 21 mm free edges, finer than any mesh the analysis meets.
constexpr int kColumns = 200;

struct ColumnBand {
  double top = -1;    // mm below the free edge where the band begins; -1 without a band
  double height = 0;  // mm
};

// The band along one column (see "Heights" in the header): the indicator c (1 at coapting,
// unshared nodes, else 0) and the deformed positions x are interpolated at each crossing;
// between two crossings both are linear (one triangle, affine in it), so the band's ends,
// where c passes 0.5, are placed exactly on the piecewise-linear interpolant.
ColumnBand column_band(const std::vector<EdgePoint>& path, const VecX& x, const std::vector<double>& c, double offset) {
  ColumnBand band;
  double length = 0, c_prev = 0;
  Vec3 p_prev = Vec3::Zero();
  for (std::size_t i = 0; i < path.size(); ++i) {
    const EdgePoint& e = path[i];
    const Vec3 p = (1 - e.t) * node3(x, e.a) + e.t * node3(x, e.b);
    const double ci = (1 - e.t) * c[e.a] + e.t * c[e.b];
    if (i == 0) {
      if (ci >= 0.5) band.top = 0;
    } else {
      const double seg = (p - p_prev).norm();
      if (band.top < 0 && ci >= 0.5) {
        band.top = length + seg * (0.5 - c_prev) / (ci - c_prev);
        if (band.top > offset) return {};
      } else if (band.top >= 0 && ci < 0.5) {
        band.height = length + seg * (c_prev - 0.5) / (c_prev - ci) - band.top;
        return band;
      }
      length += seg;
    }
    if (band.top < 0 && length > offset) return {};
    c_prev = ci;
    p_prev = p;
  }
  if (band.top >= 0) band.height = length - band.top;  // the band reaches the border
  return band;
}

}  // namespace

void CoaptationOptions::validate() const {
  if (!(threshold_mm > 0) || !std::isfinite(threshold_mm))
    throw_input_error("coaptation", "threshold_mm", "a finite distance > 0 mm", std::to_string(threshold_mm));
  if (!(commissure_margin >= 0 && commissure_margin < 0.5))
    throw_input_error("coaptation", "commissure_margin", "a fraction in [0, 0.5)", std::to_string(commissure_margin));
  if (!(closed_min_height_mm > 0) || !std::isfinite(closed_min_height_mm))
    throw_input_error("coaptation", "closed_min_height_mm", "a finite height > 0 mm", std::to_string(closed_min_height_mm));
  if (!(free_edge_offset_mm >= 0) || !std::isfinite(free_edge_offset_mm))
    throw_input_error("coaptation", "free_edge_offset_mm", "a finite distance >= 0 mm", std::to_string(free_edge_offset_mm));
  if (axis && !axis->valid())
    throw_input_error("coaptation", "axis", "a finite point and a non-zero finite direction", "a degenerate axis");
}

std::string CoaptationResult::report() const {
  std::ostringstream s;
  s << std::fixed << std::setprecision(2) << (closed ? "closed" : "open")
    << (central_gap ? ", central gap" : ", no central gap");
  for (const auto& l : leaflets) {
    s << "; leaflet " << l.leaflet << ": area " << l.area_mm2 << " mm2, midline height " << l.midline_height_mm
      << " mm, min height " << l.min_height_mm << " mm";
    if (l.free_edge_axis_distance_mm >= 0) s << ", free edge " << l.free_edge_axis_distance_mm << " mm from the axis";
  }
  if (orifice_area_mm2 >= 0) s << "; projected orifice " << orifice_area_mm2 << " mm2";
  return s.str();
}

nlohmann::json coaptation_metrics(const CoaptationResult& r, const CoaptationOptions& o) {
  nlohmann::json per = nlohmann::json::array();
  for (const auto& l : r.leaflets)
    per.push_back({{"leaflet", l.leaflet}, {"area_mm2", l.area_mm2}, {"midline_height_mm", l.midline_height_mm},
                   {"midline_band_top_mm", l.midline_band_top_mm}, {"min_height_mm", l.min_height_mm},
                   {"coapting_fraction_of_free_edge", l.coapting_fraction_of_free_edge},
                   {"free_edge_axis_distance_mm", l.free_edge_axis_distance_mm}, {"closed", l.closed}});
  return {{"closed", r.closed},
          {"central_gap", r.central_gap},
          {"min_height_mm", r.min_height_mm},
          {"max_free_edge_axis_distance_mm", r.max_free_edge_axis_distance_mm},
          {"orifice_area_mm2", r.orifice_area_mm2},
          {"gap", to_string(o.gap)},
          {"threshold_mm", o.threshold_mm},
          {"free_edge_offset_mm", o.free_edge_offset_mm},
          {"commissure_margin", o.commissure_margin},
          {"closed_min_height_mm", o.closed_min_height_mm},
          {"leaflets", per}};
}

std::string coaptation_columns_csv(const CoaptationResult& r) {
  std::ostringstream csv;
  csv << std::setprecision(10) << "leaflet,arc_mm,height_mm,band_top_mm\n";
  for (const auto& l : r.leaflets)
    for (std::size_t k = 0; k < l.column_arc_mm.size(); ++k)
      csv << l.leaflet << ',' << l.column_arc_mm[k] << ',' << l.column_height_mm[k] << ',' << l.column_band_top_mm[k] << '\n';
  return csv.str();
}

CoaptationResult analyze_coaptation(const TriMesh& m, const VecX& x, const CoaptationOptions& opt) {
  opt.validate();
  const int n = m.num_nodes();
  const int nt = m.num_triangles();
  if (x.size() != 3 * static_cast<Eigen::Index>(n))
    throw_input_error("coaptation", "positions", std::to_string(3 * n) + " entries (3 per node)",
                      std::to_string(x.size()));
  if (!x.allFinite()) throw_input_error("coaptation", "positions", "finite coordinates", "NaN or inf");
  if (static_cast<int>(m.boundary.size()) != n)
    throw_input_error("coaptation", "BoundaryType", std::to_string(n) + " values", std::to_string(m.boundary.size()));
  if (!m.leaflet.empty() && static_cast<int>(m.leaflet.size()) != nt)
    throw_input_error("coaptation", "leaflet", std::to_string(nt) + " values", std::to_string(m.leaflet.size()));
  const std::vector<int> tri_leaflet = m.leaflet.empty() ? std::vector<int>(nt, 0) : m.leaflet;
  for (int l : tri_leaflet)
    if (l < 0) throw_input_error("coaptation", "leaflet", "indices >= 0", std::to_string(l));

  // Leaflets of each node and the own-leaflet area-weighted normal (Σ of edge cross
  // products, each twice its triangle's area times its unit normal).
  std::vector<std::vector<int>> node_leaflets(n);
  std::vector<Vec3> normal(n, Vec3::Zero());
  for (int t = 0; t < nt; ++t)
    for (int k = 0; k < 3; ++k) node_leaflets[m.triangles[t][k]].push_back(tri_leaflet[t]);
  for (auto& list : node_leaflets) {
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
  }
  for (int t = 0; t < nt; ++t) {
    const Tri& tri = m.triangles[t];
    const Vec3 a = node3(x, tri[0]), b = node3(x, tri[1]), c = node3(x, tri[2]);
    const Vec3 area_normal = (b - a).cross(c - a);
    for (int k = 0; k < 3; ++k)
      if (node_leaflets[tri[k]].size() == 1) normal[tri[k]] += area_normal;
  }

  // Gaps.
  CoaptationResult r;
  r.gap_mm.assign(n, kCoaptationNoHit);
  r.coapting.assign(n, 0);
  std::vector<char> shared(n, 0);
  const LeafletSurfaces surfaces(m, tri_leaflet, x, opt.gap);
  for (int i = 0; i < n; ++i) {
    double gap = kInf;
    if (node_leaflets[i].size() > 1) {
      gap = 0;
      shared[i] = 1;
    } else if (node_leaflets[i].size() == 1 && opt.gap == GapMeasure::nearest) {
      gap = surfaces.nearest(node3(x, i), node_leaflets[i][0]);
    } else if (node_leaflets[i].size() == 1 && normal[i].norm() > 0) {
      const Vec3 dir = normal[i].normalized();
      const Vec3 p = node3(x, i);
      gap = std::min(surfaces.cast(p, dir, node_leaflets[i][0]), surfaces.cast(p, -dir, node_leaflets[i][0]));
    }
    if (std::isfinite(gap)) r.gap_mm[i] = gap;
    r.coapting[i] = gap <= opt.threshold_mm ? 1 : 0;
  }

  // Per leaflet.
  std::vector<int> ids = tri_leaflet;
  std::sort(ids.begin(), ids.end());
  ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
  // Heights only over coapting, unshared nodes.
  std::vector<double> band_indicator(n, 0.0);
  for (int i = 0; i < n; ++i) band_indicator[i] = r.coapting[i] && !shared[i] ? 1.0 : 0.0;
  for (int id : ids) {
    LeafletCoaptation lc;
    lc.leaflet = id;
    for (int t = 0; t < nt; ++t)
      if (tri_leaflet[t] == id) {
        const Tri& tri = m.triangles[t];
        const double area = 0.5 * (node3(x, tri[1]) - node3(x, tri[0])).cross(node3(x, tri[2]) - node3(x, tri[0])).norm();
        lc.area_mm2 += area * (r.coapting[tri[0]] + r.coapting[tri[1]] + r.coapting[tri[2]]) / 3.0;
      }

    const LeafletColumns columns(m, id);
    lc.free_edge = columns.free_edge();
    lc.middle_node = free_edge_middle_node(m, id);
    const double total = columns.free_edge_length();
    if (total > 0) {
      const std::vector<double>& arc = columns.free_edge_arc();
      double coapting_length = 0;
      for (std::size_t k = 1; k < lc.free_edge.size(); ++k)
        if (r.coapting[lc.free_edge[k]] && r.coapting[lc.free_edge[k - 1]]) coapting_length += arc[k] - arc[k - 1];
      lc.coapting_fraction_of_free_edge = coapting_length / total;

      // Columns every total / kColumns, at both margins and at the middle; the first corner's
      // column is traced a hair inside the free edge, where it begins.
      const double lo = opt.commissure_margin * total, hi = total - lo, middle = 0.5 * total;
      std::vector<double> samples{lo, hi, middle};
      // (total * k / kColumns can round past total at k = kColumns, where no column begins.)
      for (int k = 1; k <= kColumns; ++k) samples.push_back(std::min(total * k / kColumns, total));
      // Samples within eps of each other are one column (the margins and the middle usually
      // fall on the even spacing up to rounding), and the margins admit them within eps, so
      // the same valve gives the same columns whatever the rounding of its rest lengths.
      const double eps = 1e-9 * total;
      std::sort(samples.begin(), samples.end());
      samples.erase(std::unique(samples.begin(), samples.end(), [eps](double a, double b) { return b - a <= eps; }),
                    samples.end());
      double min_height = kInf;
      for (double s : samples) {
        const ColumnBand band = column_band(columns.trace(std::max(s, 1e-9 * total)), x, band_indicator,
                                            opt.free_edge_offset_mm);
        lc.column_arc_mm.push_back(s);
        lc.column_height_mm.push_back(band.height);
        lc.column_band_top_mm.push_back(band.top);
        if (s >= lo - eps && s <= hi + eps) min_height = std::min(min_height, band.height);
        if (std::abs(s - middle) <= eps) lc.midline_height_mm = band.height, lc.midline_band_top_mm = band.top;
      }
      lc.min_height_mm = min_height;
      if (opt.axis) {
        const Vec3 u = opt.axis->unit_direction();
        // Closest approach of each free-edge segment to the axis: with q(t) the part of
        // a + t (b - a) - axis point normal to the axis, |q(t)| is smallest at
        // t = clamp(-q(0)·(q(1) - q(0)) / |q(1) - q(0)|², 0, 1).
        auto normal_part = [&](int v) {
          const Vec3 d = node3(x, v) - opt.axis->point;
          return Vec3(d - u * u.dot(d));
        };
        double nearest = normal_part(lc.free_edge.front()).norm();
        for (std::size_t k = 1; k < lc.free_edge.size(); ++k) {
          const Vec3 q0 = normal_part(lc.free_edge[k - 1]), e = normal_part(lc.free_edge[k]) - q0;
          const double ee = e.squaredNorm();
          const double t = ee > 0 ? std::clamp(-q0.dot(e) / ee, 0.0, 1.0) : 0.0;
          nearest = std::min(nearest, (q0 + t * e).norm());
        }
        lc.free_edge_axis_distance_mm = nearest;
      }
    }
    lc.closed = lc.min_height_mm >= opt.closed_min_height_mm;
    if (lc.middle_node >= 0 && !r.coapting[lc.middle_node]) r.central_gap = true;
    r.leaflets.push_back(std::move(lc));
  }
  r.closed = !r.leaflets.empty() &&
             std::all_of(r.leaflets.begin(), r.leaflets.end(), [](const LeafletCoaptation& l) { return l.closed; });
  for (std::size_t k = 0; k < r.leaflets.size(); ++k) {
    r.min_height_mm = k == 0 ? r.leaflets[k].min_height_mm : std::min(r.min_height_mm, r.leaflets[k].min_height_mm);
    r.max_free_edge_axis_distance_mm = std::max(r.max_free_edge_axis_distance_mm, r.leaflets[k].free_edge_axis_distance_mm);
  }
  if (opt.axis) r.orifice_area_mm2 = projected_orifice(m, x, *opt.axis, 0.5 * opt.threshold_mm).area_mm2;
  return r;
}

}  // namespace valve
