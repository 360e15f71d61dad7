#include "valve/scene/simulation.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <random>

#include "valve/core/error.hpp"
#include "valve/analysis/leaflet_metrics.hpp"
#include "valve/mechanics/aortic_root.hpp"
#include "valve/mechanics/bending.hpp"
#include "valve/mechanics/chordae_rods.hpp"
#include "valve/mesh/closest_point.hpp"
#include "valve/mechanics/contact.hpp"
#include "valve/mechanics/penalty_contact.hpp"
#include "valve/mechanics/damping.hpp"
#include "valve/mechanics/mass_spring.hpp"
#include "valve/mechanics/membrane_fe.hpp"
#include "valve/mechanics/nodal_load.hpp"
#include "valve/mechanics/pressure.hpp"
#include "valve/solver/bdf2.hpp"
#include "valve/solver/static_solver.hpp"

namespace valve {

namespace {

// Leaflets listed in leaflet_materials get their own material and thickness; the rest of
// the mesh gets the scene's. Each group is one term over its triangles.
TriMesh triangle_subset(const TriMesh& m, const std::vector<char>& keep) {
  TriMesh sub = m;
  sub.triangles.clear();
  sub.leaflet.clear();
  std::vector<int> kept;
  for (int t = 0; t < m.num_triangles(); ++t)
    if (keep[t]) kept.push_back(t);
  sub.fiber.resize(static_cast<int>(kept.size()), 3);
  for (size_t k = 0; k < kept.size(); ++k) {
    sub.triangles.push_back(m.triangles[kept[k]]);
    sub.leaflet.push_back(m.leaflet[kept[k]]);
    sub.fiber.row(k) = m.fiber.row(kept[k]);
  }
  return sub;
}

void add_material_term(const SceneConfig& sc, const TriMesh& m, const MaterialConfig& mat, double thickness,
                       MechanicalSystem& sys) {
  if (m.triangles.empty()) return;
  if (sc.model == ModelKind::mass_spring)
    sys.add_term(std::make_unique<MassSpringTerm>(m, mat.bilinear(), thickness));
  else
    sys.add_term(std::make_unique<MembraneFETerm>(m, mat.law(), thickness));
}

}  // namespace

std::vector<int> material_groups(const SceneConfig& sc, const TriMesh& m) {
  std::vector<int> group(m.num_triangles(), 0);
  for (size_t g = 0; g < sc.leaflet_materials.size(); ++g) {
    const auto& leaflets = sc.leaflet_materials[g].leaflets;
    const std::string key = "leaflet_materials[" + std::to_string(g) + "].leaflets";
    int count = 0;
    for (int t = 0; t < m.num_triangles(); ++t) {
      if (std::find(leaflets.begin(), leaflets.end(), m.leaflet[t]) == leaflets.end()) continue;
      if (group[t] != 0)
        throw_input_error(sc.file.string(), key, "each leaflet in one group", "leaflet " + std::to_string(m.leaflet[t]) + " listed twice");
      group[t] = static_cast<int>(g) + 1;
      ++count;
    }
    if (count == 0)
      throw_input_error(sc.file.string(), key, "leaflet indices present in the mesh's Leaflet array", describe_json(json(leaflets)));
  }
  return group;
}

void add_material_terms(const SceneConfig& sc, const TriMesh& m, MechanicalSystem& sys) {
  if (sc.leaflet_materials.empty()) {
    add_material_term(sc, m, sc.material, sc.thickness, sys);
    return;
  }
  const std::vector<int> group = material_groups(sc, m);
  for (size_t g = 0; g <= sc.leaflet_materials.size(); ++g) {
    std::vector<char> keep(m.num_triangles());
    for (int t = 0; t < m.num_triangles(); ++t) keep[t] = group[t] == static_cast<int>(g);
    const TriMesh subset = triangle_subset(m, keep);
    if (g == 0)
      add_material_term(sc, subset, sc.material, sc.thickness, sys);
    else
      add_material_term(sc, subset, sc.leaflet_materials[g - 1].material, sc.leaflet_materials[g - 1].thickness, sys);
  }
}

namespace {

std::unique_ptr<MechanicalSystem> build_system(const SceneConfig& sc, const TriMesh& mesh, const SceneModel* model) {
  const std::string where = sc.file.string();
  TriMesh m = mesh;
  if (!sc.fixed.use_node_roles) m.roles.assign(m.num_nodes(), NodeRole::free);
  if (model && model->annulus)  // the annulus moves to its targets and stays there
    for (int i : model->annulus->nodes) m.roles[i] = NodeRole::fixed;
  auto sys = std::make_unique<MechanicalSystem>(m, sc.density, sc.thickness);
  if (model && !model->attachment.rods.empty()) {
    const ChordaeAttachment& a = model->attachment;
    for (std::size_t k = 0; k < a.extra_mass.size(); ++k) {
      const int node = a.mesh_nodes + static_cast<int>(k);
      sys->add_node_mass(node, a.extra_mass[k]);
      if (a.extra_roles[k] == NodeRole::free) sys->free_node(node);
    }
  }
  for (int i : sc.fixed.nodes) {
    if (i < 0 || i >= m.num_nodes())
      throw_input_error(where, "fixed.nodes", "node indices in [0, " + std::to_string(m.num_nodes() - 1) + "]", std::to_string(i));
    sys->fix_node(i);
  }
  if (sc.fixed.planar)
    for (int i = 0; i < m.num_nodes(); ++i) sys->constrained()[3 * i + 2] = 1;
  if (sc.fixed.pin_centre) {
    const int centre = nearest_point_index(m.points, m.points.colwise().mean().transpose());
    sys->constrained()[3 * centre] = sys->constrained()[3 * centre + 1] = 1;
  }
  // Model only what the scene requires: each block below exists only if declared.
  add_material_terms(sc, m, *sys);
  if (sc.bending) sys->add_term(std::make_unique<BendingTerm>(m, sc.bending->flexural_rigidity()));
  std::vector<const ForceTerm*> external;
  if (sc.pressure) {
    auto term = std::make_unique<PressureTerm>(m, sc.pressure->value, sc.pressure->along_normal);
    external.push_back(term.get());
    sys->add_term(std::move(term));
  }
  if (sc.contact) sys->add_term(std::make_unique<ContactTerm>(m, *sc.contact, external, sys->constrained()));
  if (sc.penalty_contact) sys->add_term(std::make_unique<PenaltyContactTerm>(m, *sc.penalty_contact, sys->constrained()));
  if (sc.edge_loads)
    sys->add_term(std::make_unique<NodalLoadTerm>(
        biaxial_edge_forces(m, sc.edge_loads->stress_x, sc.edge_loads->stress_y, sc.thickness)));
  if (model && !model->attachment.rods.empty()) sys->add_term(std::make_unique<ChordaeTerm>(model->attachment.rods));
  if (sc.damping) sys->add_term(std::make_unique<DampingTerm>(sys->node_masses(), sc.damping->mode, sc.damping->factor));
  sys->finalize();

  int free_dofs = 0;
  for (char c : sys->constrained()) free_dofs += !c;
  if (free_dofs == 0) throw_input_error(where, "fixed", "at least one free node", "every node constrained");
  if (free_dofs == sys->num_dofs() && !sc.fixed.planar)
    throw_input_error(where, "fixed", "at least one constrained node (NodeRole fixed, fixed.nodes or fixed.pin_centre)",
                      "none: the model could move as a rigid body");
  return sys;
}

}  // namespace

std::unique_ptr<MechanicalSystem> build_system(const SceneConfig& sc, const TriMesh& mesh) {
  return build_system(sc, mesh, nullptr);
}

std::unique_ptr<MechanicalSystem> build_system(const SceneConfig& sc, const SceneModel& model) {
  return build_system(sc, model.mesh, &model);
}

std::vector<int> resolve_monitor(const SceneConfig& sc, const TriMesh& m) {
  switch (sc.monitor.kind) {
    case MonitorConfig::Kind::all: return {};
    case MonitorConfig::Kind::node:
      if (sc.monitor.node >= m.num_nodes())
        throw_input_error(sc.file.string(), "monitor", "a node index below " + std::to_string(m.num_nodes()), std::to_string(sc.monitor.node));
      return {sc.monitor.node};
    case MonitorConfig::Kind::nearest_point:
      return {nearest_point_index(m.points, sc.monitor.point)};
    case MonitorConfig::Kind::free_edge_middle: {
      const int n = free_edge_middle_node(m, 0);
      if (n < 0) throw_input_error(sc.file.string(), "monitor", "a mesh with free-edge nodes (BoundaryType 2)", "none");
      return {n};
    }
  }
  return {};
}

namespace {

// The scene's load increments; with annulus motion, first an equilibrium at zero pressure
// with the annulus at its closed positions (seed 5.2.2: "first, mesh nodes lying on the
// valve annulus are moved ...").
std::vector<double> load_steps(const SceneConfig& sc) {
  std::vector<double> loads = sc.load_increments;
  if (!sc.annulus_motion) return loads;
  if (!sc.pressure && !sc.edge_loads) return {0.0};  // nothing is loaded: the annulus step is all
  if (loads.empty() || loads.front() != 0) loads.insert(loads.begin(), 0.0);
  return loads;
}

SimulationResult run_bdf2(const SceneConfig& sc, const TriMesh& mesh, MechanicalSystem& sys, const SimulationHooks& hooks,
                          const std::vector<int>& monitor) {
  SimulationResult res;
  Bdf2Options opt = sc.bdf2;
  opt.monitor_nodes = monitor;
  Bdf2Integrator integ(sys, opt);
  integ.reset(flatten(mesh.start_positions()));
  if (hooks.on_step) integ.on_accepted = hooks.on_step;
  const std::vector<double> loads = load_steps(sc);
  for (size_t k = 0; k < loads.size(); ++k) {
    const double load = loads[k];
    StepObserver obs = hooks.observer_for_increment ? hooks.observer_for_increment(static_cast<int>(k), load) : StepObserver{};
    IncrementResult inc{load, integ.run(load, obs)};
    if (k == 0)
      res.summary = inc.summary;
    else
      res.summary.accumulate(inc.summary);
    res.increments.push_back(inc);
    if (hooks.on_increment) hooks.on_increment(static_cast<int>(k), integ.positions(), inc);
    if (inc.summary.status != SolverStatus::ok) break;
  }
  res.x = integ.positions();
  res.summary.solver = "bdf2";
  return res;
}

// The equilibrium solvers (static, quasi-static) over the scene's load steps, each step from
// where the last ended; `solve` takes one step from `previous` to `load` within `wall_seconds`
// (what is left of the solver's max_wall_seconds: the limit holds for the whole closure, not
// for each step). Each step's solver is new, so linear statistics add up.
using EquilibriumStep = std::function<SolverSummary(VecX&, double load, double previous, double wall_seconds)>;
SimulationResult run_equilibrium(const SceneConfig& sc, const TriMesh& mesh, const SimulationHooks& hooks,
                                 const std::string& name, double max_wall_seconds, const EquilibriumStep& solve) {
  const auto start = std::chrono::steady_clock::now();
  SimulationResult res;
  res.x = flatten(mesh.start_positions());
  double previous = 0;
  const std::vector<double> loads = load_steps(sc);
  for (size_t k = 0; k < loads.size(); ++k) {
    const double load = loads[k];
    const double spent = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    IncrementResult inc{load, solve(res.x, load, previous, std::max(0.0, max_wall_seconds - spent))};
    previous = load;
    if (k == 0) {
      res.summary = inc.summary;
    } else {
      const LinearSolverStats before = res.summary.linear;
      res.summary.accumulate(inc.summary);
      res.summary.linear += before;
    }
    res.increments.push_back(inc);
    if (hooks.on_increment) hooks.on_increment(static_cast<int>(k), res.x, inc);
    if (inc.summary.status != SolverStatus::ok) break;
  }
  res.summary.solver = name;
  return res;
}

SimulationResult run_static(const SceneConfig& sc, const TriMesh& mesh, MechanicalSystem& sys, const SimulationHooks& hooks) {
  return run_equilibrium(sc, mesh, hooks, "static", sc.statics.max_wall_seconds,
                         [&](VecX& x, double load, double previous, double wall_seconds) {
    StaticOptions options = sc.statics;
    options.max_wall_seconds = wall_seconds;
    if (load == 0) options.residual_reference_load = 1.0;
    return solve_static(sys, x, options, load, previous);
  });
}

SimulationResult run_quasistatic(const SceneConfig& sc, const TriMesh& mesh, MechanicalSystem& sys,
                                 const SimulationHooks& hooks, const std::vector<int>& monitor) {
  if (sc.quasistatic_approach.dynamic) {
    // BDF2 over every load step until it settles, then Newton at the last load from there.
    const auto start = std::chrono::steady_clock::now();
    auto elapsed = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };
    SceneConfig dynamic = sc;
    dynamic.bdf2.settle_tolerance = sc.quasistatic_approach.settle_tolerance;
    if (dynamic.bdf2.settle_window <= 0) dynamic.bdf2.settle_window = 50;
    dynamic.bdf2.max_wall_seconds = std::min(sc.bdf2.max_wall_seconds, sc.quasistatic.max_wall_seconds);
    SimulationResult approach = run_bdf2(dynamic, mesh, sys, SimulationHooks{}, monitor);
    char line[256];
    std::snprintf(line, sizeof line, "bdf2 to %g mm settled: %s, %ld steps, %ld factorizations, %.3f s",
                  sc.quasistatic_approach.settle_tolerance, to_string(approach.summary.status).c_str(),
                  approach.summary.steps, approach.summary.linear.factorizations, approach.summary.wall_seconds);
    if (!approach.x.allFinite()) {
      approach.summary.status = SolverStatus::failed;
      approach.summary.reason = "the dynamic approach ended at non-finite positions";
      approach.summary.solver = "quasistatic";
      approach.summary.approach = line;
      return approach;
    }
    SimulationResult res;
    res.x = approach.x;
    const double load = load_steps(sc).back();
    QuasistaticOptions options = sc.quasistatic;
    options.max_wall_seconds = std::max(0.0, sc.quasistatic.max_wall_seconds - elapsed());
    SolverSummary newton = solve_quasistatic(sys, res.x, options, load, load);
    res.summary = newton;
    res.summary.steps = approach.summary.steps;
    res.summary.rejected_steps = approach.summary.rejected_steps + newton.rejected_steps;
    res.summary.jacobian_evaluations += approach.summary.jacobian_evaluations;
    res.summary.simulated_time_ms = approach.summary.simulated_time_ms;
    res.summary.linear += approach.summary.linear;
    res.summary.wall_seconds = elapsed();
    res.summary.solver = "quasistatic";
    res.summary.approach = line;
    res.increments.push_back(IncrementResult{load, res.summary});
    if (hooks.on_increment) hooks.on_increment(0, res.x, res.increments.back());
    return res;
  }
  return run_equilibrium(sc, mesh, hooks, "quasistatic", sc.quasistatic.max_wall_seconds,
                         [&](VecX& x, double load, double previous, double wall_seconds) {
    QuasistaticOptions options = sc.quasistatic;
    options.max_wall_seconds = wall_seconds;
    return solve_quasistatic(sys, x, options, load, previous);
  });
}

}  // namespace

