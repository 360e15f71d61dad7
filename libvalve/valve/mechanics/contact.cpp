#include "valve/mechanics/contact.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "valve/core/error.hpp"
#include "valve/mechanics/contact_base.hpp"
#include "valve/mesh/topology.hpp"

namespace valve {
namespace {

/// Where a node sits relative to a triangle's plane.
struct PlaneGeometry {
  Vec3 n;            // unit winding normal
  double area2;      // |c| = twice the area
  double d;          // n · (p − x_a)
  Vec3 barycentric;  // of p's projection
};

PlaneGeometry plane_geometry(const VecX& x, const Tri& t, const Vec3& p) {
  const Vec3 xa = node3(x, t[0]), e1 = node3(x, t[1]) - xa, e2 = node3(x, t[2]) - xa;
  const Vec3 c = e1.cross(e2);
  PlaneGeometry g;
  g.area2 = c.norm();
  g.n = g.area2 > 0 ? Vec3(c / g.area2) : Vec3::Zero();
  const Vec3 r = p - xa;
  g.d = g.n.dot(r);
  // Barycentric coordinates of the projection from sub-triangle areas.
  const double inv = g.area2 > 0 ? 1.0 / (g.area2 * g.area2) : 0.0;
  const double wb = c.dot(r.cross(e2)) * inv, wc = c.dot(e1.cross(r)) * inv;
  g.barycentric = Vec3(1 - wb - wc, wb, wc);
  return g;
}

// τ(u) = 1 − 3u² + 2u³ on [0, 1]: 1 → 0 with zero slope at u = 1.
double taper(double u) { return 1 - u * u * (3 - 2 * u); }
double taper_slope(double u) { return 6 * u * (u - 1); }

}  // namespace

void ContactOptions::validate() const {
  if (!(stiffness > 0)) throw InputError("contact.stiffness: expected > 0, found " + std::to_string(stiffness));
  if (!(penetration_stiffness > 0))
    throw InputError("contact.penetration_stiffness: expected > 0, found " + std::to_string(penetration_stiffness));
  if (!(zone > 0)) throw InputError("contact.zone: expected > 0, found " + std::to_string(zone));
  if (detection != 0 && !(detection > zone))
    throw InputError("contact.detection: expected 0 (automatic) or more than the zone width");
  if (max_detection != 0 && !(max_detection > zone && detection == 0))
    throw InputError("contact.max_detection: expected 0, or more than the zone width with detection 0");
  if (!between_leaflets && !self_contact)
    throw InputError("contact: expected between_leaflets or self_contact (or both) to be true");
}

ContactTerm::ContactTerm(const TriMesh& mesh, const ContactOptions& opt, std::vector<const ForceTerm*> external,
                         const std::vector<char>& constrained)
    : opt_(opt), topology_(mesh, opt.self_contact, opt.between_leaflets), external_(std::move(external)) {
  opt_.validate();
  const int n = mesh.num_nodes();
  query_.assign(n, 0);
  for (int i = 0; i < n; ++i) query_[i] = !constrained[3 * i] && topology_.has_triangles(i);
  detection_ = opt_.detection != 0 ? opt_.detection : opt_.zone + topology_.mean_edge_length();
  if (opt_.max_detection != 0) detection_ = std::min(detection_, opt_.max_detection);
}

void ContactTerm::couplings(std::vector<std::pair<int, int>>& pairs) const {
  pairs.insert(pairs.end(), coupled_.begin(), coupled_.end());
}

bool ContactTerm::update_couplings(const VecX& x) {
  const auto t0 = std::chrono::steady_clock::now();
  const auto pairs = broad_phase_pairs(x, topology_.triangles(), detection_, opt_.broad_phase, query_);
  std::vector<Candidate> next;
  std::vector<PlaneGeometry> geom;
  next.reserve(pairs.size());
  for (const auto& [i, t] : pairs) {
    if (topology_.excluded(i, t)) continue;
    const PlaneGeometry g = plane_geometry(x, topology_.triangles()[t], node3(x, i));
    if (g.area2 <= 0 || std::abs(g.d) > detection_) continue;
    auto old = std::lower_bound(candidates_.begin(), candidates_.end(), std::make_pair(i, t),
                                [](const Candidate& c, const std::pair<int, int>& key) {
                                  return std::make_pair(c.node, c.triangle) < key;
                                });
    int side = (old != candidates_.end() && old->node == i && old->triangle == t) ? old->side : 0;
    const bool own = topology_.on_leaflet(i, topology_.leaflet_of(t));
    if (opt_.normal_side_between_leaflets && !own) side = 1;
    next.push_back({i, t, side});
    geom.push_back(g);
  }
  // Decide the side of pairs now in front of their triangle: inherit it from a decided pair
  // of the same node with a neighbouring, similarly oriented triangle (a node sliding along a
  // sheet keeps its side even if it is slightly through it), else take the side it is on.
  const double undecided_band = 1e-3 * opt_.zone;
  for (size_t a = 0; a < next.size();) {
    size_t b = a;
    while (b < next.size() && next[b].node == next[a].node) ++b;
    for (size_t k = a; k < b; ++k) {
      if (next[k].side != 0 || geom[k].barycentric.minCoeff() < opt_.inside_tolerance) continue;
      const Tri& tk = topology_.triangles()[next[k].triangle];
      for (size_t j = a; j < b && next[k].side == 0; ++j) {
        if (next[j].side == 0 || topology_.leaflet_of(next[j].triangle) != topology_.leaflet_of(next[k].triangle)) continue;
        if (share_vertex(tk, topology_.triangles()[next[j].triangle]) && geom[k].n.dot(geom[j].n) > 0.5)
          next[k].side = next[j].side;
      }
      if (next[k].side == 0 && std::abs(geom[k].d) > undecided_band) next[k].side = geom[k].d > 0 ? 1 : -1;
    }
    a = b;
  }
  candidates_ = std::move(next);
  std::vector<std::pair<int, int>> coupled;
  coupled.reserve(3 * candidates_.size());
  for (const Candidate& c : candidates_)
    for (int k = 0; k < 3; ++k)
      coupled.emplace_back(std::min(c.node, topology_.triangles()[c.triangle][k]), std::max(c.node, topology_.triangles()[c.triangle][k]));
  ++stats_.candidate_updates;
  stats_.candidate_pairs = static_cast<long>(candidates_.size());
  stats_.broad_phase_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return grow_couplings(coupled_, std::move(coupled));
}

void ContactTerm::add(const State& s, VecX& f, BlockJacobian* dfdx, BlockJacobian*) const {
  stats_.active_pairs = 0;
  stats_.deepest_penetration = 0;
  if (candidates_.empty()) return;
  VecX fext = VecX::Zero(f.size());
  for (const auto* e : external_) e->add(s, fext, nullptr, nullptr);
  const double k = opt_.stiffness, z = opt_.zone;
  struct Chosen {
    int leaflet;
    size_t index;
    double d;
    PlaneGeometry geometry;
  };
  std::vector<Chosen> chosen;
  for (size_t a = 0; a < candidates_.size();) {
    const int i = candidates_[a].node;
    size_t b = a;
    while (b < candidates_.size() && candidates_[b].node == i) ++b;
    const Vec3 p = node3(s.x, i);
    // The nearest triangle in front, per leaflet.
    chosen.clear();
    for (size_t c = a; c < b; ++c) {
      const Candidate& cand = candidates_[c];
      if (cand.side == 0) continue;
      const PlaneGeometry g = plane_geometry(s.x, topology_.triangles()[cand.triangle], p);
      const double d = cand.side * g.d;
      if (g.area2 <= 0 || d >= z || g.barycentric.minCoeff() < opt_.inside_tolerance) continue;
      const int l = topology_.leaflet_of(cand.triangle);
      auto it = std::find_if(chosen.begin(), chosen.end(), [l](const Chosen& ch) { return ch.leaflet == l; });
      if (it == chosen.end()) chosen.push_back({l, c, d, g});
      else if (d < it->d) *it = {l, c, d, g};
    }
    for (const Chosen& ch : chosen) {
      const Candidate& cand = candidates_[ch.index];
      const Tri& t = topology_.triangles()[cand.triangle];
      const PlaneGeometry& geo = ch.geometry;
      const Vec3 m = cand.side * geo.n;
      const Vec3 fe = node3(fext, i);
      const double d = ch.d;
      const double F = std::max(0.0, -m.dot(fe));
      double g, g_d, g_F;
      if (d < 0) {
        g = F - opt_.penetration_stiffness * d, g_d = -opt_.penetration_stiffness, g_F = 1;
      } else if (F > 0) {
        const double ex = std::exp(-k * d / F), u = d / z;
        g = F * ex * taper(u);
        g_d = ex * (-k * taper(u) + F * taper_slope(u) / z);
        g_F = ex * taper(u) * (1 + k * d / F);
      } else {
        continue;  // in the zone but nothing pushes it toward the triangle
      }
      ++stats_.active_pairs;
      stats_.deepest_penetration = std::max(stats_.deepest_penetration, -d);
      node3(f, i) += g * m;
      if (!dfdx) continue;
      if (F == 0) g_F = 0;
      const Vec3 xa = node3(s.x, t[0]), e1 = node3(s.x, t[1]) - xa, e2 = node3(s.x, t[2]) - xa;
      const Vec3 r = p - xa;
      const Mat3 P = cand.side * (Mat3::Identity() - geo.n * geo.n.transpose()) / geo.area2;
      const Mat3 dc[3] = {cross_matrix(e2) - cross_matrix(e1), -cross_matrix(e2), cross_matrix(e1)};
      dfdx->add(i, i, g_d * m * m.transpose());
      for (int v = 0; v < 3; ++v) {
        const Mat3 dm = P * dc[v];
        Eigen::RowVector3d dd = r.transpose() * dm;
        if (v == 0) dd -= m.transpose();
        const Eigen::RowVector3d dF = -fe.transpose() * dm;
        dfdx->add(i, t[v], m * (g_d * dd + g_F * dF) + g * dm);
      }
    }
    a = b;
  }
}

}  // namespace valve
