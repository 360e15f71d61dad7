#pragma once
// Static equilibrium by Newton's method on an incremental potential: the closed valve as the
// equilibrium it is, not as the end of a trajectory (no time-step error to resolve).
//
// Each iteration k at the state x_k minimises, along one Newton direction, the merit
//     Φ_k(y) = Π(y) − f_ext(x_k)·(y − x_k) + (y − x_k)ᵀ M (y − x_k) / (2δ),
// where Π is the stored energy of every material and constraint term (membrane, springs,
// bending, chordae, contact barrier: MechanicalSystem::internal_energy), f_ext the applied
// loads and M the lumped mass. Terms:
// * Follower pressure: its force is frozen at x_k, so within an iteration it is a dead load
//   with the potential −f_ext(x_k)·(y − x_k); the next iteration takes it at the new state.
//   ∇Φ_k(x_k) = −f(x_k), the true residual, so a fixed point is the follower equilibrium.
//   (An open sheet under a follower pressure has no potential of its own: the pressure's
//   work depends on the path once the free edge moves.)
// * The proximal (inertia) term M/δ regularises: it makes the Newton matrix
//   H = −∂f/∂x + M/δ positive definite where the membrane is slack or compressed and
//   shortens steps far from equilibrium. A direction that does not descend on Φ_k is taken
//   again at the same δ without the applied loads' stiffness (Φ_k's own Hessian); δ shrinks
//   ×4 when that fails too, or the solve or the line search fails; how it grows is
//   ProximalStepRule's. Near equilibrium the iteration is Newton's (δ → ∞).
// * Contact Hessians: projected to positive semi-definite until δ ≥ 1e4 ms² and the load
//   increment's relative residual has come within 0.1, exact from there on, so that the last
//   iterations converge quadratically (the projection's error made them linear: 200
//   iterations from 1e-2 to 1e-6 on the sample mitral closure). A direction
//   that fails with the exact ones (it does not descend on Φ_k: their negative part, b′∇²d of
//   pairs closest at an edge or a vertex, outweighs the rest along f; or GMRES does not
//   converge on it) is solved again with
//   their departure from the projected ones halved, P + (E − P)/2, then quartered, down to
//   1/64, and only then with projected ones, all on the same factorisation at the same δ
//   (ExactHessianSchedule: when exact ones come back). A share of the exact curvature keeps
//   the iteration closer to Newton's than the projection does. Measured against the projected
//   retry alone, with exact Hessians from δ = 1e4 on whatever the residual: the normal-valve
//   study's 100 taut-root closures 7,341 factorisations against 8,395 (2 against 7 over 150),
//   its 70 slack-root ones 26,283 against 26,209; the ×16
//   mitral closure from six starts 1e-6 mm apart 78-119 against 79-159; the sample mitral
//   closure from eleven 72-111 against 72-138 (median 96 both); the aortic valve M-S closure
//   from eleven 55-62 against 54-73, FE 54 against 72 from every start; the Texas TriValve
//   deck 912 against 901, but 7,019 GMRES steps against 9,550 and 260 s against 280 s. Every
//   closure ends on the same equilibrium (1e-7 mm apart on the small ones, mean over nodes;
//   ×16 0.014 mm, the deck 0.003 mm).
// * Line search: from the largest step the limits allow (a trust radius on node moves, and
//   every term's step_ratio: the contact barrier's conservative collision bounds, so that no
//   iterate ever intersects), halved until Φ_k falls by the Armijo fraction, or failing that
//   the residual |f| does: near equilibrium Φ_k (the pressure frozen) need not fall along
//   Newton's direction for f = 0, whose matrix holds the pressure's non-symmetric stiffness.
//   Every accepted step lowers Φ_k or |f|; neither merit is ever allowed to rise on its own
//   test, and the contact energy is finite at every iterate. Since Φ_k changes with k, two
//   iterates can each lower the other's merit; a step back to any of the last eight iterates
//   is refused, and the search goes on halving it (RecentIterates).
// Load continuation: the load factor steps to the target, halving the increment when an
// increment fails to converge within its budget of iterations (IncrementBudget).
// Linear algebra: the whole system (with the pressure's non-symmetric stiffness: the last
// iterations are then Newton's on f = 0, and far from equilibrium, where leaflets swing
// through large rotations, the symmetric part alone gave directions that did not converge on
// the aortic valve) by GMRES preconditioned with a Cholesky of its symmetric part, one per
// direction: Eigen's simplicial LLᵀ below 6,000 unknowns, CHOLMOD's supernodal one above.
// * With the contact Hessians projected. Exact ones may make the matrix indefinite, so they
//   enter as GMRES's operator only, on the projected Jacobian's Cholesky; where that
//   direction fails, the scaled ones and then the projected one are solved on the same
//   factorisation (no second factorisation for the retries).
//   The cost, measured with the projected retry alone: on the ×16 mitral closure an exact
//   direction took 45 GMRES steps (mean over 36), a projected one 9 (the pressure's skew part
//   alone), and on the Texas TriValve deck 85 against 5; those steps are most of the GMRES
//   time. Why this preconditioner all the same (each measured on the ×16 closure with the
//   projected retry alone, 79 factorisations and 36 s):
//   - the pair Hessians' eigenvalues made absolute instead of clamped: 169 steps (A − P is
//     twice the negative part instead of once);
//   - negative eigenvalues scaled by 0.8 instead of clamped: 38 steps, with 19 refused
//     factorisations more;
//   - the exact matrix's own Cholesky where it is positive definite: 9 steps there, but it is
//     on 12 of the 36 exact directions and on none of the deck's 77; adding (4^k − 1) M (its
//     δ divided by 4^k) makes it so on the same 12 at k = 1 and on no other even at k = 7:
//     the exact pair Hessians' negative part (b′ ∇²d; ∇²d = (I − nnᵀ)/d for a pair closest at a
//     vertex) is far larger than any M/δ the iteration could afford;
//   - Eigen's LDLᵀ of the exact matrix (indefinite allowed): 10 steps, but its simplicial
//     factorisations of 16,000 unknowns take 41 s over the closure (beside a second job;
//     CHOLMOD's Cholesky factorisations 7 s alone);
//   - exact Hessians only below a relative residual of 1e-2 or 1e-3: 139 and 341
//     factorisations (projected directions converge linearly near equilibrium);
//   - at most 40 GMRES steps on an exact direction, then the projected one: 168 directions,
//     48 s.
//   - Krylov subspace recycling from one direction to the next (GCRO-DR, each solve's slowest
//     harmonic Ritz vectors carried on as solution-space directions, 20 or 30 kept): 7,378
//     steps on 83 directions against 1,995 on 81, some solves stalling at the 2,000-step cap.
//     The exact Hessians' negative part spans more directions than a recycled space holds (on
//     a synthetic sequence of systems with eight slow eigenvalues the same code took 10 steps
//     where plain GMRES took 177);
//   - a restart of 100 instead of 30: another path, 278 directions.
// * A Cholesky refuses a symmetric part that is not positive definite, and δ then shrinks: the
//   proximal term regularises there. On the sample mitral closure (mass-spring) 14 of its 16
//   refusals come from springs in compression (their transverse stiffness F/l < 0), 2 from the
//   pressure's stiffness: factorised without the latter, 14 are refused still. Dropping the
//   compressed springs' F/l refuses none but lengthens the path (measured with the projected
//   retry alone): 111 directions with it dropped from every matrix (the last ones linear,
//   stopping at 9e-7), 255 with it dropped from the projected directions' matrices only,
//   against 71. The membrane FE tangent so projected on the Texas TriValve deck (its material
//   tangent's and its stress's eigenvalues clamped at 0) stops the refusals there, where δ stays
//   at 0.01-0.16 for about 300 directions, but the path does not shorten: δ reaches 1e4 by the
//   88th direction, where the exact directions then take about 1,000 GMRES steps each (stopped
//   after 134 directions); with exact contact Hessians kept out until the residual is within
//   1e-2 the residual wanders between 0.01 and 2 for 300 directions at δ's ceiling (stopped at
//   434 directions, 210 s; the default converges in 624, 248 s). Refusal keeps
//   Newton's path continuous in its start: over eleven starts 1e-6 mm apart the aortic valve FE
//   closure spreads 9e-10 mm (median, mean over nodes), against 0.007 mm with an LDLᵀ, which
//   factorises the indefinite matrix and lets δ grow past it; at a fixed 2.5 mm contact detection
//   (the mitral scene's cap) the ×16 mitral closure takes 128 factorisations, against 407 with the symmetric
//   part's Cholesky alone as the direction.
// Symbolic analyses are kept while the pattern holds. A direction that does not descend
// (∇Φ·Δ >= 0) counts as a failed factorisation.
// Ends when |f_free| <= relative_residual_tolerance · |f_ext,free|.
#include <algorithm>
#include <vector>