RootDistension distend_root(const SceneConfig& sc, const TriMesh& mesh, VecX& x) {
  const AorticRootConfig& rc = *sc.aortic_root;
  const RootGeometry g = root_geometry(mesh, rc.axis_point, rc.axis_direction);
  RootDistension out;
  out.mesh_diameter = 2 * g.mesh_radius;
  const double r0 = g.mesh_radius / rc.unloaded_diameter_ratio;
  out.unloaded_diameter = 2 * r0;
  // The stiffening radius: the linear tube's radius at the stiffening pressure.
  std::optional<double> stiffening_radius;
  if (rc.stiffening_pressure)
    stiffening_radius = free_tube_radius(*rc.stiffening_pressure, rc.youngs_modulus, rc.wall_thickness, r0, std::nullopt);
  try {
    out.tube_diameter = 2 * free_tube_radius(rc.pressure, rc.youngs_modulus, rc.wall_thickness, r0, stiffening_radius,
                                             rc.stiffness_index);
  } catch (const NumericalError&) {
    out.tube_diameter = std::numeric_limits<double>::infinity();
  }
  // The attachment is free to follow the root; everything else as in the scene, minus the
  // leaflet pressure (the leaflets are loaded in the second step).
  TriMesh free_mesh = mesh;
  free_mesh.roles.assign(mesh.num_nodes(), NodeRole::free);
  MechanicalSystem sys(free_mesh, sc.density, sc.thickness);
  add_material_terms(sc, free_mesh, sys);
  sys.add_term(std::make_unique<RootSpringTerm>(g, mesh.start_positions(), rc.youngs_modulus, rc.wall_thickness, r0,
                                                stiffening_radius, rc.stiffness_index));
  sys.add_term(std::make_unique<RootPressureTerm>(g, rc.pressure));
  sys.finalize();
  x = flatten(mesh.start_positions());
  // Start from the free tube's radius: the leaflets then carry little stress and the
  // solve only corrects for their tension (hundreds of iterations fewer than from the mesh).
  if (std::isfinite(out.tube_diameter)) {
    const double scale = out.tube_diameter / out.mesh_diameter;
    for (int i = 0; i < mesh.num_nodes(); ++i) {
      const Vec3 p = node3(x, i), a = g.axis_point, u = g.axis_direction;
      const Vec3 along = a + u * u.dot(p - a);
      node3(x, i) = along + scale * (p - along);
    }
  }
  // Straight at full pressure: the leaflets start unstressed near the distended diameter,
  // while ramping the pressure from zero would first crush them onto the unloaded root.
  out.summary = solve_static(sys, x, sc.statics, 1.0, 1.0);
  out.summary.solver = "static";
  double r = 0;
  for (int i : g.nodes) r += radius_from_axis(g, node3(x, i));
  out.loaded_diameter = 2 * r / g.nodes.size();
  return out;
}

