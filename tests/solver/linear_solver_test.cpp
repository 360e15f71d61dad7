// The linear solvers against Eigen's sparse LU on systems like BDF2's: a symmetric positive
// definite part (mass + stiffness) plus a small antisymmetric part (follower pressure).
#include <catch2/catch.hpp>

#include <Eigen/SparseLU>
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
}  // namespace

TEST_CASE("ldlt_bicgstab solves the whole non-symmetric system, the symmetric part alone does not", "[solver]") {
  const int n = 300;
  const SparseMatrix A = bdf2_like(n, 0.8);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  VecX b(n);
  for (int i = 0; i < n; ++i) b[i] = u(rng);

  Eigen::SparseLU<SparseMatrix> lu(A);
  REQUIRE(lu.info() == Eigen::Success);
  const VecX reference = lu.solve(b);

  auto whole = make_linear_solver(LinearSolverType::ldlt_bicgstab, 1e-10, 200);
  CHECK_FALSE(whole->needs_symmetric());
  VecX x;
  REQUIRE(whole->factorize(A));
  REQUIRE(whole->solve(b, x));
  CHECK(relative_residual(A, x, b) < 1e-9);
  CHECK((x - reference).norm() < 1e-8 * reference.norm());
  CHECK(whole->stats().iterations <= 20);

  // What BDF2 solved before: the symmetric part only; its answer misses the whole system.
  auto sym = make_linear_solver(LinearSolverType::ldlt);
  REQUIRE(sym->factorize(symmetric_part(A)));
  REQUIRE(sym->solve(b, x));
  CHECK(relative_residual(A, x, b) > 1e-2);
}

TEST_CASE("ldlt_bicgstab on a symmetric system needs no iteration beyond the factorization", "[solver]") {
  const SparseMatrix A = bdf2_like(200, 0.0);
  const VecX b = VecX::LinSpaced(200, -1, 1);
  auto s = make_linear_solver(LinearSolverType::ldlt_bicgstab, 1e-10, 200);
  VecX x;
  REQUIRE(s->factorize(A));
  REQUIRE(s->solve(b, x));
  CHECK(relative_residual(A, x, b) < 1e-10);
  CHECK(s->stats().iterations <= 1);
}

TEST_CASE("automatic linear solver: the whole system for small BDF2 systems, Cholesky for large", "[solver]") {
  CHECK(make_linear_solver(LinearSolverType::automatic, 1e-10, 100, 1000, SystemSymmetry::symmetrized)->name() ==
        "ldlt_bicgstab");
  CHECK(make_linear_solver(LinearSolverType::automatic, 1e-10, 100, kLargeSystemDofs + 3, SystemSymmetry::symmetrized)
            ->name() == "cholmod_llt");
  CHECK(make_linear_solver(LinearSolverType::automatic, 1e-10, 100, 1000, SystemSymmetry::general)->name() == "klu");
}
