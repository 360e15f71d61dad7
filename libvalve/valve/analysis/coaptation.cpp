#include "valve/analysis/coaptation.hpp"

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <functional>
#include <iomanip>
#include <limits>
#include <map>
#include <queue>
#include <sstream>

#include "valve/analysis/leaflet_metrics.hpp"
#include "valve/core/error.hpp"
#include "valve/mesh/topology.hpp"

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

// Multi-source Dijkstra over the edges `adj` from `sources`: distance to and index (into
// `sources`) of the nearest source per node; -1 for nodes not reached.
void nearest_source(const std::vector<std::vector<std::pair<int, double>>>& adj, const std::vector<int>& sources,
                    std::vector<double>& dist, std::vector<int>& src) {
  dist.assign(adj.size(), kInf);
  src.assign(adj.size(), -1);
  using Item = std::pair<double, int>;
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> queue;
  for (size_t k = 0; k < sources.size(); ++k)
    if (src[sources[k]] < 0) {  // a closed polyline lists its start twice: keep the first
      dist[sources[k]] = 0;
      src[sources[k]] = static_cast<int>(k);
      queue.push({0.0, sources[k]});
    }
  while (!queue.empty()) {
    const auto [d, v] = queue.top();
    queue.pop();
    if (d > dist[v]) continue;
    for (const auto& [w, len] : adj[v])
      if (d + len < dist[w]) {
        dist[w] = d + len;
        src[w] = src[v];
        queue.push({dist[w], w});
      }
  }
}

}  // namespace

