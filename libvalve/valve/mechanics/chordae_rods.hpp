#pragma once
// Chordae tendineae as rods that carry tension only (seed 5.2.2), each with its own uniaxial
// law (material/rod_law.hpp: linear, E = 40 MPa in seed Table 5.1, or the Texas TriValve
// deck's Ogden law) and reference section A0. A rod between nodes a and b with rest length L0:
//   L = |x_b − x_a|,  d = (x_b − x_a) / L,  λ = L / L0,  T = A0 P(λ)  (P = 0 for λ <= 1),
//   f_a = T d,  f_b = −T d,
//   ∂f_a/∂x_b = K = (A0 P'(λ) / L0) d dᵀ + (T / L)(I − d dᵀ),  ∂f_a/∂x_a = −K,
//   energy A0 L0 W(λ).
// A slack rod contributes nothing, so a buckled chord never pushes a leaflet.
#include <memory>
#include <vector>

#include "valve/material/rod_law.hpp"
#include "valve/mechanics/force_term.hpp"

namespace valve {

struct Rod {
  int a = 0, b = 0;
  double rest_length = 1;  // mm
  double area = 0;         // reference section A0, mm²
  std::shared_ptr<const RodLaw> law;
};

class ChordaeTerm final : public ForceTerm {
 public:
  explicit ChordaeTerm(std::vector<Rod> rods);
  std::string name() const override { return "chordae"; }
  void couplings(std::vector<std::pair<int, int>>& pairs) const override;
  void add(const State& s, VecX& f, BlockJacobian* dfdx, BlockJacobian* dfdv) const override;
  bool energy(const State& s, double& e) const override;
  const std::vector<Rod>& rods() const { return rods_; }
  /// Tension (N) of every rod at positions x (0 when slack).
  std::vector<double> tensions(const VecX& x) const;

 private:
  std::vector<Rod> rods_;
};

}  // namespace valve
