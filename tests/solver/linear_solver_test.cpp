// The linear solvers against Eigen's sparse LU on systems like BDF2's: a symmetric positive
// definite part (mass + stiffness) plus a small antisymmetric part (follower pressure).
#include <catch2/catch.hpp>

#include <Eigen/SparseLU>
#include <dlfcn.h>

#include <cstdlib>
#include <filesystem>
#include <random>

#include "valve/solver/constrained_system.hpp"
#include "valve/solver/linear_solver.hpp"

using namespace valve;

namespace {
// n x n: a 1-D Laplacian with bandwidth 3 plus a diagonal (SPD) and, scaled by `skew`, an
// antisymmetric coupling on the first off-diagonals.
SparseMatrix bdf2_like(int n, double skew) {
  std::vector<Eigen::Triplet<double>> t;
  for (int i = 0; i < n; ++i) {
    t.emplace_back(i, i, 8.0);
    for (int d = 1; d <= 3 && i + d < n; ++d) {
      const double k = -1.0 / d;
      t.emplace_back(i, i + d, k + (d == 1 ? skew : 0.0));
      t.emplace_back(i + d, i, k - (d == 1 ? skew : 0.0));
    }
  }
  SparseMatrix A(n, n);
  A.setFromTriplets(t.begin(), t.end());
  A.makeCompressed();
  return A;
}

double relative_residual(const SparseMatrix& A, const VecX& x, const VecX& b) { return (A * x - b).norm() / b.norm(); }

const LinearSolverType kOnSymmetricPart[] = {LinearSolverType::ldlt_bicgstab, LinearSolverType::llt_bicgstab,
                                             LinearSolverType::cholmod_bicgstab, LinearSolverType::ldlt_gmres,
                                             LinearSolverType::llt_gmres, LinearSolverType::cholmod_gmres};
}  // namespace

TEST_CASE("BiCGStab or GMRES on the symmetric part's LDLT, LLT or CHOLMOD Cholesky solves the whole non-symmetric system, the symmetric part alone does not", "[solver]") {
  const int n = 300;
  const SparseMatrix A = bdf2_like(n, 0.8);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  VecX b(n);
  for (int i = 0; i < n; ++i) b[i] = u(rng);

  Eigen::SparseLU<SparseMatrix> lu(A);
  REQUIRE(lu.info() == Eigen::Success);
  const VecX reference = lu.solve(b);

  VecX x;
  for (auto type : kOnSymmetricPart) {
    INFO(to_string(type));
    auto whole = make_linear_solver(type, 1e-10, 200);
    CHECK(whole->name() == to_string(type));
    CHECK_FALSE(whole->needs_symmetric());
    REQUIRE(whole->factorize(A));
    REQUIRE(whole->solve(b, x));
    CHECK(relative_residual(A, x, b) < 1e-9);
    CHECK((x - reference).norm() < 1e-8 * reference.norm());
    CHECK(whole->stats().iterations <= 20);
  }

  // The symmetric part alone: its answer misses the whole system.
  auto sym = make_linear_solver(LinearSolverType::ldlt);
  REQUIRE(sym->factorize(symmetric_part(A)));
  REQUIRE(sym->solve(b, x));
  CHECK(relative_residual(A, x, b) > 1e-2);
}

TEST_CASE("a Krylov solve on the symmetric part's factorization needs no iteration on a symmetric system", "[solver]") {
  const SparseMatrix A = bdf2_like(200, 0.0);
  const VecX b = VecX::LinSpaced(200, -1, 1);
  for (auto type : kOnSymmetricPart) {
    INFO(to_string(type));
    auto s = make_linear_solver(type, 1e-10, 200);
    VecX x;
    REQUIRE(s->factorize(A));
    REQUIRE(s->solve(b, x));
    CHECK(relative_residual(A, x, b) < 1e-10);
    CHECK(s->stats().iterations <= 1);
  }
}

TEST_CASE("BiCGStab or GMRES on a Cholesky solves an indefinite system on a definite preconditioner, and another on the same factorization", "[solver]") {
  // A: the definite system P with a rank-2 indefinite change (two unknowns' diagonals turned
  // negative), as an exact contact Hessian differs from its projection on a few pairs.
  const int n = 300;
  const SparseMatrix P = bdf2_like(n, 0.3);
  SparseMatrix A = P;
  A.coeffRef(40, 40) = -3.0;
  A.coeffRef(200, 200) = -5.0;
  const VecX b = VecX::LinSpaced(n, -1, 2);
  auto reference = [&](const SparseMatrix& M) {
    Eigen::SparseLU<SparseMatrix> lu(M);
    REQUIRE(lu.info() == Eigen::Success);
    return VecX(lu.solve(b));
  };
  auto cholesky = make_linear_solver(LinearSolverType::cholmod_llt);
  CHECK_FALSE(cholesky->factorize(symmetric_part(A)));
  CHECK_FALSE(cholesky->factorize_preconditioned(A, P));

  for (auto type : {LinearSolverType::llt_bicgstab, LinearSolverType::cholmod_bicgstab, LinearSolverType::llt_gmres,
                    LinearSolverType::cholmod_gmres}) {
    INFO(to_string(type));
    auto s = make_linear_solver(type, 1e-12, 200);
    CHECK_FALSE(s->factorize(A));  // its symmetric part is indefinite
    VecX x;
    REQUIRE(s->factorize_preconditioned(A, P));
    REQUIRE(s->solve(b, x));
    CHECK((x - reference(A)).norm() < 1e-9 * reference(A).norm());
    REQUIRE(s->set_operator(P));
    REQUIRE(s->solve(b, x));
    CHECK((x - reference(P)).norm() < 1e-9 * reference(P).norm());
    CHECK(s->stats().factorizations == 2);
  }
}

