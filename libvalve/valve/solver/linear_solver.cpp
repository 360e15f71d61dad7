#include "valve/solver/linear_solver.hpp"

#include <Eigen/CholmodSupport>
#include <Eigen/IterativeLinearSolvers>
#include <Eigen/KLUSupport>
#include <Eigen/UmfPackSupport>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseLU>
#include <dlfcn.h>

#include <algorithm>
#include <cstdlib>
#include <chrono>
#include <vector>

#include "valve/core/error.hpp"
#include "valve/solver/constrained_system.hpp"
#include "valve/solver/gmres.hpp"
#include "valve/solver/node_block_ordering.hpp"

namespace valve {
namespace {

double since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// CHOLMOD prints "not positive definite" warnings itself; a failed factorization is
// already reported through info() and the stage's summary, so keep stderr to one line.
template <class D>
void silence(D&) {}
template <class M, int UpLo>
void silence(Eigen::CholmodSupernodalLLT<M, UpLo>& d) {
  d.cholmod().print = 0;
}
template <class M, int UpLo>
void silence(Eigen::CholmodSimplicialLDLT<M, UpLo>& d) {
  d.cholmod().print = 0;
}

using NodeBlockLdlt = Eigen::SimplicialLDLT<SparseMatrix, Eigen::Lower, NodeBlockAmdOrdering<SparseMatrix::StorageIndex>>;
using NodeBlockLlt = Eigen::SimplicialLLT<SparseMatrix, Eigen::Lower, NodeBlockAmdOrdering<SparseMatrix::StorageIndex>>;
using CholmodLlt = Eigen::CholmodSupernodalLLT<SparseMatrix>;

// The pattern a decomposition was last analysed for. Contact grows the Jacobian pattern
// during a solve, so the symbolic analysis is redone only when the pattern changes.
class AnalysedPattern {
 public:
  template <class Decomposition>
  void factorize(Decomposition& dec, const SparseMatrix& A) {
    if (!matches(A)) {
      dec.analyzePattern(A);
      analysed_ = true;
      outer_.assign(A.outerIndexPtr(), A.outerIndexPtr() + A.outerSize() + 1);
      inner_.assign(A.innerIndexPtr(), A.innerIndexPtr() + A.nonZeros());
    }
    dec.factorize(A);
  }

 private:
  bool matches(const SparseMatrix& A) const {
    return analysed_ && A.isCompressed() && static_cast<size_t>(A.outerSize() + 1) == outer_.size() &&
           static_cast<size_t>(A.nonZeros()) == inner_.size() &&
           std::equal(outer_.begin(), outer_.end(), A.outerIndexPtr()) &&
           std::equal(inner_.begin(), inner_.end(), A.innerIndexPtr());
  }
  bool analysed_ = false;
  std::vector<int> outer_, inner_;
};

// A matrix without its stored zeros. The Jacobian's pattern keeps every contact pair that was
// ever active (so that it rarely changes), and late in an aortic valve closure 46k of the
// 78k stored entries are zeros: factorizing the 32k left takes 2.9 ms instead of 7.0 ms
// (1,179 unknowns, LDLᵀ), more than the symbolic analysis the changing pattern then costs
// (1.2 ms, and only when it changes). Valid until the next call.
class StoredZerosDropped {
 public:
  const SparseMatrix& of(const SparseMatrix& A) {
    pruned_ = A;
    pruned_.prune([](Eigen::Index, Eigen::Index, double v) { return v != 0.0; });
    return pruned_;
  }

 private:
  SparseMatrix pruned_;
};

// Books one factorization (or preconditioner build) into `stats`; true if it succeeded.
bool book_factorization(Eigen::ComputationInfo info, std::chrono::steady_clock::time_point t0,
                        LinearSolverStats& stats) {
  ++stats.factorizations;
  stats.factor_seconds += since(t0);
  const bool ok = info == Eigen::Success;
  if (!ok) ++stats.failures;
  return ok;
}

// Books one solve (and its Krylov iterations) into `stats`; true if it succeeded with finite values.
bool book_solve(bool succeeded, long iterations, const VecX& x, std::chrono::steady_clock::time_point t0,
                LinearSolverStats& stats) {
  ++stats.solves;
  stats.iterations += iterations;
  stats.solve_seconds += since(t0);
  const bool good = succeeded && x.allFinite();
  if (!good) ++stats.failures;
  return good;
}

// Direct solvers share the analyse-once / factorize-per-matrix pattern.
template <class Decomposition>
class DirectSolver final : public LinearSolver {
 public:
  DirectSolver(std::string name, bool symmetric) : name_(std::move(name)), symmetric_(symmetric) { silence(dec_); }
  bool needs_symmetric() const override { return symmetric_; }
  std::string name() const override { return name_; }
  bool factorize(const SparseMatrix& A) override {
    const auto t0 = std::chrono::steady_clock::now();
    pattern_.factorize(dec_, nonzeros_.of(A));
    ok_ = book_factorization(dec_.info(), t0, stats_);
    return ok_;
  }
  bool solve(const VecX& b, VecX& x) override {
    if (!ok_) return false;
    const auto t0 = std::chrono::steady_clock::now();
    x = dec_.solve(b);
    return book_solve(dec_.info() == Eigen::Success, 0, x, t0, stats_);
  }

