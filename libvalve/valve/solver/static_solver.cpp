#include "valve/solver/static_solver.hpp"

#include <chrono>
#include <algorithm>
#include <cmath>

#include "valve/solver/constrained_system.hpp"
#include "valve/solver/load_continuation.hpp"

namespace valve {

SolverSummary solve_static(MechanicalSystem& sys, VecX& x, const StaticOptions& opt, double load_target,
                           double load_start) {
  const auto t_start = std::chrono::steady_clock::now();
  auto wall = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - t_start).count(); };
  auto solver = make_linear_solver(opt.linear_solver, opt.iterative_tolerance, opt.iterative_max_iterations, sys.num_dofs());
  SolverSummary sum;
  sum.linear_solver = solver->name();
  const VecX v = VecX::Zero(x.size());
  const auto& cons = sys.constrained();
  VecX f;

  const VecX& M = sys.dof_masses();
  double trust = opt.trust_radius;
  if (trust <= 0) {
    // A fixed fraction of the model size: 1 mm steps made the FE leaflet wander for
    // thousands of iterations, 0.5 mm (2.5 % of 20 mm) converged in ~80 on every mesh tried.
    const MatX3 p = unflatten(x);
    trust = 0.025 * (p.colwise().maxCoeff() - p.colwise().minCoeff()).norm();
  }
  // Contact sees a node only inside its detection slab: no step may jump across it.
  trust = std::min(trust, sys.max_step_length());
  // Ψtc iterations at a fixed load factor; returns true when the residual tolerance is met.
  auto newton = [&](double load) -> bool {
    const State s0{x, v, opt.residual_reference_load > 0 ? opt.residual_reference_load : load, 0.0};
    // Residuals are relative to the applied load; with none (annulus motion alone), to the
    // first residual of this solve.
    double f_ext = free_norm(sys.external_force(s0), cons);
    double delta = opt.initial_pseudo_step;
    for (int it = 0; it < opt.max_newton_iterations; ++it) {
      if (wall() > opt.max_wall_seconds) return false;
      const State s{x, v, load, 0.0};
      if (!sys.evaluate(s, f, true, false)) return false;
      ++sum.jacobian_evaluations;
      const double r0 = free_norm(f, cons);
      if (!(f_ext > 0)) f_ext = std::max(r0, 1e-300);
      sum.relative_residual = r0 / f_ext;
      if (sum.relative_residual <= opt.relative_residual_tolerance) return true;
      bool accepted = false;
      for (int attempt = 0; attempt < 30 && !accepted; ++attempt) {
        SparseMatrix A = -sys.dfdx().matrix();
        if (delta < 1e30)
          for (int i = 0; i < A.cols(); ++i) A.coeffRef(i, i) += M[i] / delta;
        VecX b = f;
        apply_constraints(A, b, cons);
        if (solver->needs_symmetric()) A = symmetric_part(A);
        VecX dx;
        if (!solver->factorize(A) || !solver->solve(b, dx)) {
          delta *= 0.25;
          continue;
        }
        ++sum.newton_iterations;
        // Step limits: the trust radius (displacement) and the strain increment of any edge.
        const double longest = largest_node_norm(dx);
        double strain = 0;
        const std::vector<std::pair<int, int>> edges =
            opt.max_strain_increment > 0 ? sys.couplings() : std::vector<std::pair<int, int>>{};
        for (const auto& [a, b] : edges) {
          const Vec3 e = node3(x, b) - node3(x, a);
          const double l = e.norm();
          if (l > 0) strain = std::max(strain, std::abs((e + node3(dx, b) - node3(dx, a)).norm() - l) / l);
        }
        double scale = std::min(1.0, trust / std::max(longest, 1e-300));
        if (opt.max_strain_increment > 0) scale = std::min(scale, opt.max_strain_increment / std::max(strain, 1e-300));
        dx *= scale;
        const VecX trial = x + dx;
        VecX ft;
        if (!sys.evaluate(State{trial, v, load, 0.0}, ft, false, false)) {
          delta *= 0.25;
          continue;
        }
        const double r1 = free_norm(ft, cons);
        x = trial;
        accepted = true;
        if (scale < 1) {
          // The step had to be cut: δ is too large for this state. Shrink it in proportion,
          // so the next linear step is about the size the limits allow.
          delta *= std::max(scale, 0.1);
        } else {
          // Switched evolution relaxation, with a bias towards growth: while a membrane swings
          // through (the pressure is constant and stress has not built up) the residual stays
          // flat, and plain SER would keep δ, and the step, tiny forever. Growth is bounded so
          // one lucky step cannot jump to an undamped Newton step far from equilibrium.
          delta *= std::clamp(1.5 * r0 / std::max(r1, 1e-300), 0.25, 4.0);
        }
      }
      if (!accepted) return false;
    }
    return false;
  };

  LoadContinuationOptions lc;
  lc.initial_increment = opt.initial_increment;
  lc.min_increment = opt.min_increment;
  lc.max_increments = opt.max_increments;
  lc.max_wall_seconds = opt.max_wall_seconds;
  lc.fast_iterations = 6;
  const double load = continue_load(x, load_start, load_target, lc, sum, wall, newton, [&] { return sum.newton_iterations; });
  sum.linear = solver->stats();
  const State s{x, v, load, 0.0};
  sys.evaluate(s, f, false, false);
  sum.max_free_force_N = sys.max_free_force(f);
  sum.wall_seconds = wall();
  sum.term_timings = sys.timings();
  return sum;
}

}  // namespace valve
