#pragma once
// What a solver run reports (Ceres-style): a status with a reason, counts in
// machine-independent units, and the time spent in each force term and in linear algebra.
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "valve/mechanics/mechanical_system.hpp"
#include "valve/solver/linear_solver.hpp"

namespace valve {

enum class SolverStatus { ok, not_converged, failed };
std::string to_string(SolverStatus s);

struct SolverSummary {
  SolverStatus status = SolverStatus::not_converged;
  std::string reason;
  long steps = 0;               // accepted time steps (BDF2) or load increments (static)
  long rejected_steps = 0;
  long oscillation_cuts = 0;  // BDF2: steps cut because the state swung back and forth
  long newton_iterations = 0;   // static solver
  long jacobian_evaluations = 0;
  // Quasi-static: directions solved with exact contact Hessians, with their departure from the
  // projected ones scaled down (after an exact one failed), with projected ones.
  long exact_directions = 0, scaled_exact_directions = 0, projected_directions = 0;
  LinearSolverStats linear;
  std::string linear_solver;
  std::string solver;          // which solver produced the result (bdf2 | static)
  std::string fallback_from;   // set when the automatic choice fell back to BDF2, with why
  std::string approach;        // quasi-static: how Newton's start was reached (its BDF2 run), or empty
  double simulated_time_ms = 0;
  double final_step_ms = 0;
  double last_monitor_displacement_mm = 0;
  double max_free_force_N = 0;     // largest unbalanced nodal force at the end
  double relative_residual = 0;    // |f_free| / |f_external_free| at the end
  double wall_seconds = 0;
  std::vector<TermTiming> term_timings;

  nlohmann::json to_json() const;
  std::string one_line() const;
  /// Adds another run's counts (for runs continued over several load increments).
  void accumulate(const SolverSummary& other);
};

}  // namespace valve
