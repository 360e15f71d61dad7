#pragma once
// What a closure reports besides its positions (valve-simulate's summary and closed mesh).
//
// closure_run_metrics: for any run, failed or not: the solver summary, model and sizes, each
// load increment's status, the aortic root's distension, the annulus motion, the chordae
// (counts, taut segments, largest tension) and contact statistics with an intersection check
// done apart from the contact term (analysis/surface_intersections.hpp), which sees only
// distances.
//
// analyze_closed_valve: for finite closed positions x of the leaflet mesh (rest X):
//   Displacement (point)   x − X
//   GreenStrain (cell)     (E11, E22, E12) in each triangle's rest frame, tensor components
//   StretchFiber (cell)    |F a0| for the rest fiber direction a0; StretchCross the same across it
//   AreaRatio (cell)       current over rest area
//   PK2Stress (cell, FE)   each triangle's second Piola-Kirchhoff stress from its own law
//                          (leaflet_materials, else the scene's), (S11, S22, S12)
// with several leaflets the coaptation (analysis/coaptation.hpp) and its CoaptationGap_mm and
// Coapting point arrays, and per leaflet the free edge's and the midline's length at rest and
// closed (and, with an aortic root, the belly's drop), plus the largest displacement.
#include <nlohmann/json.hpp>
#include <optional>
#include <vector>

#include "valve/analysis/coaptation.hpp"
#include "valve/scene/scene_config.hpp"
#include "valve/mechanics/mechanical_system.hpp"
#include "valve/mesh/named_array.hpp"
#include "valve/scene/scene_model.hpp"
#include "valve/scene/simulation.hpp"

namespace valve {

/// The chordae at the end of a run: where each attachment point is and each segment's tension.
struct ChordaeState {
  MatX3 attachment_positions;  ///< one row per ChordaeNetwork point
  std::vector<double> tension;  ///< N, per segment (0 when slack)
};

struct ClosureRunReport {
  nlohmann::json metrics = nlohmann::json::object();
  std::optional<ChordaeState> chordae;  ///< when the model has chordae
};

/// `mesh` is the leaflet mesh; `full_state` holds every node of model.mesh (leaflets, then
/// chordae nodes).
ClosureRunReport closure_run_metrics(const SceneConfig& scene, const TriMesh& mesh, const SceneModel& model,
                                     const MechanicalSystem& system, const SimulationResult& result, const VecX& full_state);

struct ClosedValveAnalysis {
  std::vector<NamedArray> arrays;  ///< in the order listed above
  std::optional<CoaptationResult> coaptation;
  CoaptationOptions coaptation_options;  ///< the scene's, with the aortic root's axis
  nlohmann::json leaflets = nlohmann::json::array();  ///< per leaflet with a free edge
  double max_displacement_mm = 0;
};

/// Throws NumericalError when x is not finite (a failed run has nothing to analyse).
ClosedValveAnalysis analyze_closed_valve(const SceneConfig& scene, const TriMesh& mesh, const VecX& x);

}  // namespace valve
