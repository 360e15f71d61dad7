#include "valve/scene/simulation.hpp"

#include <cmath>

#include "valve/core/error.hpp"
#include "valve/analysis/leaflet_metrics.hpp"
#include "valve/mechanics/damping.hpp"
#include "valve/mechanics/mass_spring.hpp"
#include "valve/mechanics/membrane_fe.hpp"
#include "valve/mechanics/nodal_load.hpp"
#include "valve/mechanics/pressure.hpp"
#include "valve/solver/bdf2.hpp"
#include "valve/solver/static_solver.hpp"

namespace valve {

std::unique_ptr<MechanicalSystem> build_system(const SceneConfig& sc, const TriMesh& mesh) {
  const std::string where = sc.file.string();
  TriMesh m = mesh;
  if (!sc.fixed.use_node_roles) m.roles.assign(m.num_nodes(), NodeRole::free);
  auto sys = std::make_unique<MechanicalSystem>(m, sc.density, sc.thickness);
  for (int i : sc.fixed.nodes) {
    if (i < 0 || i >= m.num_nodes())
      throw_input_error(where, "fixed.nodes", "node indices in [0, " + std::to_string(m.num_nodes() - 1) + "]", std::to_string(i));
    sys->fix_node(i);
  }
  if (sc.fixed.planar)
    for (int i = 0; i < m.num_nodes(); ++i) sys->constrained()[3 * i + 2] = 1;
  if (sc.fixed.pin_centre) {
    const Vec3 c = m.points.colwise().mean();
    int centre = 0;
    double best = 1e300;
    for (int i = 0; i < m.num_nodes(); ++i) {
      const double d = (m.points.row(i).transpose() - c).norm();
      if (d < best) best = d, centre = i;
    }
    sys->constrained()[3 * centre] = sys->constrained()[3 * centre + 1] = 1;
  }
  // Model only what the scene requires: each block below exists only if declared.
  if (sc.model == ModelKind::mass_spring)
    sys->add_term(std::make_unique<MassSpringTerm>(m, sc.material.bilinear(), sc.thickness));
  else
    sys->add_term(std::make_unique<MembraneFETerm>(m, sc.material.law(), sc.thickness));
  if (sc.pressure) sys->add_term(std::make_unique<PressureTerm>(m, sc.pressure->value, sc.pressure->along_normal));
  if (sc.edge_loads)
    sys->add_term(std::make_unique<NodalLoadTerm>(
        biaxial_edge_forces(m, sc.edge_loads->stress_x, sc.edge_loads->stress_y, sc.thickness)));
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

std::vector<int> resolve_monitor(const SceneConfig& sc, const TriMesh& m) {
  switch (sc.monitor.kind) {
    case MonitorConfig::Kind::all: return {};
    case MonitorConfig::Kind::node:
      if (sc.monitor.node >= m.num_nodes())
        throw_input_error(sc.file.string(), "monitor", "a node index below " + std::to_string(m.num_nodes()), std::to_string(sc.monitor.node));
      return {sc.monitor.node};
    case MonitorConfig::Kind::nearest_point: {
      int best = 0;
      double bd = 1e300;
      for (int i = 0; i < m.num_nodes(); ++i) {
        const double d = (m.points.row(i).transpose() - sc.monitor.point).norm();
        if (d < bd) bd = d, best = i;
      }
      return {best};
    }
    case MonitorConfig::Kind::free_edge_middle: {
      const int n = free_edge_middle_node(m, 0);
      if (n < 0) throw_input_error(sc.file.string(), "monitor", "a mesh with free-edge nodes (BoundaryType 2)", "none");
      return {n};
    }
  }
  return {};
}

namespace {

SimulationResult run_bdf2(const SceneConfig& sc, const TriMesh& mesh, MechanicalSystem& sys, const SimulationHooks& hooks,
                          const std::vector<int>& monitor) {
  SimulationResult res;
  Bdf2Options opt = sc.bdf2;
  opt.monitor_nodes = monitor;
  Bdf2Integrator integ(sys, opt);
  integ.reset(flatten(mesh.points));
  if (hooks.on_step) integ.on_accepted = hooks.on_step;
  for (size_t k = 0; k < sc.load_increments.size(); ++k) {
    const double load = sc.load_increments[k];
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

SimulationResult run_static(const SceneConfig& sc, const TriMesh& mesh, MechanicalSystem& sys, const SimulationHooks& hooks) {
  SimulationResult res;
  res.x = flatten(mesh.points);
  double previous = 0;
  for (size_t k = 0; k < sc.load_increments.size(); ++k) {
    const double load = sc.load_increments[k];
    IncrementResult inc{load, solve_static(sys, res.x, sc.statics, load, previous)};
    previous = load;
    if (k == 0)
      res.summary = inc.summary;
    else
      res.summary.accumulate(inc.summary);
    res.increments.push_back(inc);
    if (hooks.on_increment) hooks.on_increment(static_cast<int>(k), res.x, inc);
    if (inc.summary.status != SolverStatus::ok) break;
  }
  res.summary.solver = "static";
  return res;
}

}  // namespace

SimulationResult simulate(const SceneConfig& sc, const TriMesh& mesh, MechanicalSystem& sys, const SimulationHooks& hooks) {
  const auto monitor = resolve_monitor(sc, mesh);
  SimulationResult res;
  // A per-step convergence rule (the biaxial protocol) is a property of the dynamics.
  const bool wants_dynamics = sc.solver == SolverKind::bdf2 || (sc.solver == SolverKind::automatic && hooks.observer_for_increment);
  if (wants_dynamics) {
    res = run_bdf2(sc, mesh, sys, hooks, monitor);
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
  return res;
}

}  // namespace valve