TriMesh perturb_start_positions(const TriMesh& mesh, const std::vector<char>& constrained, const PerturbationConfig& p) {
  TriMesh out = mesh;
  out.initial = mesh.start_positions();
  std::mt19937_64 generator(p.seed);
  for (int i = 0; i < out.num_nodes(); ++i)
    for (int c = 0; c < 3; ++c) {
      // 53 random bits to [0, 1), then [−1, 1): std::uniform_real_distribution's mapping is
      // left to the library, this one is not.
      const double u = 2 * static_cast<double>(generator() >> 11) * 0x1.0p-53 - 1;
      if (!constrained[3 * i + c]) out.initial(i, c) += p.amplitude * u;
    }
  return out;
}

SimulationResult simulate(const SceneConfig& sc, const TriMesh& unperturbed_mesh, MechanicalSystem& sys,
                          const SimulationHooks& hooks) {
  std::optional<TriMesh> perturbed;
  if (sc.perturbation) perturbed = perturb_start_positions(unperturbed_mesh, sys.constrained(), *sc.perturbation);
  const TriMesh& input_mesh = perturbed ? *perturbed : unperturbed_mesh;
  std::optional<RootDistension> root;
  TriMesh distended;
  if (sc.aortic_root) {
    VecX x;
    root = distend_root(sc, input_mesh, x);
    if (root->summary.status != SolverStatus::ok || !x.allFinite()) {
      SimulationResult res;
      res.x = flatten(input_mesh.start_positions());
      res.summary = root->summary;
      res.summary.status = root->summary.status == SolverStatus::ok ? SolverStatus::failed : root->summary.status;
      res.summary.reason = "aortic root distension: " + root->summary.reason;
      res.root = root;
      return res;
    }
    distended = input_mesh;
    distended.initial = unflatten(x);
  }
  const TriMesh& mesh = sc.aortic_root ? distended : input_mesh;
  sys.start_at(flatten(mesh.start_positions()));
  const auto monitor = resolve_monitor(sc, mesh);
  SimulationResult res;
  // A per-step convergence rule (the biaxial protocol) is a property of the dynamics.
  const bool wants_dynamics = sc.solver == SolverKind::bdf2 || (sc.solver == SolverKind::automatic && hooks.observer_for_increment);
  if (wants_dynamics) {
    res = run_bdf2(sc, mesh, sys, hooks, monitor);
  } else if (sc.solver == SolverKind::quasistatic) {
    res = run_quasistatic(sc, mesh, sys, hooks, monitor);
  } else {
    res = run_static(sc, mesh, sys, hooks);
    if (sc.solver == SolverKind::automatic && (res.summary.status != SolverStatus::ok || !res.x.allFinite())) {
      const std::string why = res.summary.reason;
      const SolverSummary first = res.summary;
      res = run_bdf2(sc, mesh, sys, hooks, monitor);
      res.summary.fallback_from = "static (" + why + ")";
      res.summary.wall_seconds += first.wall_seconds;
    }
  }
  if (!res.x.allFinite()) {
    res.summary.status = SolverStatus::failed;
    res.summary.reason = "non-finite positions";
  }
  res.root = root;
  return res;
}

}  // namespace valve
