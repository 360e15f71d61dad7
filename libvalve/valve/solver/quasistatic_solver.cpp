#include "valve/solver/quasistatic_solver.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "valve/solver/constrained_system.hpp"
#include "valve/solver/load_continuation.hpp"

namespace valve {

namespace {

constexpr double kMinProximalStep = 1e-14;
// The smallest share of the exact contact Hessians' departure from the projected ones tried
// before the projected direction: six more solves on the same factorisation at most.
constexpr double kSmallestExactShare = 1.0 / 64;

}  // namespace

SolverSummary solve_quasistatic(MechanicalSystem& sys, VecX& x, const QuasistaticOptions& opt, double load_target,
                                double load_start) {
  const auto t_start = std::chrono::steady_clock::now();
  auto wall = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - t_start).count(); };
  // The whole system (the pressure's stiffness is not symmetric) by GMRES on a Cholesky of
  // its symmetric part, so that the last iterations are Newton's on f = 0 and converge
  // quadratically (with the symmetric part alone, the frozen pressure made the tail linear:
  // 1e-5 to 1e-6 took hundreds of iterations on the sample mitral closure): Eigen's simplicial
  // LLᵀ below kLargeSystemDofs, CHOLMOD's supernodal one above (linear_solver.hpp). GMRES rather
  // than BiCGStab: one preconditioner solve per step against BiCGStab's two, and fewer solves
  // per direction in all (the sample mitral closure: 824 against 1,600). A Cholesky refuses a
  // symmetric part that is not positive definite, and δ then shrinks (see the header).
  // Sized by the free unknowns: held ones stay in the matrix only as unit rows (condensed
  // chordae hold thousands of points).
  LinearSolverType type = opt.linear_solver;
  const long free_dofs = std::count(sys.constrained().begin(), sys.constrained().end(), 0);
  if (type == LinearSolverType::automatic)
    type = free_dofs < kLargeSystemDofs ? LinearSolverType::llt_gmres : LinearSolverType::cholmod_gmres;
  auto solver = make_linear_solver(type, opt.iterative_tolerance, 2000, sys.num_dofs(), SystemSymmetry::symmetrized);
  SolverSummary sum;
  sum.solver = "quasistatic";
  sum.linear_solver = solver->name();
  {
    double e = 0;
    std::string missing;
    if (!sys.internal_energy(State{x, VecX::Zero(x.size()), load_start, 0.0}, e, &missing)) {
      sum.status = SolverStatus::failed;
      sum.reason = "the quasi-static solver needs every term's energy; " + missing + " has none";
      return sum;
    }
  }
  const VecX v = VecX::Zero(x.size());
  const auto& cons = sys.constrained();
  const VecX& M = sys.dof_masses();
  double trust = opt.trust_radius;
  if (trust <= 0) {
    const MatX3 p = unflatten(x);
    trust = 0.05 * (p.colwise().maxCoeff() - p.colwise().minCoeff()).norm();
  }
  SystemMatrix system_matrix;
  SparseMatrix exact_matrix, exact_departure, blended_matrix;
  VecX f, fe, dx, b, f_trial;
  RecentIterates recent;
  double delta = opt.initial_proximal_step;
  ExactHessianSchedule exact_hessians;
  bool exact = false;

  // Newton iterations at a fixed load factor; true when the residual tolerance is met.
  auto converge = [&](double load) -> bool {
    // Residuals are relative to the load this solve applies (at the target, so that a small
    // first increment is not held to a tighter absolute tolerance); with none (annulus motion
    // alone), to the increment's first residual.
    double reference = free_norm(sys.external_force(State{x, v, load_target, 0.0}), cons);
    ForcingTerm forcing(opt.iterative_tolerance, opt.relative_residual_tolerance);
    IncrementBudget budget(opt.max_iterations);
    exact_hessians.start_increment();
    for (int it = 0; budget.allows(it); ++it) {
      if (wall() > opt.max_wall_seconds) return false;
      const State s{x, v, load, 0.0};
      // The Jacobian's kind is chosen before the evaluation that gives this iterate's residual:
      // the schedule knows the residuals up to the last iterate.
      exact = exact_hessians.exact_at(delta);
      sys.set_jacobian_mode(exact ? JacobianMode::exact : JacobianMode::projected);
      if (!sys.evaluate(s, f, true, false)) return false;
      bool exact_jacobian = exact;  // what sys.dfdx() holds
      ++sum.jacobian_evaluations;
      const double r = free_norm(f, cons);
      if (!(reference > 0)) reference = std::max(r, 1e-300);
      sum.relative_residual = r / reference;
      if (sum.relative_residual <= opt.relative_residual_tolerance) return true;
      exact_hessians.record_residual(sum.relative_residual);
      budget.record(sum.relative_residual);
      if (opt.forcing == NewtonForcing::adaptive) solver->set_tolerance(forcing.next(sum.relative_residual));
      fe = sys.external_force(s);  // frozen for this iteration (the follower pressure)
      double pi0 = 0;
      if (!sys.internal_energy(s, pi0) || !std::isfinite(pi0)) return false;
      // A direction that fails (its solve, or its descent) with exact contact Hessians is taken
      // again with projected ones at the same δ (on GMRES's path, after the scaled ones below).
      auto retry_projected = [&] {
        if (!exact) return false;
        exact = false;
        exact_hessians.failed_at(delta);
        sys.set_jacobian_mode(JacobianMode::projected);
        return sys.evaluate(s, f, true, false);
      };
      // A projected direction that does not descend on Φ_k is taken again, at the same δ, from
      // Φ_k's own Hessian: without the applied loads' stiffness, which Φ_k (the loads frozen)
      // does not have and whose symmetric part is indefinite. Only then does δ shrink: on the
      // sample mitral closure the direction with it stayed uphill from δ = 3.5e11 to 1.3 ms²,
      // twenty factorisations.
      bool load_stiffness = true;
      auto retry_without_load_stiffness = [&] {
        if (exact || !load_stiffness) return false;
        load_stiffness = false;
        return sys.evaluate(s, f, true, false, false);
      };
      bool accepted = false;
      while (!accepted) {
        // The wall-time limit holds within an iteration too: one whose directions keep failing
        // factorises again and again.
        if (delta < kMinProximalStep || wall() > opt.max_wall_seconds) return false;
        // δ H = M − δ ∂f/∂x (its symmetric part for a Cholesky), δ H Δ = δ f.
        b = delta * f;
        const SparseMatrix& A =
            system_matrix.assemble(sys.dfdx(), -delta, nullptr, 0.0, M, cons, solver->needs_symmetric(), b);
        if (exact && solver->takes_preconditioner()) {
          // The exact matrix by GMRES on the Cholesky of the projected one; where its
          // direction fails, scaled ones and then the projected one on the same factorization.
          if (!exact_jacobian) {  // a line search failed after the last try: evaluate again
            sys.set_jacobian_mode(JacobianMode::exact);
            if (!sys.evaluate(s, f, true, false)) return false;
            exact_jacobian = true;
            continue;
          }
          exact_matrix = A;
          sys.set_jacobian_mode(JacobianMode::projected);
          if (!sys.evaluate(s, f, true, false)) return false;
          exact_jacobian = false;
          const SparseMatrix& P =
              system_matrix.assemble(sys.dfdx(), -delta, nullptr, 0.0, M, cons, solver->needs_symmetric(), b);
          if (!solver->factorize_preconditioned(exact_matrix, P)) {
            delta *= 0.25;
            continue;
          }
          ++sum.newton_iterations;
          ++sum.exact_directions;
          bool exact_descends = solver->solve(b, dx) && dx.allFinite() && f.dot(dx) > 0;
          // Where the exact direction fails (it does not descend, or GMRES does not converge),
          // the same again with the exact Hessians' departure from the projected ones scaled
          // down, P + t (E − P) for t = 1/2, 1/4, ... (the header says why). Each solve counts
          // as a Newton direction, load continuation's fast-increment test included.
          if (!exact_descends) exact_departure = exact_matrix - P;
          for (double t = 0.5; !exact_descends && t >= kSmallestExactShare; t *= 0.5) {
            blended_matrix = P + t * exact_departure;
            ++sum.newton_iterations;
            ++sum.scaled_exact_directions;
            exact_descends = solver->set_operator(blended_matrix) && solver->solve(b, dx) && dx.allFinite() &&
                             f.dot(dx) > 0;
          }
          if (!exact_descends) {
            exact = false;
            exact_hessians.failed_at(delta);
            if (!solver->set_operator(P) || !solver->solve(b, dx) || !dx.allFinite()) {
              delta *= 0.25;
              continue;
            }
            ++sum.newton_iterations;
            ++sum.projected_directions;
          }
        } else if (!solver->factorize(A) || !solver->solve(b, dx) || !dx.allFinite()) {
          if (!retry_projected()) delta *= 0.25;
          continue;
        } else {
          ++sum.newton_iterations;
          ++(exact ? sum.exact_directions : sum.projected_directions);
        }
        const double descent = f.dot(dx);  // −∇Φ·Δ
        if (!(descent > 0)) {              // H not positive definite: not a descent direction
          if (!retry_projected() && !retry_without_load_stiffness()) delta *= 0.25;
          continue;
        }
        // The largest step the limits allow: the trust radius, then every term's step bound
        // (the contact barrier's conservative collision bound).
        double alpha = std::min(1.0, trust / std::max(largest_node_norm(dx), 1e-300));
        const bool beyond_trust = alpha < 1;
        const double ratio = sys.step_ratio(x, alpha * dx);
        if (ratio > 1) alpha *= 0.99 / ratio;
        const double mass_term = dx.dot(M.cwiseProduct(dx)) / (2 * delta);
        for (int search = 0; search < 40 && !accepted; ++search, alpha *= 0.5) {
          const VecX trial = x + alpha * dx;
          double pi = 0;
          if (!sys.internal_energy(State{trial, v, load, 0.0}, pi)) return false;
          const double merit = pi - alpha * fe.dot(dx) + alpha * alpha * mass_term;
          // Φ_k changes with k (the pressure frozen at x_k), so two iterates can each lower the
          // other's merit: across a kink of the contact forces Newton can step from one to the
          // other and back (without this rule one of ten perturbed aortic starts spends 330
          // iterations between two states 0.001 mm apart, relative residuals 5.9e-4 and
          // 1.2e-3); across several kinks, in longer cycles (RecentIterates). A step back to one
          // of the last iterates is refused; the search halves it.
          const bool returns = recent.returns_to(trial, 1e-3 * alpha * largest_node_norm(dx));
          bool sufficient = !returns && std::isfinite(merit) && merit <= pi0 - opt.armijo * alpha * descent;
          // Near equilibrium Φ_k, a model with the pressure frozen, need not fall along Newton's
          // direction for f = 0 (the pressure's non-symmetric stiffness is in the direction,
          // not in Φ_k); the residual does: |f| must then fall by the Armijo fraction.
          if (!sufficient && !returns && std::isfinite(pi) &&
              sys.evaluate(State{trial, v, load, 0.0}, f_trial, false, false))
            sufficient = free_norm(f_trial, cons) <= (1 - opt.armijo * alpha) * r;
          if (sufficient) {
            recent.push(x);
            x = trial;
            accepted = true;
            if (opt.proximal_rule == ProximalStepRule::step) {
              // A direction accepted at once earns less regularisation (less still if the
              // step was whole); one that needed cutting back, more; one longer than the
              // trust radius, nothing: the model is not yet trusted that far.
              if (!beyond_trust && search == 0)
                delta = std::min(delta * (ratio > 1 ? 2 : 4), kMaxProximalStep);
              else if (!beyond_trust && search > 1)
                delta *= 0.5;
            } else {
              // The gain ratio of trust-region methods: the merit's fall over the quadratic
              // model's, α f·Δ (1 − α/2) with H Δ = f.
              const double predicted = alpha * descent * (1 - alpha / 2);
              const double gain = std::isfinite(merit) ? (pi0 - merit) / predicted : -1;
              if (gain > 0.75 && search == 0)
                delta = std::min(delta * (beyond_trust || ratio > 1 ? 2 : 4), kMaxProximalStep);
              else if (gain < 0.25)
                delta *= 0.5;
            }
          }
        }
        if (!accepted) delta *= 0.25;
      }
    }
    return false;
  };

  LoadContinuationOptions lc;
  lc.initial_increment = opt.initial_increment;
  lc.min_increment = opt.min_increment;
  lc.max_wall_seconds = opt.max_wall_seconds;
  lc.fast_iterations = 10;
  // After a failed increment the regularisation starts afresh, and Eigen's Cholesky (below
  // 6,000 unknowns; above, an LDLᵀ is too slow to take over) hands over to its LDLᵀ: where the
  // symmetric part stays indefinite the Cholesky refuses it until δ is too small to move
  // (measured with the Cholesky alone: a slack-root closure of the normal-valve study stalls so
  // at load factor 0.66, which the LDLᵀ closes from its start in 506 directions); 6 of the
  // study's 170 quasi-static closures fail an increment and hand over.
  LinearSolverStats earlier;
  auto after_failed_increment = [&] {
    delta = opt.initial_proximal_step;
    if (type != LinearSolverType::llt_gmres && type != LinearSolverType::llt_bicgstab) return;
    earlier += solver->stats();
    type = type == LinearSolverType::llt_gmres ? LinearSolverType::ldlt_gmres : LinearSolverType::ldlt_bicgstab;
    solver = make_linear_solver(type, opt.iterative_tolerance, 2000, sys.num_dofs(), SystemSymmetry::symmetrized);
    sum.linear_solver += ", then " + solver->name();
  };
  const double load = continue_load(x, load_start, load_target, lc, sum, wall, converge,
                                    [&] { return sum.newton_iterations; }, after_failed_increment);
  sum.linear = earlier;
  sum.linear += solver->stats();
  sys.evaluate(State{x, v, load, 0.0}, f, false, false);
  sum.max_free_force_N = sys.max_free_force(f);
  sum.wall_seconds = wall();
  sum.term_timings = sys.timings();
  return sum;
}

}  // namespace valve