 private:
  std::string name_;
  bool symmetric_;
  Decomposition dec_;
  StoredZerosDropped nonzeros_;
  AnalysedPattern pattern_;
  bool ok_ = false;
};

// Books one Eigen Krylov solve into `stats`; true if it converged to finite values.
template <class Krylov>
bool book_krylov_solve(const Krylov& it, const VecX& x, std::chrono::steady_clock::time_point t0,
                       LinearSolverStats& stats) {
  return book_solve(it.info() == Eigen::Success, it.iterations(), x, t0, stats);
}

template <class Krylov>
class IterativeSolver final : public LinearSolver {
 public:
  IterativeSolver(std::string name, bool symmetric, double tol, int max_it)
      : name_(std::move(name)), symmetric_(symmetric) {
    it_.setTolerance(tol);
    it_.setMaxIterations(max_it);
  }
  bool needs_symmetric() const override { return symmetric_; }
  std::string name() const override { return name_; }
  void set_tolerance(double tol) override { it_.setTolerance(tol); }
  bool factorize(const SparseMatrix& A) override {
    const auto t0 = std::chrono::steady_clock::now();
    it_.compute(A);
    ok_ = book_factorization(it_.info(), t0, stats_);
    return ok_;
  }
  bool solve(const VecX& b, VecX& x) override {
    if (!ok_) return false;
    const auto t0 = std::chrono::steady_clock::now();
    x = it_.solve(b);
    return book_krylov_solve(it_, x, t0, stats_);
  }

 private:
  std::string name_;
  bool symmetric_;
  Krylov it_;
  bool ok_ = false;
};

// Eigen preconditioner interface over a factorization owned by the solver below.
template <class Factorization>
class SymmetricPartPreconditioner {
 public:
  template <class M>
  SymmetricPartPreconditioner& analyzePattern(const M&) { return *this; }
  template <class M>
  SymmetricPartPreconditioner& factorize(const M&) { return *this; }
  template <class M>
  SymmetricPartPreconditioner& compute(const M&) { return *this; }
  template <class Rhs>
  VecX solve(const Rhs& b) const { return factorization->solve(b); }
  Eigen::ComputationInfo info() const { return Eigen::Success; }
  const Factorization* factorization = nullptr;
};

enum class Krylov { bicgstab, gmres };

// Restart length of GMRES: the sample mitral closure's directions took 872 steps in all with
// 20, 824 with 30 and 824 with 40, so a longer basis (kept as 31 vectors of the system's size)
// buys nothing.
constexpr int kGmresRestart = 30;

// The whole (non-symmetric) system by BiCGStab or GMRES, preconditioned by a factorization of
// its symmetric part (see LinearSolverType::ldlt_bicgstab, llt_gmres and the others).
template <class Factorization>
class SymmetricPartKrylov final : public LinearSolver {
 public:
  SymmetricPartKrylov(std::string name, Krylov method, double tol, int max_it)
      : name_(std::move(name)), method_(method), tol_(tol), max_it_(max_it) {
    silence(factorization_);
    bicgstab_.setTolerance(tol);
    bicgstab_.setMaxIterations(max_it);
    bicgstab_.preconditioner().factorization = &factorization_;
  }
  // The BiCGStab and the operator point into this object.
  SymmetricPartKrylov(const SymmetricPartKrylov&) = delete;
  SymmetricPartKrylov& operator=(const SymmetricPartKrylov&) = delete;
  bool needs_symmetric() const override { return false; }
  std::string name() const override { return name_; }
  void set_tolerance(double tol) override {
    tol_ = tol;
    bicgstab_.setTolerance(tol);
  }
  bool factorize(const SparseMatrix& A) override { return factorize_preconditioned(A, A); }
  bool takes_preconditioner() const override { return true; }
  bool factorize_preconditioned(const SparseMatrix& A, const SparseMatrix& preconditioner) override {
    const auto t0 = std::chrono::steady_clock::now();
    pattern_.factorize(factorization_, symmetric_nonzeros_.of(symmetric_.of(preconditioner)));
    ok_ = book_factorization(factorization_.info(), t0, stats_);
    return set_operator(A);
  }
  bool set_operator(const SparseMatrix& A) override {
    if (ok_) {
      operator_ = &nonzeros_.of(A);
      if (method_ == Krylov::bicgstab) bicgstab_.compute(*operator_);
    }
    return ok_;
  }
  bool solve(const VecX& b, VecX& x) override {
    if (!ok_) return false;
    const auto t0 = std::chrono::steady_clock::now();
    // Start from the symmetric part's solution: the skew part is a small correction.
    if (method_ == Krylov::bicgstab) {
      x = bicgstab_.solveWithGuess(b, factorization_.solve(b));
      return book_krylov_solve(bicgstab_, x, t0, stats_);
    }
    x = factorization_.solve(b);
    const GmresResult r = gmres([&](const VecX& v, VecX& out) { out.noalias() = *operator_ * v; },
                                [&](const VecX& v, VecX& out) { out = factorization_.solve(v); }, b, x, tol_, max_it_,
                                kGmresRestart);
    return book_solve(r.converged, r.iterations, x, t0, stats_);
  }

