#pragma once
// Chordae tendineae as linear elastic rods that carry tension only (seed 5.2.2, Table 5.1:
// E = 40 MPa, D = 0.5 mm). A rod between nodes a and b with rest length L0 and axial
// stiffness EA (N) pulls its ends together when stretched:
//   L = |x_b − x_a|,  d = (x_b − x_a) / L,  T = EA (L − L0) / L0 if L > L0, else 0,
//   f_a = T d,  f_b = −T d,
//   ∂f_a/∂x_b = K = (EA / L0) d dᵀ + (T / L)(I − d dᵀ),  ∂f_a/∂x_a = −K,
//   energy ½ (EA / L0)(L − L0)² while taut.
// A slack rod contributes nothing, so a buckled chord never pushes a leaflet.
#include <vector>

#include "valve/mechanics/force_term.hpp"

namespace valve {

struct Rod {
  int a = 0, b = 0;
  double rest_length = 1;  // mm
  double axial_stiffness = 0;  // EA, N
};

class ChordaeTerm final : public ForceTerm {
 public:
  explicit ChordaeTerm(std::vector<Rod> rods) : rods_(std::move(rods)) {}
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
