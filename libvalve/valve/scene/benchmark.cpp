#include "valve/scene/benchmark.hpp"

#include <algorithm>
#include <cmath>
#include <chrono>

#include "valve/core/error.hpp"
#include "valve/mechanics/broad_phase.hpp"
#include "valve/mechanics/mass_spring.hpp"
#include "valve/mechanics/membrane_fe.hpp"
#include "valve/mechanics/penalty_contact.hpp"
#include "valve/mesh/subdivide.hpp"
#include "valve/scene/simulation.hpp"
#include "valve/solver/constrained_system.hpp"
#include "valve/solver/linear_solver.hpp"

namespace valve {
namespace {
double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0 : v[v.size() / 2];
}
double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}
}  // namespace

TermCost measure_term_cost(const SceneConfig& sc, const TriMesh& mesh, ModelKind model, const VecX& x, int reps) {
  std::unique_ptr<ForceTerm> term;
  if (model == ModelKind::mass_spring)
    term = std::make_unique<MassSpringTerm>(mesh, sc.material.bilinear(), sc.thickness);
  else
    term = std::make_unique<MembraneFETerm>(mesh, sc.material.law(), sc.thickness);
  std::vector<std::pair<int, int>> pairs;
  term->couplings(pairs);
  BlockJacobian J(mesh.num_nodes(), pairs);
  const VecX v = VecX::Zero(x.size());
  VecX f(x.size());
  const State s{x, v, 1.0, 0.0};
  // Each sample repeats the evaluation enough times to last ~1 ms, beyond timer resolution.
  const int inner = std::max(1, 200000 / std::max(1, mesh.num_triangles()));
  std::vector<double> t_force, t_jac;
  for (int r = 0; r < reps; ++r) {
    auto t0 = std::chrono::steady_clock::now();
    for (int k = 0; k < inner; ++k) {
      f.setZero();
      term->add(s, f, nullptr, nullptr);
    }
    t_force.push_back(seconds_since(t0) / inner);
    t0 = std::chrono::steady_clock::now();
    for (int k = 0; k < inner; ++k) {
      f.setZero();
      J.set_zero();
      term->add(s, f, &J, nullptr);
    }
    t_jac.push_back(seconds_since(t0) / inner);
  }
  TermCost c;
  c.term = term->name();
  c.elements = mesh.num_triangles();
  c.force_ns_per_element = 1e9 * median(t_force) / c.elements;
  c.force_and_jacobian_ns_per_element = 1e9 * median(t_jac) / c.elements;
  return c;
}

ClosureCost measure_closure(const SceneConfig& scene, const SceneModel& scene_model, ModelKind model, int reps) {
  SceneConfig sc = scene;
  sc.model = model;
  auto sys = build_system(sc, scene_model);
  ClosureCost out;
  const auto t0 = std::chrono::steady_clock::now();
  const SimulationResult res = simulate(sc, scene_model.mesh, *sys);
  out.solve_seconds = seconds_since(t0);
  out.solver = res.summary.to_json();
  out.x = scene_model.leaflet_state(res.x);
  // One factorization of the same system: the static tangent at the solution, with the
  // solver the run used.
  VecX f;
  const VecX v = VecX::Zero(res.x.size());
  sys->evaluate(State{res.x, v, 1.0, 0.0}, f, true, false);
  const SparseMatrix tangent = -sys->dfdx().matrix();
  // The linear solver the run used, by the name its summary gives: the first, where a
  // quasi-static run handed over to another after a failed increment ("llt_gmres, then ldlt_gmres").
  const std::string used = res.summary.linear_solver;
  const LinearSolverType type = parse_linear_solver(used.substr(0, used.find(',')));
  auto solver = make_linear_solver(type, 1e-10, 2000, sys->num_dofs());
  // The tangent at a closed valve need not be positive definite (compressed membrane, the
  // pressure's stiffness): a Cholesky refuses it at its first non-positive pivot, for a fraction
  // of a whole factorization's cost (0.3 ms against 1.8 ms on the aortic valve FE tangent). So
  // the diagonal is raised by s times its largest entry, s = 0, 1e-4, 1e-2, ..., 1e4, until the
  // run's solver takes it: the pattern, and so the cost of a whole factorization, stays.
  const double largest_diagonal = tangent.diagonal().cwiseAbs().maxCoeff();
  SparseMatrix A;
  for (int k = 0; k <= 5 && out.one_factorization_shift < 0; ++k) {
    const double shift = k == 0 ? 0.0 : std::pow(10.0, 2 * k - 6);
    A = tangent;
    for (int i = 0; i < A.cols(); ++i)
      A.coeffRef(i, i) += 1e-6 * std::max(1.0, std::abs(A.coeff(i, i))) + shift * largest_diagonal;
    VecX b = f;
    apply_constraints(A, b, sys->constrained());
    if (solver->needs_symmetric()) A = symmetric_part(A);
    if (solver->factorize(A)) out.one_factorization_shift = shift;  // the symbolic analysis once, as in a run
  }
  std::vector<double> t;
  for (int r = 0; r < reps && out.one_factorization_shift >= 0; ++r) {
    const auto t1 = std::chrono::steady_clock::now();
    solver->factorize(A);
    t.push_back(seconds_since(t1));
  }
  out.one_factorization_seconds = median(t);
  out.ratio_to_factorization = out.one_factorization_seconds > 0 ? out.solve_seconds / out.one_factorization_seconds : 0;
  return out;
}

std::vector<BroadPhaseCost> measure_broad_phase(const SceneConfig& sc, const TriMesh& mesh, int reps) {
  const PenaltyContactOptions opt = sc.penalty_contact.value_or(PenaltyContactOptions{});
  std::vector<BroadPhaseCost> out;
  TriMesh level = mesh;
  for (int refinement = 0; refinement < 3; ++refinement) {
    if (refinement > 0) level = subdivide_midpoint(level);
    const VecX x = flatten(level.points);
    // The margin the contact term would use on this mesh (its detection distance D).
    const double margin =
        PenaltyContactTerm(level, opt, std::vector<char>(3 * level.num_nodes(), 0)).detection_distance();
    std::vector<std::pair<int, int>> reference;
    for (BroadPhaseMethod method :
         {BroadPhaseMethod::sweep_and_prune, BroadPhaseMethod::spatial_hash, BroadPhaseMethod::bvh}) {
      std::vector<double> times;
      std::vector<std::pair<int, int>> pairs;
      for (int r = 0; r < reps; ++r) {
        const auto t0 = std::chrono::steady_clock::now();
        pairs = broad_phase_pairs(x, level.triangles, margin, method);
        times.push_back(seconds_since(t0));
      }
      if (method == BroadPhaseMethod::sweep_and_prune) reference = pairs;
      else if (pairs != reference)
        throw Error("broad phase: " + to_string(method) + " and sweep_and_prune disagree on " + std::to_string(level.num_triangles()) +
                    " triangles (" + std::to_string(pairs.size()) + " vs " + std::to_string(reference.size()) + " pairs)");
      out.push_back({to_string(method), level.num_triangles(), margin, median(times), static_cast<long>(pairs.size())});
    }
  }
  return out;
}

}  // namespace valve
