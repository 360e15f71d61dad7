#pragma once
// Semi-implicit second-order backward differences (seed Appendix, Eq. A.1-A.4) with
// adaptive step size by step doubling. One step solves
//   (M - 2/3 h ∂f/∂v - 4/9 h² ∂f/∂x) Δx = M[(x^n - x^{n-1})/3 + h/9 (8v^n - 2v^{n-1})]
//        + 4/9 h² (f^n - ∂f/∂v v^n) - 2/9 h ∂f/∂v (x^n - x^{n-1})
// (A.4 multiplied by M), then v^{n+1} = (1.5 x^{n+1} - 2 x^n + 0.5 x^{n-1}) / h.
// Step doubling: one step of 2h and two of h from the same state; their difference
// estimates the local error, the step is accepted when the largest nodal difference is
// under the truncation tolerance, and h is scaled by 0.9 (tol/err)^(1/3), within [0.2, 2].
// Predictor estimate (error_estimate = predictor): one step of h, compared with the
// quadratic through x^{n-1}, x^n and v^n extrapolated to t + h (the same quadratic that
// re-samples the history), x_p = x^{n-1} + 2 h v^n. That predictor's local error is
// h³x'''/3 and BDF2's is -2/9 h³x''', so the step's own error is estimated as
//   err = (2/9) / (2/9 + 1/3) |x^{n+1} - x_p| = 0.4 |x^{n+1} - x_p|,
// from one factorization per step instead of step doubling's three per two steps. The
// step after a restart (implicit Euler, no history) is still checked by doubling.
// Move limits: force terms bound how far a step may move nodes (contact: step_ratio in
// penalty_contact.hpp). A step over the bound is rejected and h cut so the largest ratio
// comes to 0.75, and after an accepted step h grows no further than that target predicts.
// (Why not quarter h on every such rejection: that makes a saw-tooth; the aortic valve
// closure so rejects 316 of 1,383 steps on move limits and steps below them for most of the rest.)
// Period-2 swings: near a stiffness jump (a chord going taut or slack, a contact pair at
// the edge of its zone) a linearised step at large h overshoots to the far side and the
// next one back, and the predictor estimate lets a swing of amplitude A through when 1.6 A
// is under the tolerance (x^{n+1} = x^{n-1}, x_p = 4 x^n - 3 x^{n-1}). Such a swing never
// settles: the sample mitral closure with primary chordae only, at a tolerance of 0.2 mm,
// sent one free-edge node 0.069 mm back and forth at every 50 ms step for 600 s of wall
// time. So when the monitor node that moves most turns back (by more than 120°, moving
// more than settle_tolerance) on kReversalsBeforeCut consecutive accepted steps, h is cut
// by 4, where inertia and damping weigh more against the jump; the same closure then
// settles in 137 steps. A physical oscillation turns back once per half period, not at
// every step, and is left alone (tests/solver/bdf2_test.cpp).
// When h changes, the previous state is re-sampled at the new spacing by quadratic
// interpolation through x^{n-1}, x^n and v^n. A run starts (and restarts after a load
// change, where the acceleration jumps) with one implicit Euler step,
//   (M - h ∂f/∂v - h² ∂f/∂x) Δx = h M v^n + h² (f^n - ∂f/∂v v^n),  v^{n+1} = Δx / h,
// because a BDF2 step over the jump would make the velocity, and so the whole trajectory,
// only first-order accurate.
// Termination (seed): the monitor nodes move less than displacement_tolerance per step.
// A single such step also happens at the turning point of an oscillation, so the rule must
// hold on `quiet_steps` consecutive steps and the static residual |f|/|f_ext| must be below
// relative_residual_tolerance.
// Settle rule (optional, settle_window > 0): the run has also converged when no monitor
// node strayed more than settle_tolerance from where it was at the start of a window of
// settle_window of simulated time. With penalty contact a few nodes can chatter in place
// by micrometres per step for ever, so the per-step rule never fires although the shape has
// stopped changing (sample mitral closure with bending: every node within 0.007 mm over the
// last 650 ms, 0.005 mm per step); the residual tolerance still applies.
#include <chrono>
#include <functional>
#include <memory>
#include <vector>

#include "valve/mechanics/mechanical_system.hpp"
#include "valve/solver/constrained_system.hpp"
#include "valve/solver/linear_solver.hpp"
#include "valve/solver/solver_summary.hpp"