void CoaptationOptions::validate() const {
  if (!(threshold_mm > 0) || !std::isfinite(threshold_mm))
    throw_input_error("coaptation", "threshold_mm", "a finite distance > 0 mm", std::to_string(threshold_mm));
  if (!(commissure_margin >= 0 && commissure_margin < 0.5))
    throw_input_error("coaptation", "commissure_margin", "a fraction in [0, 0.5)", std::to_string(commissure_margin));
  if (!(free_edge_offset_mm >= 0) || !std::isfinite(free_edge_offset_mm))
    throw_input_error("coaptation", "free_edge_offset_mm", "a finite distance >= 0 mm", std::to_string(free_edge_offset_mm));
  // stableNorm: a finite direction of any size, 1e-170 or 1e200, is a direction.
  const double length = axis ? axis->direction.stableNorm() : 1.0;
  if (axis && (!axis->point.allFinite() || !(length > 0) || !std::isfinite(length)))
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
          {"gap", to_string(o.gap)},
          {"threshold_mm", o.threshold_mm},
          {"free_edge_offset_mm", o.free_edge_offset_mm},
          {"commissure_margin", o.commissure_margin},
          {"leaflets", per}};
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
  const VecX X = flatten(m.points);
  std::vector<std::vector<std::pair<int, double>>> adj(n);
  std::vector<double> dist;
  std::vector<int> src, component(n);
  for (int id : ids) {
    LeafletCoaptation lc;
    lc.leaflet = id;
    std::vector<Tri> tris;
    for (int t = 0; t < nt; ++t)
      if (tri_leaflet[t] == id) {
        const Tri& tri = m.triangles[t];
        tris.push_back(tri);
        const double area = 0.5 * (node3(x, tri[1]) - node3(x, tri[0])).cross(node3(x, tri[2]) - node3(x, tri[0])).norm();
        lc.area_mm2 += area * (r.coapting[tri[0]] + r.coapting[tri[1]] + r.coapting[tri[2]]) / 3.0;
      }

    lc.free_edge = free_edge_polyline(m, id);
    lc.middle_node = free_edge_middle_node(m, id);
    const int nf = static_cast<int>(lc.free_edge.size());
    lc.height_mm.assign(nf, 0.0);
    lc.band_top_mm.assign(nf, -1.0);
    if (nf > 0) {
      // Deformed edge graph of this leaflet; heights only over coapting, unshared nodes.
      for (auto& list : adj) list.clear();
      for (const auto& [a, b] : unique_edges(tris)) {
        const double len = (node3(x, a) - node3(x, b)).norm();
        adj[a].push_back({b, len});
        adj[b].push_back({a, len});
      }
      nearest_source(adj, lc.free_edge, dist, src);
      auto counts = [&](int v) { return r.coapting[v] && !shared[v]; };
      std::fill(component.begin(), component.end(), -1);
      int ncomp = 0;
      for (int seed = 0; seed < n; ++seed) {
        if (!counts(seed) || adj[seed].empty() || component[seed] >= 0) continue;
        std::vector<int> stack{seed};
        component[seed] = ncomp;
        while (!stack.empty()) {
          const int v = stack.back();
          stack.pop_back();
          for (const auto& e : adj[v])
            if (counts(e.first) && component[e.first] < 0) component[e.first] = ncomp, stack.push_back(e.first);
        }
        ++ncomp;
      }
      // Per column: the coapting node nearest the free edge picks the band.
      std::vector<int> band(nf, -1);
      for (int v = 0; v < n; ++v) {
        if (component[v] < 0 || src[v] < 0 || dist[v] > opt.free_edge_offset_mm) continue;
        const int k = src[v];
        if (band[k] < 0 || dist[v] < lc.band_top_mm[k]) band[k] = component[v], lc.band_top_mm[k] = dist[v];
      }
      for (int v = 0; v < n; ++v) {
        if (component[v] < 0 || src[v] < 0 || component[v] != band[src[v]]) continue;
        lc.height_mm[src[v]] = std::max(lc.height_mm[src[v]], dist[v] - lc.band_top_mm[src[v]]);
      }

      // Rest arc length along the free edge for the margins and the coapting fraction.
      std::vector<double> arc(nf, 0.0);
      double coapting_length = 0;
      for (int k = 1; k < nf; ++k) {
        const double seg = (node3(X, lc.free_edge[k]) - node3(X, lc.free_edge[k - 1])).norm();
        arc[k] = arc[k - 1] + seg;
        if (r.coapting[lc.free_edge[k]] && r.coapting[lc.free_edge[k - 1]]) coapting_length += seg;
      }
      const double total = arc.back();
      lc.coapting_fraction_of_free_edge = total > 0 ? coapting_length / total : 0.0;
      // Inclusive margins, with a rounding allowance so that a node lying exactly on a
      // margin is not dropped or kept depending on the last bit of the arc length.
      const double lo = opt.commissure_margin * total * (1 - 1e-12), hi = total - lo;
      double min_height = kInf;
      for (int k = 0; k < nf; ++k)
        if (arc[k] >= lo && arc[k] <= hi) min_height = std::min(min_height, lc.height_mm[k]);
      for (int k = 0; k < nf; ++k)
        if (lc.free_edge[k] == lc.middle_node) {
          lc.midline_height_mm = lc.height_mm[k];
          lc.midline_band_top_mm = lc.band_top_mm[k];
          break;
        }
      lc.min_height_mm = std::isfinite(min_height) ? min_height : lc.midline_height_mm;
      if (opt.axis) {
        const Vec3 u = opt.axis->direction / opt.axis->direction.stableNorm();
        double nearest = kInf;
        for (int v : lc.free_edge) {
          const Vec3 d = node3(x, v) - opt.axis->point;
          nearest = std::min(nearest, (d - u * u.dot(d)).norm());
        }
        lc.free_edge_axis_distance_mm = nearest;
      }
    }
    lc.closed = lc.min_height_mm > 0;
    if (lc.middle_node >= 0 && !r.coapting[lc.middle_node]) r.central_gap = true;
    r.leaflets.push_back(std::move(lc));
  }
  r.closed = !r.leaflets.empty() &&
             std::all_of(r.leaflets.begin(), r.leaflets.end(), [](const LeafletCoaptation& l) { return l.closed; });
  for (std::size_t k = 0; k < r.leaflets.size(); ++k) {
    r.min_height_mm = k == 0 ? r.leaflets[k].min_height_mm : std::min(r.min_height_mm, r.leaflets[k].min_height_mm);
    r.max_free_edge_axis_distance_mm = std::max(r.max_free_edge_axis_distance_mm, r.leaflets[k].free_edge_axis_distance_mm);
  }
  return r;
}

}  // namespace valve