#include "valve/mechanics/mechanical_system.hpp"
#include "valve/solver/linear_solver.hpp"
#include "valve/solver/solver_summary.hpp"

namespace valve {

/// How the proximal step δ grows after an accepted step.
/// step: ×4 after a whole step taken at once, ×2 when the collision bound shortened it, no
///   change when the trust radius did (the model is not trusted that far yet), ×0.5 when the
///   line search cut twice.
/// gain: by the gain ratio of trust-region methods, the merit's fall over the quadratic
///   model's, (Φ_k(x_k) − Φ_k(x_k + αΔ)) / (α f·Δ (1 − α/2)): ×4 (×2 when a step bound
///   shortened the step) after a step taken at once with a gain above 3/4, ×0.5 below 1/4.
/// `step` converges on every closure measured (docs/results/quasistatic-solver.md): the remeshed
/// Texas TriValve in 299 directions, as `gain` does; `gain` stalled on two of ten aortic
/// starts with descending fibers in the slack root (with the supporting-plane collision bound
/// alone).
/// Either rule may grow δ back to where the Cholesky last refused: on the slack aortic root a
/// closure often alternates, a whole step at δ, a refusal at 4δ, so that about half its
/// factorisations are refused ones (196 of 433 in one closure; they stop at the first
/// non-positive pivot and cost less than a whole one). Holding δ below half the refused value
/// for the next eight accepted steps takes 29 % fewer factorisations over the normal-valve
/// study's 70 slack-root closures, 6 % fewer over its 100 taut ones, but 86 against 72 on the
/// aortic valve FE closure (medians of eleven starts; 1.24 s against 1.00 s in the solver; all
/// measured with the projected retry alone), so δ is not held.
enum class ProximalStepRule { step, gain };

/// Largest proximal step δ (ms²): from there on the M/δ term is nothing and δ stops growing.
constexpr double kMaxProximalStep = 1e14;

/// The relative residual a load increment must first come within before exact contact
/// Hessians enter (ExactHessianSchedule). Why: δ can reach 1e4 while the leaflets are still
/// settling into contact (the ×16 mitral closure at a relative residual of 0.44), and there the
/// exact Hessians' negative part (pairs closest at an edge or a vertex, a set that still changes
/// from one iterate to the next) gives directions that do not descend and GMRES solves of
/// 40-170 steps. Measured from the ×16 closure's mesh and five starts moved by 1e-6 mm: 77-105
/// factorisations (median 92), 1,072-2,680 GMRES steps, 27-41 s (median 32 s), against 78-119
/// (median 106), 1,850-4,376 and 31-52 s (median 45 s) with δ alone deciding (the mesh's two
/// closures 0.014 mm apart); the aortic valve closures from their mesh and ten perturbed starts,
/// the sample mitral closure and the Texas TriValve deck take the same paths, while 120 of the
/// graft study's 180 closures take others, among neighbouring equilibria where a size sits at a
/// fork (docs/results/quasistatic-solver.md). Once within the bound they stay, although the residual
/// may rise again across a kink: switching back to projected Hessians whenever it exceeds the
/// bound made the aortic valve M-S closure take 69 factorisations from each of ten perturbed
/// starts instead of 55-62.
constexpr double kExactHessianResidual = 0.1;

/// When the contact Hessians enter exact rather than projected to positive semi-definite:
/// from δ = 1e4 ms² on (the M/δ term is then too weak to matter and the iteration is Newton's,
/// which the projection's error would make linear), once the load increment's relative residual
/// has come within kExactHessianResidual, and after a direction failed with them, once δ has
/// grown fourfold past where it failed. That threshold stops at the largest δ, where δ itself
/// stops: past it exact Hessians would never come back, and the aortic valve FE closure ended in
/// 150 linear iterations (1e-3 to 1e-6 relative residual) with projected ones.
class ExactHessianSchedule {
 public:
  /// A load increment starts: its residual has not yet come near equilibrium.
  void start_increment() { near_equilibrium_ = false; }
  /// The relative residual of the iterate a direction starts from.
  void record_residual(double relative_residual) {
    if (relative_residual <= kExactHessianResidual) near_equilibrium_ = true;
  }
  bool exact_at(double delta) const { return near_equilibrium_ && delta >= from_; }
  void failed_at(double delta) { from_ = std::min(4 * delta, kMaxProximalStep); }

