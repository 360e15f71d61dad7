#pragma once
// The seed's biaxial test protocol (3.2.2.5) on top of a scene with edge loads and strain
// markers: after every accepted step the marker strains are read; an increment has
// converged when both normal strains changed by less than 2 % of their (cumulative) value
// in `quiet_steps` consecutive steps. Each converged increment records the marker strain,
// the second Piola-Kirchhoff stress and the law's strain at that stress.
#include <nlohmann/json.hpp>
#include <vector>

#include "valve/analysis/strain_markers.hpp"
#include "valve/scene/scene_config.hpp"
#include "valve/scene/simulation.hpp"

namespace valve {

class BiaxialProtocol {
 public:
  BiaxialProtocol(const SceneConfig& scene, const TriMesh& mesh);
  /// Hooks to pass to simulate(): the seed rule (if configured) and per-increment records.
  void install(SimulationHooks& hooks);
  /// increments[], and components[] comparing the final increment with the law.
  nlohmann::json report() const;

 private:
  const SceneConfig& scene_;
  StrainMarkers markers_;
  std::shared_ptr<const MaterialLaw> law_;
  nlohmann::json increments_ = nlohmann::json::array();
  Eigen::Vector3d last_E_ = Eigen::Vector3d::Zero(), last_S_ = Eigen::Vector3d::Zero();
};

}  // namespace valve
