#pragma once
// Cost measurements in machine-independent and normalized units (DESIGN: Tests and
// measurement): internal-force time per element per evaluation (seed Table 3.3), and a
// closure run's counts with its total time divided by the time of one factorization of
// the same system.
#include <nlohmann/json.hpp>

#include "valve/config/scene_config.hpp"
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
  VecX x;
};

/// Runs the scene with `model` and measures one factorization of the final tangent.
ClosureCost measure_closure(const SceneConfig& scene, const TriMesh& mesh, ModelKind model, int repetitions);

}  // namespace valve
