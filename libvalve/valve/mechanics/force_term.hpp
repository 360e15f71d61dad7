#pragma once
// The interface every force term implements. Terms know nothing of solvers: they add
// nodal forces f(x, v) and, when asked, their Jacobians df/dx and df/dv into a pattern
// built once from couplings(). The solver sees only the sum of terms.
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "valve/core/types.hpp"
#include "valve/mechanics/jacobian.hpp"

namespace valve {

/// What a force term is evaluated at. `load` scales external loads (load continuation
/// and load increments); `time` is simulated time in ms.
struct State {
  const VecX& x;
  const VecX& v;
  double load = 1.0;
  double time = 0.0;
};

/// How a term with an indefinite Hessian (the contact barrier) gives its Jacobian: projected
/// to positive semi-definite, so that a Newton matrix with it stays positive definite far from
/// equilibrium; or exact, so that Newton's method converges quadratically near equilibrium
/// (the projection's error makes the last iterations linear).
enum class JacobianMode { projected, exact };

class ForceTerm {
 public:
  virtual ~ForceTerm() = default;
  virtual std::string name() const = 0;
  /// Node pairs whose positions this term couples (for the Jacobian pattern).
  virtual void couplings(std::vector<std::pair<int, int>>& pairs) const = 0;
  /// Adds forces to f (length 3N); adds df/dx to dfdx and df/dv to dfdv when non-null.
  virtual void add(const State& s, VecX& f, BlockJacobian* dfdx, BlockJacobian* dfdv) const = 0;
  /// Adds the potential energy (mJ) to e for conservative terms; terms without one return false.
  virtual bool energy(const State& s, double& e) const {
    (void)s, (void)e;
    return false;
  }
  /// Terms whose Hessian may be indefinite follow `mode` from the next evaluation on.
  virtual void set_jacobian_mode(JacobianMode mode) { (void)mode; }
  /// Whether df/dv is nonzero (damping).
  virtual bool depends_on_velocity() const { return false; }
  /// Terms whose couplings follow the state (contact) refresh them here and return true
  /// when couplings() grew; MechanicalSystem then rebuilds the Jacobian pattern.
  virtual bool update_couplings(const VecX& x) {
    (void)x;
    return false;
  }
  /// Largest node displacement per solver step (mm) this term tolerates; infinity if any.
  virtual double max_step_length() const { return std::numeric_limits<double>::infinity(); }
  /// How much of what this term tolerates a step dx from x (the state of the last
  /// update_couplings()) uses: the step is acceptable while the ratio is at most 1. By
  /// default the largest nodal |dx_i| over max_step_length().
  virtual double step_ratio(const VecX& x, const VecX& dx) const {
    (void)x;
    const double m = max_step_length();
    return std::isfinite(m) ? largest_node_norm(dx) / m : 0;
  }
  /// The positions a solve starts from, before its first evaluation (the contact barrier
  /// excludes the pairs already within its reach there).
  virtual void start_at(const VecX& x) { (void)x; }
  /// Whether this is an applied load (pressure, edge loads) rather than a material or
  /// constraint response; solvers use the applied load to scale residual tolerances.
  virtual bool is_external_load() const { return false; }
};

}  // namespace valve
