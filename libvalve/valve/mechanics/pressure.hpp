#pragma once
// Follower pressure (seed 3.2.2.6): a uniform pressure p on every triangle, always normal
// to its current plane. With the area vector n = ½ (x2 - x1) × (x3 - x1) (winding normal
// times area) each node of the triangle receives
//     f_a = σ p λ n / 3,   σ = +1 (push along the winding normal) or -1 (against it),
// λ the load factor. Jacobian (not symmetric): with e1 = x2 - x1, e2 = x3 - x1 and
// [a]× the cross-product matrix, dn/dx2 = -½[e2]×, dn/dx3 = ½[e1]×, dn/dx1 = ½([e2]× - [e1]×).
#include <vector>

#include "valve/mechanics/force_term.hpp"
#include "valve/mesh/tri_mesh.hpp"

namespace valve {

class PressureTerm final : public ForceTerm {
 public:
  /// `pressure` in MPa; `along_normal` picks σ. Only triangles with a true entry in
  /// `active` (or all, if empty) are loaded.
  PressureTerm(const TriMesh& mesh, double pressure, bool along_normal, std::vector<char> active = {});
  bool is_external_load() const override { return true; }
  std::string name() const override { return "pressure"; }
  void couplings(std::vector<std::pair<int, int>>& pairs) const override;
  void add(const State& s, VecX& f, BlockJacobian* dfdx, BlockJacobian* dfdv) const override;

 private:
  std::vector<Tri> triangles_;
  double signed_pressure_;
  mutable BlockSlotCache slots_;  // 9 per triangle: (t[a], t[b]), a major
};

}  // namespace valve
