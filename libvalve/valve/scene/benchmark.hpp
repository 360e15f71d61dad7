#pragma once
// Cost measurements in machine-independent and normalized units (DESIGN: Tests and
// measurement): internal-force time per element per evaluation (seed Table 3.3), and a
// closure run's counts with its total time divided by the time of one factorization of
// the same system.
#include <nlohmann/json.hpp>

#include "valve/scene/scene_config.hpp"
#include "valve/scene/scene_model.hpp"
#include "valve/mesh/tri_mesh.hpp"

namespace valve {

struct TermCost {
  std::string term;
  int elements = 0;                 // triangles
  double force_ns_per_element = 0;  // forces only, median over repetitions
  double force_and_jacobian_ns_per_element = 0;
};

/// Times the internal-force term of `model` on `mesh` at deformed positions `x`.
TermCost measure_term_cost(const SceneConfig& scene, const TriMesh& mesh, ModelKind model, const VecX& x,
                           int repetitions);

struct ClosureCost {
  nlohmann::json solver;            // the run's SolverSummary
  double solve_seconds = 0;         // wall time of simulate()
  double one_factorization_seconds = 0;  // median time to factorize the final system once
  double ratio_to_factorization = 0;
  /// The diagonal shift, as a fraction of the largest diagonal entry, under which the timed
  /// factorization succeeded: 0 (the tangent itself), else 1e-4, 1e-2, ..., 1e4; -1 if none did
  /// (nothing timed).
  double one_factorization_shift = -1;
  VecX x;
};

/// Runs the scene with `model` on the scene's whole model (leaflets, chordae, annulus motion:
/// prepare_scene_model) and measures one factorization of the final tangent. `x` holds the
/// leaflet nodes' final positions.
ClosureCost measure_closure(const SceneConfig& scene, const SceneModel& scene_model, ModelKind model, int repetitions);

/// One broad-phase method on one mesh (seed 4.2.3; valve-bench runs it on 660, 2,600 and
/// 10,000 triangles): median wall time of broad_phase_pairs() at the mesh's positions with the
/// penalty contact's detection distance as margin, and the candidate pairs it found.
struct BroadPhaseCost {
  std::string method;
  int triangles = 0;
  double margin_mm = 0;
  double seconds = 0;  // median over repetitions
  long pairs = 0;
};

/// Every method (sweep and prune, spatial hash, BVH, in that order) on `mesh` and on its
/// midpoint subdivisions ×4 and ×16 (same surface), with the scene's penalty-contact options
/// (defaults if it declares none). Throws Error if a method's pair list differs from sweep and
/// prune's: they are meant to be interchangeable.
std::vector<BroadPhaseCost> measure_broad_phase(const SceneConfig& scene, const TriMesh& mesh, int repetitions);

}  // namespace valve