 private:
  double from_ = 1e4;
  bool near_equilibrium_ = false;
};

/// How accurately each Newton direction is solved (iterative linear solvers only).
/// fixed (default): to `iterative_tolerance` every time.
/// adaptive: inexact Newton with Eisenstat and Walker's forcing term (choice 2, SIAM J. Sci.
///   Comput. 17, 1996): η_k = 0.9 (r_k / r_{k−1})², kept above 0.5 τ / r_k (no solve tighter
///   than the residual target τ needs) and within [iterative_tolerance, 0.01] (never tighter
///   than `fixed`; their safeguard against sudden tightening, η_k >= 0.9 η_{k−1}² once that
///   exceeds 0.1, never acts under this ceiling). Far from equilibrium a direction solved to
///   1e-6 is wasted work; while the residual falls fast η_k falls with it, so Newton's
///   convergence stays superlinear, and the last directions are solved just well enough to
///   reach τ.
///   After a step that did not lower the residual the next direction is solved to the floor
///   (ForcingTerm::next).
///   Measured (docs/results/quasistatic-solver.md): 40 graft closures of the aortic valve
///   26.0 s against 26.1 s fixed at 1e-6 (2 jobs); six perturbed sample mitral closures took
///   72-104 factorizations against 90-111 fixed (the Newton path, not the solves, sets these);
///   the ×16 mitral closure (with the projected retry alone) 210 directions, 152
///   factorizations and 50 s against 81, 79 and 33 s (a cycle of loosely solved directions
///   near equilibrium).
///   Why it is not the default: the saving is small with GMRES's directions, and a direction
///   solved to 1e-2 differs from the exact one by that much, so the path is another than exact
///   Newton's: the normal aortic valve's forty perturbed starts land on neighbouring
///   equilibria (band heights spread by up to 0.11 mm, against 1.2e-7 mm fixed); with
///   BiCGStab's directions, where the solve stops being a discrete decision, 9 of the 40 moved
///   by more than the 0.05 mm (mean over nodes) the solver is held to, against none fixed
///   (measured with the projected retry alone).
enum class NewtonForcing { adaptive, fixed };

/// The forcing sequence η_k of NewtonForcing::adaptive for one load increment.
class ForcingTerm {
 public:
  ForcingTerm(double floor, double target) : floor_(floor), target_(target) {}
  /// η for the direction at relative residual r (the increment's first: the ceiling).
  double next(double r) {
    double eta = kCeiling;
    if (previous_r_ > 0) {
      const double ratio = r / previous_r_;
      // A step that did not lower the residual: the next direction is solved as `fixed` solves
      // it. Choice 2 would loosen it to the ceiling, and a direction 1e-2 off can push into a
      // contact whose collision bound then cuts every step to nothing.
      if (!(ratio < 1)) {
        previous_r_ = r;
        return floor_;
      }
      eta = 0.9 * ratio * ratio;
    }
    eta = std::max(eta, 0.5 * target_ / std::max(r, 1e-300));
    previous_r_ = r;
    return std::clamp(eta, floor_, std::max(floor_, kCeiling));
  }

