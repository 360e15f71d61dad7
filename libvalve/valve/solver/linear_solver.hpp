#pragma once
// Linear solvers behind one interface: CHOLMOD supernodal Cholesky and simplicial LDLᵀ,
// UMFPACK and KLU sparse LU (SuiteSparse), simplicial LDLᵀ, preconditioned conjugate
// gradients, BiCGStab and sparse LU (Eigen), and BiCGStab or GMRES preconditioned by a
// factorization of the system's symmetric part (ldlt_bicgstab, llt_gmres, ...).
// The symbolic analysis is done once per pattern; factorize() is called per matrix.
#include <memory>
#include <string>
#include <vector>

#include "valve/mechanics/jacobian.hpp"

namespace valve {

enum class LinearSolverType {
  automatic, cholmod_llt, cholmod_ldlt, ldlt, umfpack, klu, cg, bicgstab, lu,
  // The whole system by a Krylov method on a factorization of its symmetric part.
  ldlt_bicgstab, llt_bicgstab, cholmod_bicgstab, ldlt_gmres, llt_gmres, cholmod_gmres
};

/// The names parse_linear_solver() accepts, as scene files spell them.
const std::vector<std::string>& linear_solver_names();

/// "automatic" by size. For BDF2 (SystemSymmetry::symmetrized: a symmetric approximation is
/// acceptable) `ldlt_bicgstab` below `kLargeSystemDofs` unknowns: BiCGStab on the whole
/// system, preconditioned by Eigen's simplicial LDLᵀ of its symmetric part, started from that
/// factorization's solution. The whole system matters: follower pressure has an antisymmetric
/// stiffness, and with only the symmetric part in the matrix the sample mitral closure let a
/// folded free-edge node orbit at steps of 5-25 ms (predictor estimate, tolerance 0.03-0.1 mm:
/// 0.04-0.08 mm per step for 90 s simulated, never settling); with the whole system it settles
/// at every tolerance measured. Cost there: 3.3 ms per factorization and 3.2 BiCGStab iterations
/// per solve on average (iterative_tolerance 1e-10), against 2.7 ms for the symmetric part alone and 5.7 ms (UMFPACK) or
/// 7.9 ms (KLU) for an LU of the whole system. Above `kLargeSystemDofs`, CHOLMOD supernodal
/// Cholesky of the symmetric part: on the sample mitral contact system (1,140 unknowns, 90k
/// entries in L) one factorization takes 3.3 ms (Eigen LDLᵀ), 6.2 ms (CHOLMOD simplicial
/// LDLᵀ, which converts and copies on every call) and 6.6 ms (CHOLMOD supernodal); on a
/// 10,113-triangle mitral membrane a BDF2 step took 0.9 s with CHOLMOD supernodal against
/// 1.5 s with CHOLMOD simplicial. For non-symmetric systems
/// (static Newton), KLU below `kLargeSystemDofs` (least overhead on a few hundred unknowns)
/// and UMFPACK above (multifrontal with BLAS: 4x faster than KLU at 30,000 unknowns; one
/// factorization of a 20,000-triangle leaflet takes 0.72 s with KLU, 0.18 s with UMFPACK).
constexpr int kLargeSystemDofs = 6000;

LinearSolverType parse_linear_solver(const std::string& name);  // throws InputError
std::string to_string(LinearSolverType t);

struct LinearSolverStats {
  long factorizations = 0;  // numeric factorizations (or preconditioner builds)
  long solves = 0;
  long iterations = 0;      // Krylov iterations: GMRES steps (one preconditioner solve each), BiCGStab iterations (two)
  long failures = 0;        // factorizations or solves that failed
  double factor_seconds = 0, solve_seconds = 0;
  /// Adds another solver's counts (a run whose phases or load steps each had a solver).
  LinearSolverStats& operator+=(const LinearSolverStats& o) {
    factorizations += o.factorizations, solves += o.solves, iterations += o.iterations, failures += o.failures;
    factor_seconds += o.factor_seconds, solve_seconds += o.solve_seconds;
    return *this;
  }
};

class LinearSolver {
 public:
  virtual ~LinearSolver() = default;
  /// Cholesky and CG need a symmetric matrix; callers pass the symmetric part.
  virtual bool needs_symmetric() const = 0;
  /// Factorizes A (analysing the pattern on first use). False if A is singular or, for
  /// Cholesky, not positive definite.
  virtual bool factorize(const SparseMatrix& A) = 0;
  /// Solves A x = b with the last factorized A; false on failure.
  virtual bool solve(const VecX& b, VecX& x) = 0;
  /// Krylov solvers on a factorization (ldlt_bicgstab, cholmod_gmres, ...): factorizes the
  /// symmetric part of `preconditioner` and solves with A; others return false. Newton then
  /// takes an indefinite A (a Cholesky cannot factorize it) on a definite preconditioner.
  virtual bool factorize_preconditioned(const SparseMatrix& A, const SparseMatrix& preconditioner) {
    (void)A, (void)preconditioner;
    return false;
  }
  /// Whether factorize_preconditioned is supported.
  virtual bool takes_preconditioner() const { return false; }
  /// After factorize_preconditioned: solves with A from now on, on the same factorization.
  virtual bool set_operator(const SparseMatrix& A) {
    (void)A;
    return false;
  }
  /// The iterative solvers' relative residual for the next solves; direct solvers ignore it.
  virtual void set_tolerance(double) {}
  const LinearSolverStats& stats() const { return stats_; }
  virtual std::string name() const = 0;

 protected:
  LinearSolverStats stats_;
};

/// Keeps OpenBLAS (behind CHOLMOD supernodal and UMFPACK) to one thread, its load-time workers
/// stopped, unless the user set OPENBLAS_NUM_THREADS, and CHOLMOD's OpenMP regions to the calling thread unless the user
/// set OMP_MAX_ACTIVE_LEVELS. Why: our systems are small (10^3-10^4
/// unknowns) and factorized thousands of times; on the 2-core machine an unpinned mitral
/// contact closure spent 21 s of a 90 s run in the kernel (BLAS threads spinning and waking),
/// and CHOLMOD's fixed 4-thread regions cost the x16 mitral BDF2 closure 49.5 s against 29.2 s
/// (factorizations 27.3 s against 9.2 s, the same result bit for bit). Call it first thing in
/// a stage.
void limit_blas_threads_unless_set();

enum class SystemSymmetry { general, symmetrized };

/// `tolerance` and `max_iterations` apply to the iterative solvers only; `dofs` and
/// `symmetry` resolve LinearSolverType::automatic.
std::unique_ptr<LinearSolver> make_linear_solver(LinearSolverType type, double tolerance = 1e-10,
                                                 int max_iterations = 2000, int dofs = 0,
                                                 SystemSymmetry symmetry = SystemSymmetry::general);

}  // namespace valve
