#pragma once
// Scene -> the force terms and constraints it declares (and nothing more) -> a solver
// run over the scene's load increments.
#include <functional>
#include <memory>
#include <optional>
#include <vector>

#include "valve/scene/scene_config.hpp"
#include "valve/scene/scene_model.hpp"
#include "valve/mechanics/mechanical_system.hpp"
#include "valve/mesh/tri_mesh.hpp"
#include "valve/solver/solver_summary.hpp"

namespace valve {

/// Builds the mechanical system of a scene on `mesh`. Throws InputError when the scene
/// leaves the model unconstrained or names nodes the mesh does not have.
std::unique_ptr<MechanicalSystem> build_system(const SceneConfig& scene, const TriMesh& mesh);
/// The same for a model with chordae (rods, the branch points' mass) and annulus motion.
std::unique_ptr<MechanicalSystem> build_system(const SceneConfig& scene, const SceneModel& model);

/// Which material each triangle takes: 0 for the scene's, g + 1 for leaflet_materials[g].
/// Throws InputError when a leaflet is in two groups or a group names no leaflet of the mesh.
std::vector<int> material_groups(const SceneConfig& scene, const TriMesh& mesh);

/// The membrane terms of a scene: one per material group (leaflet_materials), the scene's
/// material for the leaflets no group claims.
void add_material_terms(const SceneConfig& scene, const TriMesh& mesh, MechanicalSystem& system);

/// Monitor nodes for the termination rule (empty = all free nodes).
std::vector<int> resolve_monitor(const SceneConfig& scene, const TriMesh& mesh);

struct IncrementResult {
  double load;
  SolverSummary summary;
};

/// The first of the aortic valve's two steps (seed 4.2.1): the root distended by the
/// pressure to equilibrium with its wall and the leaflets, before the leaflets are loaded.
struct RootDistension {
  SolverSummary summary;
  double mesh_diameter = 0;       // mm, attachment diameter of the mesh (leaflets unstressed)
  double unloaded_diameter = 0;   // mm, the root at zero pressure
  double tube_diameter = 0;       // mm, the root alone at the pressure: d0 / (1 − P r0 / (E t))
  double loaded_diameter = 0;     // mm, mean attachment diameter after the distension
};

/// Step one alone: solves for the distended attachment; `x` gets all positions.
RootDistension distend_root(const SceneConfig& scene, const TriMesh& mesh, VecX& x);

struct SimulationResult {
  VecX x;                    // final positions, 3N
  std::optional<RootDistension> root;
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

/// `mesh` with the start position of every node that `constrained` leaves free offset by
/// amplitude × u per coordinate, u uniform in [−1, 1] from a 64-bit Mersenne Twister seeded
/// with `seed` (the same offsets on every platform). Constrained nodes keep their positions.
TriMesh perturb_start_positions(const TriMesh& mesh, const std::vector<char>& constrained, const PerturbationConfig& p);

/// Runs the scene's solver over its load increments, stopping at the first increment that
/// does not converge. A scene's perturbation offsets the start first.
SimulationResult simulate(const SceneConfig& scene, const TriMesh& mesh, MechanicalSystem& system,
                          const SimulationHooks& hooks = {});

}  // namespace valve