 private:
  static constexpr double kCeiling = 0.01;
  double floor_, target_;
  double previous_r_ = -1;
};

/// How many Newton directions one load increment may take: `max_iterations`, and as many again
/// each time that limit is reached while the residual is still falling: the lowest relative
/// residual over the last quarter of the increment's iterations below half the lowest before
/// them. An increment that only wanders (a closure stalled against a contact, δ cycling) fails
/// at the limit, and load continuation takes a smaller one; one that is still closing goes on.
/// Why: on the Texas TriValve deck the leaflets travel 8 mm per node at steps of at most 0.5 mm,
/// and the pressure's one increment converges after about 660 directions (every chord point a
/// node); at 400 its residual is
/// near 0.8 of the load and still falling (0.28 at best over the last 100 directions, 0.92
/// before them), and a fixed limit there sends continuation back to the open valve at half the
/// load (measured: no convergence in 600 s).
/// Each extension needs a residual half as low as any before, so there are at most
/// log2(first residual / tolerance) of them.
class IncrementBudget {
 public:
  explicit IncrementBudget(int per_round) : limit_(per_round), per_round_(per_round) {}
  /// The relative residual at the start of each iteration, in order.
  void record(double relative_residual) { residuals_.push_back(relative_residual); }
  /// Whether iteration `it` (0-based) may run.
  bool allows(int it) {
    if (it < limit_) return true;
    const size_t n = residuals_.size(), quarter = n / 4;
    if (quarter == 0) return false;
    const double recent = *std::min_element(residuals_.end() - static_cast<long>(quarter), residuals_.end());
    const double before = *std::min_element(residuals_.begin(), residuals_.end() - static_cast<long>(quarter));
    if (!(recent < 0.5 * before)) return false;
    limit_ += per_round_;
    return true;
  }

