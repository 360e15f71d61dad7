#include "valve/scene/biaxial_protocol.hpp"

#include <cmath>

#include "valve/core/error.hpp"

namespace valve {

BiaxialProtocol::BiaxialProtocol(const SceneConfig& scene, const TriMesh& mesh)
    : scene_(scene), markers_(mesh, scene.strain_markers ? scene.strain_markers->side : 1.5) {
  if (!scene.edge_loads) throw InputError(scene.file.string() + ": strain_markers: expected edge_loads in the same scene, found none");
  // The law the markers are compared with is the Fung law of the material, whichever model runs.
  law_ = scene.material.law();
}

void BiaxialProtocol::install(SimulationHooks& hooks) {
  const StrainMarkerConfig cfg = scene_.strain_markers.value_or(StrainMarkerConfig{});
  if (cfg.seed_rule && scene_.solver == SolverKind::bdf2) {
    const int needed = scene_.bdf2.quiet_steps;
    hooks.observer_for_increment = [this, cfg, needed](int, double) -> StepObserver {
      auto quiet = std::make_shared<int>(0);
      return [this, cfg, needed, quiet](const StepInfo& s) {
        const Eigen::Vector3d E = markers_.green_strain(s.x), E0 = markers_.green_strain(s.x_before);
        bool small = true;
        for (int k = 0; k < 2; ++k) small = small && std::abs(E[k] - E0[k]) < cfg.rule_fraction * std::abs(E[k]);
        *quiet = small ? *quiet + 1 : 0;
        return *quiet >= needed;
      };
    };
  }
  hooks.on_increment = [this](int, const VecX& x, const IncrementResult& inc) {
    const double Px = inc.load * scene_.edge_loads->stress_x, Py = inc.load * scene_.edge_loads->stress_y;
    last_E_ = markers_.green_strain(x);
    last_S_ = markers_.pk2_stress(x, Px, Py);
    Voigt E_law;
    const bool ok = invert_stress(*law_, last_S_, E_law);
    increments_.push_back({{"load", inc.load},
                           {"status", to_string(inc.summary.status)},
                           {"steps", inc.summary.steps},
                           {"P_x_MPa", Px},
                           {"P_y_MPa", Py},
                           {"S", {last_S_[0], last_S_[1], last_S_[2]}},
                           {"E", {last_E_[0], last_E_[1], 0.5 * last_E_[2]}},
                           {"E_law", ok ? nlohmann::json{E_law[0], E_law[1], 0.5 * E_law[2]} : nlohmann::json(nullptr)}});
  };
}

nlohmann::json BiaxialProtocol::report() const {
  nlohmann::json components = nlohmann::json::array();
  for (const auto& c : compare_with_law(last_E_, last_S_, *law_))
    components.push_back({{"component", c.component},
                          {"kind", c.component == "E12" ? "shear" : "normal"},
                          {"simulated", c.simulated},
                          {"law", c.law},
                          {"error_pct", c.error_pct}});
  return {{"increments", increments_}, {"components", components},
          {"note", "material axes; E12 is the tensor shear strain; S is 2nd Piola-Kirchhoff in MPa"}};
}

}  // namespace valve
