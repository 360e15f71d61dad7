#pragma once
// The scene JSON: a mesh plus only the components the scene declares (model, material,
// pressure, edge loads, damping, fixed nodes, contact, aortic root, per-leaflet materials,
// load increments, solver, monitor, output).
// Everything is validated and defaulted here, in one place; `used` records the values
// after defaults for the stage summary. scene_key_table() lists the keys for docs/scene.md.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "valve/analysis/coaptation.hpp"
#include "valve/config/json_reader.hpp"
#include "valve/core/cli.hpp"
#include "valve/config/material_config.hpp"
#include "valve/mechanics/contact.hpp"
#include "valve/mechanics/penalty_contact.hpp"
#include "valve/mechanics/damping.hpp"
#include "valve/solver/bdf2.hpp"
#include "valve/solver/quasistatic_solver.hpp"
#include "valve/solver/static_solver.hpp"

namespace valve {

enum class ModelKind { mass_spring, membrane_fe };
/// automatic: static equilibrium first (fast), dynamic BDF2 from the rest state if the static
/// solve does not converge. bdf2 alone also gives the time history.
enum class SolverKind { automatic, bdf2, static_newton, quasistatic };

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

/// The aortic root as a boundary condition (seed 4.2.1): a thin elastic tube around `axis`
/// that the transvalvular pressure distends before the leaflets are loaded.
struct AorticRootConfig {
  Vec3 axis_point = Vec3::Zero();
  Vec3 axis_direction = Vec3::UnitZ();
  double unloaded_diameter_ratio = 1.15;  // mesh root diameter / root diameter at zero pressure
  double wall_thickness = 0;              // mm (from the preset)
  double youngs_modulus = 0;              // MPa (from the preset)
  double pressure = 0;                    // MPa distending the root (default: the scene pressure)
  /// MPa: above the linear tube's radius at this pressure the wall stiffens exponentially
  /// (mechanics/aortic_root.hpp); none keeps the seed's linear tube at every pressure.
  std::optional<double> stiffening_pressure;
  /// β above it (mechanics/aortic_root.hpp); none: the linear tube's own at that pressure.
  std::optional<double> stiffness_index;
  std::string preset, source;
};
/// Bending stiffness (mechanics/bending.hpp): flexural rigidity D = E_b t³ / 12.
struct BendingConfig {
  double modulus = 0;    // MPa, E_b
  double thickness = 0;  // mm (default: the scene's thickness)
  double flexural_rigidity() const { return modulus * thickness * thickness * thickness / 12; }  // N·mm
};
/// Chordae tendineae (seed 5.2.2): a chordae.json whose insertions are snapped to the
/// scene's mesh, as tension-only rods; papillary tips fixed (optionally moved to the
/// closed-state positions given in network order).
struct ChordaeConfig {
  std::filesystem::path file;
  /// file: each segment's own law and section where the chordae file gives them (e.g. the
  /// Texas TriValve deck's Ogden laws), linear elsewhere; linear: every chord linear.
  enum class Law { file, linear } law = Law::file;
  double youngs_modulus = 40.0;  // MPa (Table 5.1), the linear law
  double diameter = 0;           // mm; 0 = each segment's area_mm2, else the file's diameter_mm
  double snap_tolerance = 1.0;   // mm, for insertions not yet snapped to this mesh
  double rest_length_scale = 1.0;  // every chord's rest length × this (sensitivity, repairs)
  std::vector<std::string> types{"primary", "secondary", "strut"};  // chord types kept
  std::vector<Vec3> papillary_tips;  // closed-state tip positions (empty: as in the file)
  /// condensed: a run of chord segments through unbranched points is one rod
  /// (chordae_attachment.hpp), the same equilibrium with fewer unknowns; nodes: every point a
  /// node; automatic: condensed for the quasi-static solver, nodes for the others (BDF2 follows
  /// the chords' motion, and the remeshed Texas TriValve closure takes 9,793 steps condensed
  /// against 3,706 with every point a node).
  enum class Chains { automatic, nodes, condensed } chains = Chains::automatic;
};
/// Annulus motion (seed 5.2.2): the annulus nodes move from the open to the closed
/// positions before the pressure is applied. Targets come from the outer boundary loop of
/// the closed-state membrane mesh, registered rigidly to the open annulus.
struct AnnulusMotionConfig {
  std::filesystem::path closed_mesh;
  bool register_rigidly = true;
  /// How open annulus nodes find their closed positions: by arc-length fraction along the
  /// registered closed ring (seed 5.2.2; meshes of different scans), or the same node of the
  /// closed mesh (two states of one model, e.g. Texas TriValve frames 0 and 20).
  enum class Correspondence { arc_length, nodes } correspondence = Correspondence::arc_length;
};
/// A small random offset of every free node's start position, for reproducibility studies:
/// does the closed shape depend on rounding-sized differences of the input?
struct PerturbationConfig {
  double amplitude = 0;    // mm: each coordinate moves by amplitude × u, u uniform in [−1, 1]
  std::uint64_t seed = 1;  // the same seed gives the same offsets on every machine
};
/// A material (and thickness) for some leaflets, overriding the scene's.
struct LeafletMaterialConfig {
  std::vector<int> leaflets;
  MaterialConfig material;
  double thickness = 0;  // mm
};

/// How the quasi-static solver reaches its equilibrium (solver.quasistatic.approach).
/// `newton`: Newton iterations from the start. `dynamic`: the scene's BDF2 first, stopped once
/// its monitor nodes settle to `settle_tolerance` over its settle window (50 ms when the scene
/// sets none), then Newton at the last load: the damped trajectory picks the same closed shape
/// from nearby starts (Newton's own path through contact branches on rounding), and Newton then
/// takes it to a static equilibrium.
struct QuasistaticApproach {
  bool dynamic = false;
  double settle_tolerance = 0.05;  // mm
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
  /// contact.model: "penalty" (default) fills penalty_contact, "seed" fills contact.
  std::optional<ContactOptions> contact;
  std::optional<PenaltyContactOptions> penalty_contact;
  std::optional<AorticRootConfig> aortic_root;
  std::optional<ChordaeConfig> chordae;
  std::optional<BendingConfig> bending;
  /// How valve-simulate measures coaptation of a multi-leaflet mesh (the axis comes from aortic_root).
  CoaptationOptions coaptation;
  std::optional<AnnulusMotionConfig> annulus_motion;
  std::optional<PerturbationConfig> perturbation;
  std::vector<LeafletMaterialConfig> leaflet_materials;
  std::vector<double> load_increments{1.0};
  SolverKind solver = SolverKind::automatic;
  Bdf2Options bdf2;
  StaticOptions statics;
  QuasistaticOptions quasistatic;
  QuasistaticApproach quasistatic_approach;
  MonitorConfig monitor;
  std::optional<StrainMarkerConfig> strain_markers;
  bool time_series = false;
  int time_series_every = 10;  // accepted steps between frames
  json used;
  /// Settings that run but defeat a guarantee a user may count on, one line each (the
  /// stages print them as warnings).
  std::vector<std::string> warnings;
};

/// The scene file's JSON with a stage's command-line overrides applied: --mesh, --model,
/// --pressure, --solver (those a stage accepts) and every --set key.path=value.
json scene_json_with_overrides(const std::filesystem::path& scene_file, const CommandLine& cl);

/// Loads and validates a scene file; relative paths inside are taken from its folder.
SceneConfig load_scene(const std::filesystem::path& file);
SceneConfig parse_scene(const json& j, const std::string& file, const std::filesystem::path& base_dir);

std::string to_string(ModelKind m);

/// A row of the scene key table: a key as parse_scene reads it (type, default, range), and
/// the setting under which it has that meaning (empty: always).
struct SceneKeyRow {
  KeySpec key;
  std::string applies_when;
};
/// Every key parse_scene reads, recorded while it parses scenes that declare every block:
/// once as a whole, then once per choice that brings keys or defaults of its own (each
/// material law, contact model, damping type).
std::vector<SceneKeyRow> scene_key_table();
/// The table as markdown (`valve-simulate --scene-keys`; docs/scene.md holds it).
std::string scene_key_table_markdown();

}  // namespace valve
