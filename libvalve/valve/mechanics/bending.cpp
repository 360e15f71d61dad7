#include "valve/mechanics/bending.hpp"

#include <Eigen/Geometry>

#include "valve/core/error.hpp"
#include "valve/mesh/topology.hpp"

namespace valve {
namespace {

/// The node of triangle t that is neither a nor b, and whether t runs a → b.
int opposite(const Tri& t, int a, int b, bool& a_to_b) {
  for (int k = 0; k < 3; ++k)
    if (t[k] != a && t[k] != b) {
      a_to_b = t[(k + 1) % 3] == a;  // winding (k, k+1, k+2) = (c, a, b) ⇔ a → b
      return t[k];
    }
  return -1;
}

}  // namespace

Vec3 hinge_vector(const VecX& x, const Hinge& h) {
  Vec3 v = Vec3::Zero();
  for (int i = 0; i < 4; ++i) v += h.weights[i] * node3(x, h.nodes[i]);
  return v;
}

BendingTerm::BendingTerm(const TriMesh& mesh, double flexural_rigidity) {
  if (!(flexural_rigidity >= 0)) throw InputError("bending: expected a flexural rigidity >= 0, found " + std::to_string(flexural_rigidity));
  const Topology topo = build_topology(mesh.triangles, mesh.num_nodes());
  for (const Edge& e : topo.edges) {
    if (e.tris[1] < 0) continue;
    bool first_a_to_b = false, second_a_to_b = false;
    const int c = opposite(mesh.triangles[e.tris[0]], e.a, e.b, first_a_to_b);
    const int d = opposite(mesh.triangles[e.tris[1]], e.a, e.b, second_a_to_b);
    if (c < 0 || d < 0 || first_a_to_b == second_a_to_b) continue;  // degenerate or not consistently wound
    const int a = first_a_to_b ? e.a : e.b, b = first_a_to_b ? e.b : e.a;  // c's triangle runs a → b
    const Vec3 pa = mesh.points.row(a).transpose(), edge = mesh.points.row(b).transpose() - pa;
    const double le2 = edge.squaredNorm();
    const Vec3 rc = mesh.points.row(c).transpose() - pa, rd = mesh.points.row(d).transpose() - pa;
    const double hc = edge.cross(rc).norm() / std::sqrt(le2), hd = edge.cross(rd).norm() / std::sqrt(le2);
    if (!(le2 > 0 && hc > 0 && hd > 0)) continue;
    const double sc = rc.dot(edge) / le2, sd = rd.dot(edge) / le2;
    Hinge h{{a, b, c, d}, {(1 - sc) / hc + (1 - sd) / hd, sc / hc + sd / hd, -1 / hc, -1 / hd}, 0};
    const double areas = 0.5 * std::sqrt(le2) * (hc + hd);
    h.stiffness = flexural_rigidity * le2 / areas;
    hinges_.push_back(h);
  }
  std::vector<std::pair<int, int>> pairs;
  for (const Hinge& h : hinges_)
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j) pairs.emplace_back(h.nodes[i], h.nodes[j]);
  slots_ = BlockSlotCache(std::move(pairs));
}

void BendingTerm::couplings(std::vector<std::pair<int, int>>& pairs) const {
  for (const Hinge& h : hinges_)
    for (int i = 0; i < 4; ++i)
      for (int j = i + 1; j < 4; ++j) pairs.emplace_back(h.nodes[i], h.nodes[j]);
}

void BendingTerm::add(const State& s, VecX& f, BlockJacobian* dfdx, BlockJacobian*) const {
  const std::vector<BlockSlot>* slots = dfdx ? &slots_.slots(*dfdx) : nullptr;
  for (std::size_t k = 0; k < hinges_.size(); ++k) {
    const Hinge& h = hinges_[k];
    const Vec3 v = hinge_vector(s.x, h);
    for (int i = 0; i < 4; ++i) node3(f, h.nodes[i]) -= h.stiffness * h.weights[i] * v;
    if (!dfdx) continue;
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j) dfdx->add_identity((*slots)[16 * k + 4 * i + j], -h.stiffness * h.weights[i] * h.weights[j]);
  }
}

bool BendingTerm::energy(const State& s, double& e) const {
  for (const Hinge& h : hinges_) e += 0.5 * h.stiffness * hinge_vector(s.x, h).squaredNorm();
  return true;
}

}  // namespace valve