TEST_CASE("GMRES on the symmetric part's Cholesky needs fewer preconditioner solves than BiCGStab", "[solver]") {
  // BiCGStab applies the preconditioner twice per iteration, GMRES once per step and once more
  // per cycle (30 steps here are one cycle); both once for their start. On a strongly skew
  // system GMRES needs fewer in all. Both stop at the same true relative residual.
  const int n = 300;
  const SparseMatrix A = bdf2_like(n, 2.0);
  const VecX b = VecX::LinSpaced(n, -1, 2);
  auto solves = [&](LinearSolverType type) {
    auto s = make_linear_solver(type, 1e-10, 500);
    VecX x;
    REQUIRE(s->factorize(A));
    REQUIRE(s->solve(b, x));
    CHECK(relative_residual(A, x, b) < 1e-9);  // BiCGStab stops on its recurred residual
    return s->stats().iterations;
  };
  const long bicgstab = solves(LinearSolverType::llt_bicgstab), gmres = solves(LinearSolverType::llt_gmres);
  INFO("BiCGStab " << bicgstab << " iterations, GMRES " << gmres << " steps");
  CHECK(gmres > 2);
  CHECK(gmres <= 30);
  CHECK(1 + gmres + 1 < 1 + 2 * bicgstab);
}

TEST_CASE("automatic linear solver: the whole system for small BDF2 systems, Cholesky for large", "[solver]") {
  CHECK(make_linear_solver(LinearSolverType::automatic, 1e-10, 100, 1000, SystemSymmetry::symmetrized)->name() ==
        "ldlt_bicgstab");
  CHECK(make_linear_solver(LinearSolverType::automatic, 1e-10, 100, kLargeSystemDofs + 3, SystemSymmetry::symmetrized)
            ->name() == "cholmod_llt");
  CHECK(make_linear_solver(LinearSolverType::automatic, 1e-10, 100, 1000, SystemSymmetry::general)->name() == "klu");
}

namespace {
int threads_of_this_process() {
  int n = 0;
  for ([[maybe_unused]] const auto& entry : std::filesystem::directory_iterator("/proc/self/task")) ++n;
  return n;
}
}  // namespace

TEST_CASE("a CHOLMOD supernodal factorization starts no threads once the stage has limited them", "[solver]") {
  // CHOLMOD 5.12 opens OpenMP regions of a fixed 4 threads inside every supernodal
  // factorization: on two cores their wake-ups cost the x16 mitral closure 20 s of 50.
  limit_blas_threads_unless_set();
  if (std::getenv("OMP_MAX_ACTIVE_LEVELS")) {
    SUCCEED("left to the user's setting");
    return;
  }
  using GetLevels = int (*)();
  if (auto levels = reinterpret_cast<GetLevels>(dlsym(RTLD_DEFAULT, "omp_get_max_active_levels")))
    CHECK(levels() == 0);
  // A 3-D Laplacian of 20^3 unknowns: hundreds of supernodes, BLAS-3 within each.
  const int m = 20, n = m * m * m;
  std::vector<Eigen::Triplet<double>> t;
  auto id = [&](int i, int j, int k) { return (i * m + j) * m + k; };
  for (int i = 0; i < m; ++i)
    for (int j = 0; j < m; ++j)
      for (int k = 0; k < m; ++k) {
        t.emplace_back(id(i, j, k), id(i, j, k), 6.1);
        if (i + 1 < m) t.emplace_back(id(i, j, k), id(i + 1, j, k), -1), t.emplace_back(id(i + 1, j, k), id(i, j, k), -1);
        if (j + 1 < m) t.emplace_back(id(i, j, k), id(i, j + 1, k), -1), t.emplace_back(id(i, j + 1, k), id(i, j, k), -1);
        if (k + 1 < m) t.emplace_back(id(i, j, k), id(i, j, k + 1), -1), t.emplace_back(id(i, j, k + 1), id(i, j, k), -1);
      }
  SparseMatrix A(n, n);
  A.setFromTriplets(t.begin(), t.end());
  const int before = threads_of_this_process();
  auto solver = make_linear_solver(LinearSolverType::cholmod_llt, 1e-10, 100);
  REQUIRE(solver->factorize(A));
  const VecX b = VecX::Ones(n);
  VecX x;
  REQUIRE(solver->solve(b, x));
  CHECK((A * x - b).norm() <= 1e-10 * b.norm());
  CHECK(threads_of_this_process() == before);
}
