#include "valve/solver/bdf2.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "valve/core/error.hpp"
#include "valve/solver/constrained_system.hpp"

namespace valve {

Bdf2Integrator::Bdf2Integrator(MechanicalSystem& system, Bdf2Options options)
    : sys_(system), opt_(std::move(options)) {
  solver_ = make_linear_solver(opt_.linear_solver, opt_.iterative_tolerance, opt_.iterative_max_iterations,
                               sys_.num_dofs(), SystemSymmetry::symmetrized);
  monitor_ = opt_.monitor_nodes;
  if (monitor_.empty())
    for (int i = 0; i < sys_.num_nodes(); ++i)
      if (!sys_.constrained()[3 * i]) monitor_.push_back(i);
  h_ = opt_.initial_step;
}

void Bdf2Integrator::reset(const VecX& x0) {
  x_ = x0;
  x_prev_ = x0;
  v_ = VecX::Zero(x0.size());
  v_prev_ = v_;
  t_ = 0;
  h_ = opt_.initial_step;
  h_hist_ = h_;
}

Bdf2Integrator::History Bdf2Integrator::resampled(double h_new) const {
  History H{x_, v_, x_prev_, v_prev_, restart_};
  if (restart_) return H;
  if (std::abs(h_new - h_hist_) <= 1e-14 * h_hist_) return H;
  // Quadratic through x(0) = x^n, x'(0) = v^n, x(-h_old) = x^{n-1}, evaluated at -h_new.
  const double r = h_new / h_hist_;
  H.x_prev = x_ - h_new * v_ + r * r * (x_prev_ - x_ + h_hist_ * v_);
  H.v_prev = v_ - r * (v_ - v_prev_);
  return H;
}

bool Bdf2Integrator::step(const History& in, double h, double load, History& out) {
  const State s{in.x, in.v, load, t_};
  if (!sys_.evaluate(s, f_, true, sys_.has_velocity_terms())) return false;
  ++jacobians_;
  sys_.update_critical_damping(s, f_);
  const VecX& M = sys_.dof_masses();
  const VecX delta = in.x - in.x_prev;
  const bool velocity_terms = sys_.has_velocity_terms();
  const SparseMatrix* Dv = velocity_terms ? &sys_.dfdv().matrix() : nullptr;
  double c_x, c_v;
  VecX b;
  if (in.euler) {
    c_x = -h * h;
    c_v = -h;
    b = h * M.cwiseProduct(in.v) + (h * h) * f_;
    if (Dv) b -= (h * h) * (*Dv * in.v);
  } else {
    c_x = -4.0 / 9.0 * h * h;
    c_v = -2.0 / 3.0 * h;
    b = M.cwiseProduct(delta / 3.0 + (h / 9.0) * (8.0 * in.v - 2.0 * in.v_prev)) + (4.0 / 9.0 * h * h) * f_;
    if (Dv) b -= (4.0 / 9.0 * h * h) * (*Dv * in.v) + (2.0 / 9.0 * h) * (*Dv * delta);
  }
  const SparseMatrix& A = system_matrix_.assemble(sys_.dfdx(), c_x, velocity_terms ? &sys_.dfdv() : nullptr, c_v, M,
                                                  sys_.constrained(), solver_->needs_symmetric(), b);
  VecX dx;
  if (!solver_->factorize(A) || !solver_->solve(b, dx)) return false;
  out.x_prev = in.x;
  out.v_prev = in.v;
  // A node moving further than the force terms tolerate (contact: the separation and the
  // candidate list, see penalty_contact.hpp) fails the step.
  const double ratio = sys_.step_ratio(in.x, dx);
  limit_ratio_ = std::max(limit_ratio_, ratio);
  if (ratio > 1) return false;
  out.x = in.x + dx;
  out.v = in.euler ? VecX(dx / h) : VecX((1.5 * out.x - 2.0 * in.x + 0.5 * in.x_prev) / h);
  out.euler = false;
  for (int i = 0; i < out.v.size(); ++i)
    if (sys_.constrained()[i]) out.v[i] = 0;
  return out.x.allFinite() && out.v.allFinite();
}

bool Bdf2Integrator::reverses(const VecX& next, const VecX& now, const VecX& before) const {
  // The monitor node that moved most in this step; a 2-cycle sends it back along the way it came.
  int worst = -1;
  double largest = 0;
  for (int i : monitor_) {
    const double d = (node3(next, i) - node3(now, i)).norm();
    if (d > largest) largest = d, worst = i;
  }
  if (worst < 0 || largest <= opt_.settle_tolerance) return false;
  const Vec3 forward = node3(next, worst) - node3(now, worst), back = node3(now, worst) - node3(before, worst);
  return forward.dot(back) < -0.5 * forward.norm() * back.norm();
}

double Bdf2Integrator::max_node_distance(const VecX& a, const VecX& b, bool monitors_only) const {
  double m = 0;
  if (monitors_only) {
    for (int i : monitor_) m = std::max(m, (node3(a, i) - node3(b, i)).norm());
  } else {
    for (int i = 0; i < sys_.num_nodes(); ++i) m = std::max(m, (node3(a, i) - node3(b, i)).norm());
  }
  return m;
}

bool Bdf2Integrator::accept_error(double err) {
  const double scale = err > 0 ? 0.9 * std::cbrt(opt_.truncation_tolerance / err) : 2.0;
  if (err > opt_.truncation_tolerance) {
    h_ *= std::clamp(scale, 0.1, 0.5);
    return false;
  }
  h_hist_ = h_;
  h_ = std::min(opt_.max_step, h_ * std::min(std::clamp(scale, 0.2, 2.0), limit_scale()));
  return true;
}

double Bdf2Integrator::limit_scale() const {
  // A node's move grows at least linearly with h, so h * target / ratio keeps the largest
  // move near `target` of its limit.
  constexpr double target = 0.75;
  return limit_ratio_ > 0 ? std::clamp(target / limit_ratio_, 0.1, 2.0) : 2.0;
}

void Bdf2Integrator::reject_failed_step() {
  // A step over a node's move limit is cut to fit it; a failed solve is cut by 4.
  h_ *= limit_ratio_ > 1 ? limit_scale() : 0.25;
}

double Bdf2Integrator::doubling_step(double load, History& accepted) {
  limit_ratio_ = 0;
  History big, half1;
  bool ok = step(resampled(2 * h_), 2 * h_, load, big) && step(resampled(h_), h_, load, half1);
  if (ok) {
    const double save_t = t_;
    t_ += h_;
    const History mid{half1.x, half1.v, half1.x_prev, half1.v_prev, false};
    ok = step(mid, h_, load, accepted);
    t_ = save_t;
  }
  if (!ok) {
    reject_failed_step();
    return 0;
  }
  const double h = h_;
  return accept_error(max_node_distance(accepted.x, big.x, false)) ? 2 * h : 0;
}

double Bdf2Integrator::predictor_step(double load, History& accepted) {
  limit_ratio_ = 0;
  const History in = resampled(h_);
  if (!step(in, h_, load, accepted)) {
    reject_failed_step();
    return 0;
  }
  double diff = 0;  // largest nodal |x^{n+1} - x_p|, x_p = x^{n-1} + 2 h v^n
  for (int i = 0; i < sys_.num_nodes(); ++i)
    diff = std::max(diff, (node3(accepted.x, i) - node3(in.x_prev, i) - 2 * h_ * node3(in.v, i)).norm());
  const double h = h_;
  return accept_error(0.4 * diff) ? h : 0;
}

SolverSummary Bdf2Integrator::run(double load, const StepObserver& observer) {
  const auto t_start = std::chrono::steady_clock::now();
  auto wall = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - t_start).count(); };
  SolverSummary sum;
  sum.linear_solver = solver_->name();
  const long jac0 = jacobians_;
  restart_ = true;  // the load may have changed: the acceleration jumps
  reversals_ = 0;   // a swing is counted within one load level
  int quiet = 0;
  VecX settle_anchor = x_;  // positions at the start of the current settle window
  double settle_start = t_;
  const double t0 = t_;
  long steps = 0;
  History half2;
  auto finish = [&](SolverStatus st, std::string reason) {
    sum.status = st;
    sum.reason = std::move(reason);
    sum.steps = steps;
    sum.jacobian_evaluations = jacobians_ - jac0;
    sum.linear = solver_->stats();
    sum.simulated_time_ms = t_ - t0;
    sum.final_step_ms = h_;
    VecX f;
    const State s{x_, v_, load, t_};
    sys_.evaluate(s, f, false, false);
    // The static residual: the force left when velocities vanish (damping excluded).
    if (auto* d = sys_.damping()) {
      VecX fd = VecX::Zero(f.size());
      d->add(s, fd, nullptr, nullptr);
      f -= fd;
    }
    sum.max_free_force_N = sys_.max_free_force(f);
    const VecX fe = sys_.external_force(s);
    double fe_norm = 0, f_norm = 0;
    for (int i = 0; i < f.size(); ++i)
      if (!sys_.constrained()[i]) fe_norm += fe[i] * fe[i], f_norm += f[i] * f[i];
    sum.relative_residual = fe_norm > 0 ? std::sqrt(f_norm / fe_norm) : std::sqrt(f_norm);
    sum.wall_seconds = wall();
    sum.term_timings = sys_.timings();
    return sum;
  };

  while (true) {
    if (steps >= opt_.max_steps) return finish(SolverStatus::not_converged, "max_steps reached");
    if (t_ - t0 >= opt_.max_time) return finish(SolverStatus::not_converged, "max_time reached");
    if (std::chrono::duration<double>(std::chrono::steady_clock::now() - created_).count() >= opt_.max_wall_seconds)
      return finish(SolverStatus::not_converged, "max_wall_seconds reached");
    if (h_ < opt_.min_step)
      return finish(SolverStatus::failed, "step size fell below min_step (the model does not converge)");

    double advanced = 0;
    long taken = 1;
    if (!opt_.adaptive) {
      if (!step(resampled(h_), h_, load, half2)) {
        h_ *= 0.5;  // a fixed-step run still survives a failed solve
        ++sum.rejected_steps;
        continue;
      }
      advanced = h_;
      h_hist_ = h_;
    } else {
      const bool doubling = opt_.error_estimate == ErrorEstimate::step_doubling || restart_;
      advanced = doubling ? doubling_step(load, half2) : predictor_step(load, half2);
      if (advanced == 0) {
        ++sum.rejected_steps;
        continue;
      }
      taken = doubling ? 2 : 1;
    }
    restart_ = false;
    const bool reversed = reverses(half2.x, x_, x_prev_);
    x_prev_ = half2.x_prev;
    v_prev_ = half2.v_prev;
    x_ = half2.x;
    v_ = half2.v;
    t_ += advanced;
    steps += taken;
    reversals_ = reversed ? reversals_ + 1 : 0;
    if (opt_.adaptive && reversals_ >= kReversalsBeforeCut) {
      h_ *= 0.25;
      reversals_ = 0;
      ++sum.oscillation_cuts;
    }
    if (on_accepted) on_accepted(x_, t_);

    sum.last_monitor_displacement_mm = max_node_distance(x_, half2.x_prev, true);
    if (steps < opt_.min_steps) continue;
    if (observer) {
      if (observer(StepInfo{x_, v_, half2.x_prev, t_, h_hist_, steps}))
        return finish(SolverStatus::ok, "observer criterion met");
      continue;
    }
    const auto residual_ok = [&] {
      return opt_.relative_residual_tolerance <= 0 ||
             finish(SolverStatus::ok, "").relative_residual <= opt_.relative_residual_tolerance;
    };
    quiet = sum.last_monitor_displacement_mm < opt_.displacement_tolerance ? quiet + 1 : 0;
    if (quiet >= opt_.quiet_steps && residual_ok())
      return finish(SolverStatus::ok, "monitor displacement per step below tolerance");
    if (opt_.settle_window > 0) {
      const bool strayed = max_node_distance(x_, settle_anchor, true) > opt_.settle_tolerance;
      if (!strayed && t_ - settle_start >= opt_.settle_window && residual_ok())
        return finish(SolverStatus::ok, "monitor nodes settled within settle_tolerance over settle_window");
      if (strayed || t_ - settle_start >= opt_.settle_window) {  // a new window (the residual is probed once per window)
        settle_anchor = x_;
        settle_start = t_;
      }
    }
  }
}

}  // namespace valve
