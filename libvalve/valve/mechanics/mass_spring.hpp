#pragma once
// Anisotropic bilinear mass-spring model (seed 3.2.2.3, Eq. 3.4-3.6).
//
// Every triangle edge c is a spring. Its stiffness follows van Gelder:
//     k_c = E h Σ_{T ∋ c} area(T) / |c|²                                   (3.4)
// with E replaced by the bilinear slopes m1 (stretch λ = l/l0 ≤ λ*) and m2 (λ > λ*).
// The slopes and λ* depend on the rest angle φ between the edge and the fiber:
//     m(φ) = sqrt(m_f² cos²φ + m_c² sin²φ)   (same for m2 and λ*)
// where cos²φ is averaged over the edge's triangles, weighted by area. Spring force on
// the edge's first node, along n̂ = (x_b - x_a)/l:
//     F = k1 (l - l0)                                  λ ≤ λ*              (3.5)
//     F = k1 l0 (λ* - 1) + k2 (l - λ* l0)              λ > λ*              (3.6)
// Jacobian of f_a w.r.t. x_a: -[F'(l) n̂n̂ᵀ + F/l (I - n̂n̂ᵀ)]; +that w.r.t. x_b.
#include <vector>

#include "valve/material/bilinear_fit.hpp"
#include "valve/mechanics/force_term.hpp"
#include "valve/mesh/tri_mesh.hpp"

namespace valve {

struct Spring {
  int a, b;
  double rest_length;
  double k1, k2;        // N/mm
  double lambda_star;
};

class MassSpringTerm final : public ForceTerm {
 public:
  /// `thickness` in mm; slopes of `params` in MPa.
  MassSpringTerm(const TriMesh& mesh, const BilinearParameters& params, double thickness);
  std::string name() const override { return "mass_spring"; }
  void couplings(std::vector<std::pair<int, int>>& pairs) const override;
  void add(const State& s, VecX& f, BlockJacobian* dfdx, BlockJacobian* dfdv) const override;
  bool energy(const State& s, double& e) const override;
  const std::vector<Spring>& springs() const { return springs_; }

  /// Spring force magnitude and its derivative at length l.
  static void force(const Spring& sp, double l, double& F, double& dF);

 private:
  std::vector<Spring> springs_;
  mutable BlockSlotCache slots_;  // 4 per spring: (a, a), (b, b), (a, b), (b, a)
};

}  // namespace valve
