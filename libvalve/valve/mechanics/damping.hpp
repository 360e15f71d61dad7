#pragma once
// Viscous damping f_i = -b_i v_i, df_i/dv_i = -b_i I (seed Appendix). The coefficients
// are either mass-proportional (b_i = α m_i) or critical: b_i = ζ · 2 sqrt(m_i k_i) with
// k_i the largest diagonal entry of node i's block of -df/dx, recomputed by the solver
// from the current tangent (adaptive critical damping, seed 3.2.2.5).
#include <vector>

#include "valve/mechanics/force_term.hpp"

namespace valve {

class DampingTerm final : public ForceTerm {
 public:
  enum class Mode { mass_proportional, critical };
  /// For mass_proportional, `factor` is α (1/ms); for critical it is the ratio ζ.
  DampingTerm(std::vector<double> masses, Mode mode, double factor);
  std::string name() const override { return "damping"; }
  void couplings(std::vector<std::pair<int, int>>&) const override {}
  void add(const State& s, VecX& f, BlockJacobian* dfdx, BlockJacobian* dfdv) const override;
  bool depends_on_velocity() const override { return true; }

  Mode mode() const { return mode_; }
  /// Recomputes critical coefficients from the stiffness -df/dx (critical mode only).
  void update_from_stiffness(const BlockJacobian& dfdx);
  const std::vector<double>& coefficients() const { return b_; }

 private:
  std::vector<double> masses_, b_;
  Mode mode_;
  double factor_;
};

}  // namespace valve
