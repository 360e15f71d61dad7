#pragma once
// The scene JSON: a mesh plus only the components the scene declares (model, material,
// pressure, edge loads, damping, fixed nodes, load increments, solver, monitor, output).
// Everything is validated and defaulted here, in one place; `used` records the values
// after defaults for the stage summary. See configs/README.md for the schema.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "valve/config/json_reader.hpp"
#include "valve/config/material_config.hpp"
#include "valve/mechanics/damping.hpp"
#include "valve/solver/bdf2.hpp"
#include "valve/solver/static_solver.hpp"

namespace valve {

enum class ModelKind { mass_spring, membrane_fe };
/// automatic: static equilibrium first (fast), dynamic BDF2 from the rest state if the static
/// solve does not converge. bdf2 alone also gives the time history.
enum class SolverKind { automatic, bdf2, static_newton };

struct PressureConfig {
  double value = 0;  // MPa
  bool along_normal = true;
};
struct EdgeLoadConfig {
  double stress_x = 0, stress_y = 0;  // MPa, Lagrangian
};
struct DampingConfig {
  DampingTerm::Mode mode = DampingTerm::Mode::critical;
  double factor = 1.0;  // ζ (critical) or α in 1/ms (mass_proportional)
};
struct FixedConfig {
  bool use_node_roles = true;   // nodes whose NodeRole is fixed
  std::vector<int> nodes;       // extra fixed nodes
  bool planar = false;          // fix z of every node (in-plane tests)
  bool pin_centre = false;      // fix x,y of the node nearest the centroid (in-plane translation).
                                // Rotation stays free: under dead edge loads, moment balance
                                // (P Fᵀ symmetric) fixes it, and pinning it would add a reaction
                                // couple that spoils the homogeneous biaxial state.
};
/// Virtual strain markers and the seed's per-increment convergence rule (3.2.2.5).
struct StrainMarkerConfig {
  double side = 1.5;         // mm
  bool seed_rule = true;     // converge an increment when both normal marker strains change
                             // by less than `rule_fraction` of their value per step
  double rule_fraction = 0.02;
};
struct MonitorConfig {
  enum class Kind { all, node, nearest_point, free_edge_middle } kind = Kind::all;
  int node = -1;
  Vec3 point = Vec3::Zero();
};

struct SceneConfig {
  std::filesystem::path file, mesh_path;
  ModelKind model = ModelKind::mass_spring;
  MaterialConfig material;
  double thickness = 0.5;     // mm
  double density = 1.06e-3;   // g/mm³
  std::optional<PressureConfig> pressure;
  std::optional<EdgeLoadConfig> edge_loads;
  std::optional<DampingConfig> damping;
  FixedConfig fixed;
  std::vector<double> load_increments{1.0};
  SolverKind solver = SolverKind::automatic;
  Bdf2Options bdf2;
  StaticOptions statics;
  MonitorConfig monitor;
  std::optional<StrainMarkerConfig> strain_markers;
  bool time_series = false;
  int time_series_every = 1;
  json used;
};

/// Loads and validates a scene file; relative paths inside are taken from its folder.
SceneConfig load_scene(const std::filesystem::path& file);
SceneConfig parse_scene(const json& j, const std::string& file, const std::filesystem::path& base_dir);

std::string to_string(ModelKind m);

}  // namespace valve