 private:
  std::string name_;
  Krylov method_;
  double tol_;
  int max_it_;
  Factorization factorization_;
  SymmetricPart symmetric_;
  StoredZerosDropped symmetric_nonzeros_, nonzeros_;
  AnalysedPattern pattern_;
  const SparseMatrix* operator_ = nullptr;  // held by nonzeros_
  Eigen::BiCGSTAB<SparseMatrix, SymmetricPartPreconditioner<Factorization>> bicgstab_;
  bool ok_ = false;
};

}  // namespace

void limit_blas_threads_unless_set() {
  // Looked up at run time: Debian's BLAS is chosen by alternatives (OpenBLAS, reference
  // BLAS, BLIS), and only OpenBLAS has this entry point; elsewhere this does nothing.
  using SetThreads = void (*)(int);
  using Shutdown = int (*)();
  if (!std::getenv("OPENBLAS_NUM_THREADS"))
    if (auto set = reinterpret_cast<SetThreads>(dlsym(RTLD_DEFAULT, "openblas_set_num_threads"))) {
      set(1);
      // The worker threads OpenBLAS started when it was loaded keep spinning (sched_yield) for
      // its thread timeout before they sleep, whether or not BLAS is ever called: about 0.1 s
      // of a core per process, which a second job on a 2-core machine loses (measured on the
      // sample mitral closure: 1.09 s of CPU against 0.99 s with OPENBLAS_NUM_THREADS=1, the
      // same wall time). With one thread BLAS runs on the caller and needs no workers.
      if (auto shutdown = reinterpret_cast<Shutdown>(dlsym(RTLD_DEFAULT, "blas_thread_shutdown_"))) shutdown();
    }
  // CHOLMOD's supernodal factorization (SuiteSparse 5.12) runs small loops per supernode in
  // OpenMP regions of a fixed 4 threads, whatever OMP_NUM_THREADS says (measured: with it at 1
  // the x16 closure still spent 10 s in the kernel). With no active level allowed every region
  // runs on the calling thread alone (libgomp, loaded with CHOLMOD, holds the setting for the
  // process); OMP_MAX_ACTIVE_LEVELS, the one setting that reaches these regions, is the user's.
  if (!std::getenv("OMP_MAX_ACTIVE_LEVELS"))
    if (auto set = reinterpret_cast<SetThreads>(dlsym(RTLD_DEFAULT, "omp_set_max_active_levels"))) set(0);
}

namespace {
const LinearSolverType kAllTypes[] = {LinearSolverType::automatic, LinearSolverType::cholmod_llt,
                                      LinearSolverType::cholmod_ldlt, LinearSolverType::ldlt,
                                      LinearSolverType::umfpack, LinearSolverType::klu,
                                      LinearSolverType::cg, LinearSolverType::bicgstab, LinearSolverType::lu,
                                      LinearSolverType::ldlt_bicgstab, LinearSolverType::llt_bicgstab,
                                      LinearSolverType::cholmod_bicgstab, LinearSolverType::ldlt_gmres,
                                      LinearSolverType::llt_gmres, LinearSolverType::cholmod_gmres};
}  // namespace

const std::vector<std::string>& linear_solver_names() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> v;
    for (auto t : kAllTypes) v.push_back(to_string(t));
    return v;
  }();
  return names;
}

LinearSolverType parse_linear_solver(const std::string& name) {
  for (auto t : kAllTypes)
    if (to_string(t) == name) return t;
  std::string expected;
  for (const auto& n : linear_solver_names()) expected += (expected.empty() ? "" : "|") + n;
  throw InputError("linear solver: expected " + expected + ", found \"" + name + "\"");
}

