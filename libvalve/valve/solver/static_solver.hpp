#pragma once
// Static equilibrium f(x; λ) = 0 for scenes where only the loaded state matters: Newton's
// method with a backtracking line search on |f|², Levenberg-Marquardt regularization
// (K + μ diag|K|) when the tangent is singular or the step does not reduce the residual
// (a flat membrane has no out-of-plane stiffness at rest), and load continuation that
// grows the load factor λ from 0 to the target, halving the increment on failure.
#include "valve/mechanics/mechanical_system.hpp"
#include "valve/solver/linear_solver.hpp"
#include "valve/solver/solver_summary.hpp"

namespace valve {

struct StaticOptions {
  double relative_residual_tolerance = 1e-9;  // |f_free| / |f_external_free|
  int max_newton_iterations = 40;             // per load increment
  double initial_increment = 0.25;            // first Δλ
  double min_increment = 1e-5;
  long max_increments = 2000;
  double max_wall_seconds = 600;
  LinearSolverType linear_solver = LinearSolverType::lu;  // exact Newton: pressure is non-symmetric
  double iterative_tolerance = 1e-10;
  int iterative_max_iterations = 5000;
};

/// Solves from x (updated in place) at load factors from `load_start` up to `load_target`.
SolverSummary solve_static(MechanicalSystem& system, VecX& x, const StaticOptions& options,
                           double load_target = 1.0, double load_start = 0.0);

}  // namespace valve