 private:
  int limit_, per_round_;
  std::vector<double> residuals_;
};

/// The last iterates a line search may not step back to. Newton on the contact barrier has kinks
/// (a pair's closest feature switches between face, edge and vertex), and across them it can
/// cycle: the ×16 mitral closure run with two BLAS threads (OPENBLAS_NUM_THREADS=2, rounding
/// alone differing) settled at δ's ceiling into a 4-cycle (relative residuals 9.4e-4, 9.2e-4,
/// 9.4e-4, 4.6e-4; full, full, half, full steps) until its increment's budget ran out: 624
/// directions and 590 factorizations (about five minutes), against 104 and 95 (40 s) refusing
/// returns to the last eight (the same closure with one thread: 77 directions either way).
/// Refusing a return to the previous iterate alone stops only 2-cycles.
class RecentIterates {
 public:
  static constexpr std::size_t kCount = 8;
  /// Whether y lies within `tolerance` (largest node move) of one of the last kCount iterates.
  bool returns_to(const VecX& y, double tolerance) const {
    return std::any_of(iterates_.begin(), iterates_.end(), [&](const VecX& earlier) {
      return earlier.size() == y.size() && largest_node_norm(y - earlier) <= tolerance;
    });
  }
  /// Records an iterate the solve leaves.
  void push(const VecX& x) {
    if (iterates_.size() < kCount) {
      iterates_.push_back(x);
    } else {
      iterates_[next_] = x;
    }
    next_ = (next_ + 1) % kCount;
  }

 private:
  std::vector<VecX> iterates_;
  std::size_t next_ = 0;
};

struct QuasistaticOptions {
  double relative_residual_tolerance = 1e-6;
  int max_iterations = 400;           // Newton iterations per load increment (IncrementBudget)
  double initial_proximal_step = 1e-2;  // δ0 in ms² (the M/δ term's "time step" squared)
  ProximalStepRule proximal_rule = ProximalStepRule::step;
  double trust_radius = 0;            // mm: largest node move per iteration; 0 = 5 % of the bounding-box diagonal
  double armijo = 1e-4;
  double initial_increment = 1.0;     // first Δλ as a fraction of the load to apply
  double min_increment = 1e-4;
  double max_wall_seconds = 600;
  LinearSolverType linear_solver = LinearSolverType::automatic;  // llt_gmres; above 6,000 unknowns cholmod_gmres
  double iterative_tolerance = 1e-6;  // the Krylov solve's relative residual (adaptive: its floor)
  NewtonForcing forcing = NewtonForcing::fixed;
};

/// Solves from x (updated in place) at load factors from `load_start` up to `load_target`.
/// Every term but the applied loads and damping needs an energy (else status failed).
SolverSummary solve_quasistatic(MechanicalSystem& system, VecX& x, const QuasistaticOptions& options,
                                double load_target = 1.0, double load_start = 0.0);

}  // namespace valve
