#include "valve/solver/load_continuation.hpp"

#include <cmath>
#include <string>

namespace valve {

double continue_load(VecX& x, double load_start, double load_target, const LoadContinuationOptions& opt,
                     SolverSummary& sum, const std::function<double()>& wall_seconds,
                     const std::function<bool(double)>& converge, const std::function<long()>& iterations,
                     const std::function<void()>& on_failure) {
  double load = load_start, dload = opt.initial_increment * (load_target - load_start);
  if (load_target == load_start) dload = 0;
  long increments = 0;
  while (true) {
    if (wall_seconds() > opt.max_wall_seconds) {
      sum.status = SolverStatus::not_converged;
      sum.reason = "max_wall_seconds reached at load factor " + std::to_string(load);
      break;
    }
    if (increments >= opt.max_increments) {
      sum.status = SolverStatus::not_converged;
      sum.reason = "max_increments reached";
      break;
    }
    const double next = dload == 0 ? load_target
                                   : (std::abs(load_target - load) <= std::abs(dload) ? load_target : load + dload);
    const VecX saved = x;
    const long before = iterations();
    if (converge(next)) {
      ++increments;
      load = next;
      if (load == load_target) {
        sum.status = SolverStatus::ok;
        sum.reason = "residual below tolerance at the target load";
        break;
      }
      if (iterations() - before <= opt.fast_iterations) dload *= 2;
    } else {
      x = saved;
      ++sum.rejected_steps;
      dload *= 0.5;
      if (on_failure) on_failure();
      if (std::abs(dload) < opt.min_increment * std::abs(load_target - load_start) || dload == 0) {
        sum.status = SolverStatus::not_converged;
        sum.reason = "load increment fell below min_increment at load factor " + std::to_string(load) +
                     " (relative residual " + std::to_string(sum.relative_residual) + ")";
        break;
      }
    }
  }
  sum.steps = increments;
  return load;
}

}  // namespace valve