std::string to_string(LinearSolverType t) {
  switch (t) {
    case LinearSolverType::automatic: return "auto";
    case LinearSolverType::cholmod_llt: return "cholmod_llt";
    case LinearSolverType::cholmod_ldlt: return "cholmod_ldlt";
    case LinearSolverType::ldlt: return "ldlt";
    case LinearSolverType::umfpack: return "umfpack";
    case LinearSolverType::klu: return "klu";
    case LinearSolverType::cg: return "cg";
    case LinearSolverType::bicgstab: return "bicgstab";
    case LinearSolverType::lu: return "lu";
    case LinearSolverType::ldlt_bicgstab: return "ldlt_bicgstab";
    case LinearSolverType::llt_bicgstab: return "llt_bicgstab";
    case LinearSolverType::cholmod_bicgstab: return "cholmod_bicgstab";
    case LinearSolverType::ldlt_gmres: return "ldlt_gmres";
    case LinearSolverType::llt_gmres: return "llt_gmres";
    case LinearSolverType::cholmod_gmres: return "cholmod_gmres";
  }
  return "?";
}

std::unique_ptr<LinearSolver> make_linear_solver(LinearSolverType type, double tol, int max_it, int dofs,
                                                 SystemSymmetry symmetry) {
  const bool large = dofs > kLargeSystemDofs;
  switch (type) {
    case LinearSolverType::automatic:
      if (symmetry == SystemSymmetry::symmetrized)
        return make_linear_solver(large ? LinearSolverType::cholmod_llt : LinearSolverType::ldlt_bicgstab, tol, max_it);
      return make_linear_solver(large ? LinearSolverType::umfpack : LinearSolverType::klu, tol, max_it);
    case LinearSolverType::cholmod_llt:
      return std::make_unique<DirectSolver<Eigen::CholmodSupernodalLLT<SparseMatrix>>>("cholmod_llt", true);
    case LinearSolverType::cholmod_ldlt:
      return std::make_unique<DirectSolver<Eigen::CholmodSimplicialLDLT<SparseMatrix>>>("cholmod_ldlt", true);
    case LinearSolverType::ldlt:
      return std::make_unique<DirectSolver<NodeBlockLdlt>>("ldlt", true);
    case LinearSolverType::lu:
      return std::make_unique<DirectSolver<Eigen::SparseLU<SparseMatrix>>>("lu", false);
    case LinearSolverType::umfpack:
      return std::make_unique<DirectSolver<Eigen::UmfPackLU<SparseMatrix>>>("umfpack", false);
    case LinearSolverType::klu:
      return std::make_unique<DirectSolver<Eigen::KLU<SparseMatrix>>>("klu", false);
    case LinearSolverType::cg:
      return std::make_unique<IterativeSolver<
          Eigen::ConjugateGradient<SparseMatrix, Eigen::Lower | Eigen::Upper, Eigen::IncompleteCholesky<double>>>>(
          "cg", true, tol, max_it);
    case LinearSolverType::bicgstab:
      return std::make_unique<IterativeSolver<Eigen::BiCGSTAB<SparseMatrix, Eigen::IncompleteLUT<double>>>>(
          "bicgstab", false, tol, max_it);
    case LinearSolverType::ldlt_bicgstab:
      return std::make_unique<SymmetricPartKrylov<NodeBlockLdlt>>("ldlt_bicgstab", Krylov::bicgstab, tol, max_it);
    case LinearSolverType::llt_bicgstab:
      return std::make_unique<SymmetricPartKrylov<NodeBlockLlt>>("llt_bicgstab", Krylov::bicgstab, tol, max_it);
    case LinearSolverType::cholmod_bicgstab:
      return std::make_unique<SymmetricPartKrylov<CholmodLlt>>("cholmod_bicgstab", Krylov::bicgstab, tol, max_it);
    case LinearSolverType::ldlt_gmres:
      return std::make_unique<SymmetricPartKrylov<NodeBlockLdlt>>("ldlt_gmres", Krylov::gmres, tol, max_it);
    case LinearSolverType::llt_gmres:
      return std::make_unique<SymmetricPartKrylov<NodeBlockLlt>>("llt_gmres", Krylov::gmres, tol, max_it);
    case LinearSolverType::cholmod_gmres:
      return std::make_unique<SymmetricPartKrylov<CholmodLlt>>("cholmod_gmres", Krylov::gmres, tol, max_it);
  }
  throw InputError("linear solver: unknown type");
}

}  // namespace valve
