#pragma once
// The assembled model a solver works on: lumped nodal masses, constrained degrees of
// freedom, and the sum of the force terms a scene declared. It times each term.
#include <memory>
#include <string>
#include <vector>

#include "valve/mechanics/damping.hpp"
#include "valve/mechanics/force_term.hpp"
#include "valve/mesh/tri_mesh.hpp"

namespace valve {

struct TermTiming {
  std::string name;
  double seconds = 0;  // wall time spent in the term's add()
  long calls = 0;
};

class MechanicalSystem {
 public:
  /// Lumped masses m_i = Σ ρ H A_T / 3 over the node's triangles (seed 3.2.2.3);
  /// `density` in g/mm³, `thickness` in mm. Nodes with role fixed are constrained.
  MechanicalSystem(const TriMesh& mesh, double density, double thickness);

  void add_term(std::unique_ptr<ForceTerm> term);
  /// Builds the Jacobian pattern from all terms' couplings. Call after the last add_term.
  void finalize();

  int num_nodes() const { return n_; }
  int num_dofs() const { return 3 * n_; }
  const VecX& dof_masses() const { return dof_mass_; }
  const std::vector<double>& node_masses() const { return node_mass_; }
  /// Per-dof constraint flags (1 = fixed).
  std::vector<char>& constrained() { return constrained_; }
  const std::vector<char>& constrained() const { return constrained_; }
  void fix_node(int i) { constrained_[3 * i] = constrained_[3 * i + 1] = constrained_[3 * i + 2] = 1; }
  void free_node(int i) { constrained_[3 * i] = constrained_[3 * i + 1] = constrained_[3 * i + 2] = 0; }
  /// Adds mass (g) to node i, e.g. chordae mass at a branch point, which belongs to no
  /// triangle (the constructor fixed it for having none; free_node() releases it).
  void add_node_mass(int i, double mass);

  /// f = Σ terms; fills dfdx()/dfdv() when asked. A Jacobian evaluation first lets terms
  /// with state-dependent couplings (contact) refresh them, rebuilding the pattern if needed. Returns false if any entry of f is not finite.
  /// With `load_stiffness` false, dfdx() leaves out the applied loads' own stiffness (the
  /// follower pressure's): the Hessian of the stored energy alone.
  bool evaluate(const State& s, VecX& f, bool want_dfdx, bool want_dfdv, bool load_stiffness = true);
  /// Critical damping follows the tangent: recompute its coefficients from the current
  /// dfdx() and update f and dfdv() to match. No-op for other damping modes.
  void update_critical_damping(const State& s, VecX& f);
  /// Sum of the external-load terms only (for residual scaling).
  VecX external_force(const State& s) const;
  /// Total potential energy if every non-velocity term has one.
  bool energy(const State& s, double& e) const;
  /// The stored energy of the material and constraint terms (not the applied loads, not
  /// damping); false, naming the first term without one in `missing`, if any lacks it.
  bool internal_energy(const State& s, double& e, std::string* missing = nullptr) const;

  const BlockJacobian& dfdx() const { return dfdx_; }
  const BlockJacobian& dfdv() const { return dfdv_; }
  bool has_velocity_terms() const { return has_velocity_terms_; }
  DampingTerm* damping() { return damping_; }
  const std::vector<TermTiming>& timings() const { return timings_; }
  /// Unique coupled node pairs (a < b) of all terms, sorted, from the Jacobian pattern; for
  /// mesh edges these are the triangle edges (used by solvers to limit strain increments).
  /// Computed on request: the pattern changes at every contact coupling added, the
  /// request comes only from the static solver's strain limit.
  std::vector<std::pair<int, int>> couplings() const { return dfdx_.node_pairs(); }
  const std::vector<std::unique_ptr<ForceTerm>>& terms() const { return terms_; }
  /// Smallest max_step_length() of the terms (infinity if none limits the step).
  double max_step_length() const;
  /// Tells every term where the solve starts (ForceTerm::start_at).
  void start_at(const VecX& x);
  /// Every term's Jacobian mode (ForceTerm::set_jacobian_mode) from the next evaluation on.
  void set_jacobian_mode(JacobianMode mode);
  /// The largest step_ratio() of the terms for a step dx from x, the state of the last
  /// Jacobian evaluation (0 if no term limits steps); a step is acceptable up to 1.
  double step_ratio(const VecX& x, const VecX& dx) const;
  /// Largest |f| over unconstrained dofs.
  double max_free_force(const VecX& f) const;

 private:
  int n_;
  std::vector<double> node_mass_;
  VecX dof_mass_;
  std::vector<char> constrained_;
  std::vector<std::unique_ptr<ForceTerm>> terms_;
  std::vector<TermTiming> timings_;
  BlockJacobian dfdx_, dfdv_;
  bool has_velocity_terms_ = false;
  DampingTerm* damping_ = nullptr;
};

}  // namespace valve
