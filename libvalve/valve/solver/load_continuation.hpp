#pragma once
// Load continuation shared by the equilibrium solvers (static_solver.hpp,
// quasistatic_solver.hpp): the load factor steps from `load_start` to `load_target`; an
// increment whose solve (`converge(load)`, which moves x) fails is undone and halved; one that
// converged in at most `fast_iterations` doubles the next.
#include <functional>

#include "valve/core/types.hpp"
#include "valve/solver/solver_summary.hpp"

namespace valve {

struct LoadContinuationOptions {
  double initial_increment = 1.0;  // first Δλ as a fraction of the load to apply
  double min_increment = 1e-5;     // stop below this fraction
  long max_increments = 100000000;
  double max_wall_seconds = 600;
  long fast_iterations = 6;        // iterations at or below which the increment doubles
};

/// Fills sum.status, reason and steps; returns the load factor reached. `iterations` reads the
/// solver's running iteration count; `on_failure` runs after a failed increment is undone.
double continue_load(VecX& x, double load_start, double load_target, const LoadContinuationOptions& options,
                     SolverSummary& sum, const std::function<double()>& wall_seconds,
                     const std::function<bool(double)>& converge, const std::function<long()>& iterations,
                     const std::function<void()>& on_failure = {});

}  // namespace valve
