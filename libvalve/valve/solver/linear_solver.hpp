#pragma once
// Linear solvers behind one interface: CHOLMOD supernodal Cholesky and simplicial LDLᵀ,
// UMFPACK and KLU sparse LU (SuiteSparse), preconditioned conjugate gradients, BiCGStab and
// sparse LU (Eigen).
// The symbolic analysis is done once per pattern; factorize() is called per matrix.
#include <memory>
#include <string>

#include "valve/mechanics/jacobian.hpp"

namespace valve {

enum class LinearSolverType { automatic, cholmod_llt, cholmod_ldlt, umfpack, klu, cg, bicgstab, lu };

/// For non-symmetric systems, "automatic" picks KLU below `kLargeSystemDofs` unknowns (least
/// overhead on a few hundred unknowns) and UMFPACK above (multifrontal with BLAS: 4x faster
/// than KLU at 30,000 unknowns, tests/solver and valve-bench). Measured in this repository:
/// one factorization of a 20,000-triangle leaflet takes 0.72 s (KLU), 0.18 s (UMFPACK).
constexpr int kLargeSystemDofs = 6000;

LinearSolverType parse_linear_solver(const std::string& name);  // throws InputError
std::string to_string(LinearSolverType t);

struct LinearSolverStats {
  long factorizations = 0;  // numeric factorizations (or preconditioner builds)
  long solves = 0;
  long iterations = 0;      // Krylov iterations (iterative solvers)
  long failures = 0;        // factorizations or solves that failed
  double factor_seconds = 0, solve_seconds = 0;
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
  const LinearSolverStats& stats() const { return stats_; }
  virtual std::string name() const = 0;

 protected:
  LinearSolverStats stats_;
};

/// Keeps OpenBLAS (behind CHOLMOD supernodal and UMFPACK) to one thread unless the user set
/// OPENBLAS_NUM_THREADS. Why: our systems are small (10^3-10^4 unknowns) and factorized
/// thousands of times; on the 2-core machine an unpinned mitral contact closure spent 21 s
/// of a 90 s run in the kernel (threads spinning and waking). Call it first thing in a stage.
void limit_blas_threads_unless_set();

/// `tolerance` and `max_iterations` apply to the iterative solvers only; `dofs` resolves
/// LinearSolverType::automatic.
std::unique_ptr<LinearSolver> make_linear_solver(LinearSolverType type, double tolerance = 1e-10,
                                                 int max_iterations = 2000, int dofs = 0);

}  // namespace valve