namespace valve {

/// How the local error of a step is estimated (see above).
enum class ErrorEstimate { step_doubling, predictor };

struct Bdf2Options {
  double truncation_tolerance = 0.01;    // mm (seed: 1e-5 m)
  double displacement_tolerance = 1e-5;  // mm per step at the monitor nodes (seed)
  double relative_residual_tolerance = 1e-3;  // also require |f_free|/|f_ext_free| below this
  int quiet_steps = 3;                   // consecutive steps that must satisfy the monitor rule
  double initial_step = 1e-3;            // ms
  double min_step = 1e-10;               // ms
  double max_step = 50.0;                // ms
  int min_steps = 10;                    // never declare convergence earlier
  long max_steps = 200000;
  double max_time = 1e6;                 // ms of simulated time
  double max_wall_seconds = 600;         // over all run() calls of one integrator (every load
                                         // increment of a closure); with solver "auto" a
                                         // static attempt before it has its own (statics)
  bool adaptive = true;                  // false: fixed step = initial_step, no doubling
  ErrorEstimate error_estimate = ErrorEstimate::step_doubling;  // the seed's method by default
  LinearSolverType linear_solver = LinearSolverType::automatic;  // see kLargeSystemDofs
  double iterative_tolerance = 1e-10;
  int iterative_max_iterations = 5000;
  std::vector<int> monitor_nodes;        // empty: every free node
  double settle_window = 0;              // ms; 0: no settle rule
  double settle_tolerance = 0.01;        // mm
};

/// After each accepted step; returning true declares convergence.
struct StepInfo {
  const VecX& x;
  const VecX& v;
  const VecX& x_before;  // positions one (small) step earlier
  double time, step;
  long steps;
};
using StepObserver = std::function<bool(const StepInfo&)>;

class Bdf2Integrator {
 public:
  Bdf2Integrator(MechanicalSystem& system, Bdf2Options options);
  /// Starts at rest at positions x0.
  void reset(const VecX& x0);
  /// Integrates at load factor `load` until converged (monitor rule, or `observer` if given)
  /// or a limit is hit. The state carries over to the next call (load increments).
  SolverSummary run(double load, const StepObserver& observer = {});

  const VecX& positions() const { return x_; }
  const VecX& velocities() const { return v_; }
  double time() const { return t_; }
  /// Optional hook called after each accepted step (time series output, progress).
  std::function<void(const VecX& x, double time)> on_accepted;

 private:
  const std::chrono::steady_clock::time_point created_ = std::chrono::steady_clock::now();  // max_wall_seconds counts from here
  struct History {
    VecX x, v, x_prev, v_prev;
    bool euler = false;  // no usable history: take an implicit Euler step
  };
  bool step(const History& in, double h, double load, History& out);
  /// One adaptive step by step doubling (advances 2h) or by the predictor (advances h).
  /// Returns the time advanced, 0 if the step was rejected (h_ is then reduced).
  double doubling_step(double load, History& accepted);
  double predictor_step(double load, History& accepted);
  /// Accepts or rejects on the error estimate and rescales h_ for the next attempt.
  bool accept_error(double err);
  /// Factor on h that brings the attempt's largest move / limit ratio to 0.75, within
  /// [0.1, 2] (2 when no term limits the step).
  double limit_scale() const;
  void reject_failed_step();
  History resampled(double h_new) const;
  double max_node_distance(const VecX& a, const VecX& b, bool monitors_only) const;
  /// True when the monitor node that moves most from `now` to `next` (more than the settle
  /// tolerance) turns back by more than 120° against its move from `before` to `now` (see
  /// "Period-2 swings" above).
  bool reverses(const VecX& next, const VecX& now, const VecX& before) const;
  static constexpr int kReversalsBeforeCut = 4;
  int reversals_ = 0;  // consecutive accepted steps that reversed

  MechanicalSystem& sys_;
  Bdf2Options opt_;
  std::unique_ptr<LinearSolver> solver_;
  SystemMatrix system_matrix_;
  VecX x_, v_, x_prev_, v_prev_, f_;
  double t_ = 0, h_ = 0, h_hist_ = 0;  // h_hist_: spacing between x_prev_ and x_
  std::vector<int> monitor_;
  long jacobians_ = 0;
  bool restart_ = true;  // next step is implicit Euler
  double limit_ratio_ = 0;  // largest |Δx_i| / limit_i over the current attempt's steps
};

}  // namespace valve
