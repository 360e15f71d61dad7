#pragma once
// Scene -> the force terms and constraints it declares (and nothing more) -> a solver
// run over the scene's load increments.
#include <functional>
#include <memory>
#include <vector>

#include "valve/config/scene_config.hpp"
#include "valve/mechanics/mechanical_system.hpp"
#include "valve/mesh/tri_mesh.hpp"
#include "valve/solver/solver_summary.hpp"

namespace valve {

/// Builds the mechanical system of a scene on `mesh`. Throws InputError when the scene
/// leaves the model unconstrained or names nodes the mesh does not have.
std::unique_ptr<MechanicalSystem> build_system(const SceneConfig& scene, const TriMesh& mesh);

/// Monitor nodes for the termination rule (empty = all free nodes).
std::vector<int> resolve_monitor(const SceneConfig& scene, const TriMesh& mesh);

struct IncrementResult {
  double load;
  SolverSummary summary;
};

struct SimulationResult {
  VecX x;                    // final positions, 3N
  SolverSummary summary;     // accumulated over increments; status of the last one
  std::vector<IncrementResult> increments;
};

struct SimulationHooks {
  /// Per-increment convergence rule replacing the monitor rule (BDF2 only).
  std::function<StepObserver(int increment, double load)> observer_for_increment;
  /// Called after every accepted BDF2 step.
  std::function<void(const VecX& x, double time)> on_step;
  /// Called after each load increment converges (or stops).
  std::function<void(int increment, const VecX& x, const IncrementResult&)> on_increment;
};

/// Runs the scene's solver over its load increments, stopping at the first increment that
/// does not converge.
SimulationResult simulate(const SceneConfig& scene, const TriMesh& mesh, MechanicalSystem& system,
                          const SimulationHooks& hooks = {});

}  // namespace valve
