#pragma once
// Static equilibrium f(x; λ) = 0 for scenes where only the loaded state matters.
//
// A membrane at rest has no out-of-plane stiffness, and a leaflet under pressure must
// snap through (invert its curvature) on the way to equilibrium, so plain Newton stalls.
// We use pseudo-transient continuation (Ψtc, Kelley & Keyes 1998): each iteration solves
//     (K + M/δ) Δx = f,   K = -∂f/∂x,  M the lumped mass,
// which is an implicit Euler step from rest of pseudo-time sqrt(δ); δ follows switched
// evolution relaxation, δ ← δ · 1.5 |f_old|/|f_new| (bounded to [1/4, 4] per step), so far from equilibrium
// the iteration behaves like damped dynamics and near it like Newton (δ → ∞, quadratic
// convergence). Steps longer than the trust radius, or (optionally) that change an edge's
// length by more than max_strain_increment, are scaled down and δ shrinks with them; a
// failed solve or a non-finite trial (the Fung exponential overflowing) shrinks δ too. Load continuation (λ increments, halved on failure) is kept
// for strongly nonlinear loading paths.
#include "valve/mechanics/mechanical_system.hpp"
#include "valve/solver/linear_solver.hpp"
#include "valve/solver/solver_summary.hpp"

namespace valve {

struct StaticOptions {
  double relative_residual_tolerance = 1e-9;  // |f_free| / |f_external_free| (without an
                                              // external load: / the solve's first |f_free|)
  int max_newton_iterations = 500;            // per load increment
  double initial_increment = 1.0;             // first Δλ
  double initial_pseudo_step = 1e-2;          // δ0 in ms² (pseudo time step squared)
  double trust_radius = 0;                    // mm: largest nodal move per iteration;
                                              // 0 = 2.5 % of the bounding-box diagonal
  double max_strain_increment = 0;            // largest change of any edge's length per
                                              // iteration, relative to its current length;
                                              // 0 = off (a 10 % limit slowed 20,000-triangle
                                              // closures from 122 to 300+ factorizations)
  double residual_reference_load = 0;          // > 0: scale residuals by the external force at
                                              // this load factor instead of the current one
                                              // (a solve at load 0, e.g. annulus motion before
                                              // the pressure, has no external force of its own)
  double min_increment = 1e-5;
  long max_increments = 2000;
  double max_wall_seconds = 600;
  LinearSolverType linear_solver = LinearSolverType::automatic;  // non-symmetric (pressure): KLU or UMFPACK
  double iterative_tolerance = 1e-10;
  int iterative_max_iterations = 5000;
};

/// Solves from x (updated in place) at load factors from `load_start` up to `load_target`.
SolverSummary solve_static(MechanicalSystem& system, VecX& x, const StaticOptions& options,
                           double load_target = 1.0, double load_start = 0.0);

}  // namespace valve
