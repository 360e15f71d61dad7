#include "valve/solver/solver_summary.hpp"

#include <cstdio>

namespace valve {

std::string to_string(SolverStatus s) {
  switch (s) {
    case SolverStatus::ok: return "ok";
    case SolverStatus::not_converged: return "not_converged";
    case SolverStatus::failed: return "failed";
  }
  return "?";
}

nlohmann::json SolverSummary::to_json() const {
  nlohmann::json terms = nlohmann::json::array();
  for (const auto& t : term_timings) terms.push_back({{"term", t.name}, {"seconds", t.seconds}, {"calls", t.calls}});
  return {{"status", to_string(status)},
          {"reason", reason},
          {"steps", steps},
          {"rejected_steps", rejected_steps},
          {"oscillation_cuts", oscillation_cuts},
          {"newton_iterations", newton_iterations},
          {"jacobian_evaluations", jacobian_evaluations},
          {"exact_directions", exact_directions},
          {"scaled_exact_directions", scaled_exact_directions},
          {"projected_directions", projected_directions},
          {"solver", solver},
          {"fallback_from", fallback_from},
          {"approach", approach},
          {"linear_solver", linear_solver},
          {"factorizations", linear.factorizations},
          {"linear_solves", linear.solves},
          {"linear_iterations", linear.iterations},
          {"linear_failures", linear.failures},
          {"factorization_seconds", linear.factor_seconds},
          {"solve_seconds", linear.solve_seconds},
          {"simulated_time_ms", simulated_time_ms},
          {"final_step_ms", final_step_ms},
          {"last_monitor_displacement_mm", last_monitor_displacement_mm},
          {"max_free_force_N", max_free_force_N},
          {"relative_residual", relative_residual},
          {"wall_seconds", wall_seconds},
          {"term_timings", terms}};
}

std::string SolverSummary::one_line() const {
  char buf[512];
  std::snprintf(buf, sizeof buf,
                "%s (%s): %ld steps, %ld rejected, %ld Newton, %ld factorizations, %ld linear its, "
                "residual %.2e, %.3f s",
                to_string(status).c_str(), reason.c_str(), steps, rejected_steps, newton_iterations,
                linear.factorizations, linear.iterations, relative_residual, wall_seconds);
  return buf;
}

void SolverSummary::accumulate(const SolverSummary& o) {
  steps += o.steps;
  rejected_steps += o.rejected_steps;
  oscillation_cuts += o.oscillation_cuts;
  newton_iterations += o.newton_iterations;
  jacobian_evaluations += o.jacobian_evaluations;
  exact_directions += o.exact_directions;
  scaled_exact_directions += o.scaled_exact_directions;
  projected_directions += o.projected_directions;
  simulated_time_ms += o.simulated_time_ms;
  wall_seconds += o.wall_seconds;
  status = o.status;
  reason = o.reason;
  linear = o.linear;  // linear stats are cumulative per solver instance
  linear_solver = o.linear_solver;
  solver = o.solver;
  final_step_ms = o.final_step_ms;
  last_monitor_displacement_mm = o.last_monitor_displacement_mm;
  max_free_force_N = o.max_free_force_N;
  relative_residual = o.relative_residual;
  term_timings = o.term_timings;
}

}  // namespace valve
