// Restarted, right-preconditioned GMRES against dense LU on small non-symmetric systems.
#include <catch2/catch.hpp>

#include <Eigen/Dense>

#include <cmath>
#include <limits>
#include <random>

#include "valve/solver/gmres.hpp"

using namespace valve;
using Eigen::MatrixXd;
using Eigen::VectorXd;

namespace {
// A diagonally dominant matrix with a random non-symmetric part of relative size `skew`.
MatrixXd non_symmetric(int n, double skew, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  MatrixXd A = MatrixXd::Zero(n, n);
  for (int i = 0; i < n; ++i) {
    A(i, i) = 4.0;
    if (i + 1 < n) A(i, i + 1) = A(i + 1, i) = -1.0;
  }
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) A(i, j) += skew * u(rng) / std::sqrt(double(n));
  return A;
}

struct Counted {
  const MatrixXd& A;
  mutable int products = 0;
  void operator()(const VectorXd& v, VectorXd& out) const {
    ++products;
    out = A * v;
  }
};

const auto identity = [](const VectorXd& v, VectorXd& out) { out = v; };
}  // namespace

TEST_CASE("GMRES solves a non-symmetric system to the true relative residual it is asked for", "[solver]") {
  const int n = 60;
  const MatrixXd A = non_symmetric(n, 1.5, 3);
  const VectorXd b = VectorXd::LinSpaced(n, -1, 2);
  const VectorXd reference = A.partialPivLu().solve(b);
  for (double tol : {1e-4, 1e-10}) {
    VectorXd x = VectorXd::Zero(n);
    const GmresResult r = gmres(Counted{A}, identity, b, x, tol, 500, 30);
    INFO("tol " << tol << ": " << r.iterations << " steps");
    REQUIRE(r.converged);
    const double true_residual = (b - A * x).norm() / b.norm();
    CHECK(true_residual <= tol);
    CHECK(r.relative_residual == Approx(true_residual).epsilon(1e-6).margin(1e-14));
    CHECK((x - reference).norm() <= 10 * tol * reference.norm() * A.norm() * A.inverse().norm());
  }
}

TEST_CASE("GMRES with the exact inverse as preconditioner needs one step; a restart keeps a short basis converging", "[solver]") {
  const int n = 50;
  const MatrixXd A = non_symmetric(n, 2.0, 5);
  const VectorXd b = VectorXd::Ones(n);
  const auto lu = A.partialPivLu();
  VectorXd x = VectorXd::Zero(n);
  const GmresResult exact = gmres(Counted{A}, [&](const VectorXd& v, VectorXd& out) { out = lu.solve(v); }, b, x,
                                  1e-12, 100, 30);
  REQUIRE(exact.converged);
  CHECK(exact.iterations == 1);
  CHECK((A * x - b).norm() <= 1e-12 * b.norm());

  // A basis of 4 vectors cannot hold the solution (the unrestarted solve takes more steps):
  // the restarts still reach it, in more steps than without them.
  x.setZero();
  const GmresResult full = gmres(Counted{A}, identity, b, x, 1e-10, 500, 100);
  x.setZero();
  const GmresResult restarted = gmres(Counted{A}, identity, b, x, 1e-10, 500, 4);
  INFO(full.iterations << " steps unrestarted, " << restarted.iterations << " restarted every 4");
  REQUIRE(full.converged);
  REQUIRE(restarted.converged);
  CHECK(full.iterations > 4);
  CHECK(restarted.iterations > full.iterations);
  CHECK((A * x - b).norm() <= 1e-10 * b.norm());
}

TEST_CASE("GMRES solves an indefinite system, starts from the guess it is given, and reports when it runs out of steps", "[solver]") {
  const int n = 40;
  MatrixXd A = non_symmetric(n, 0.5, 9);
  A(3, 3) = -6.0;  // two negative eigenvalues' worth of indefiniteness
  A(20, 20) = -5.0;
  const VectorXd b = VectorXd::LinSpaced(n, 1, 3);
  const VectorXd reference = A.partialPivLu().solve(b);

  VectorXd x = VectorXd::Zero(n);
  const GmresResult r = gmres(Counted{A}, identity, b, x, 1e-10, 500, 30);
  REQUIRE(r.converged);
  CHECK((x - reference).norm() <= 1e-8 * reference.norm());

  // From the solution itself: no step.
  x = reference;
  CHECK(gmres(Counted{A}, identity, b, x, 1e-8, 500, 30).iterations == 0);

  // Three steps are not enough: not converged, with the residual reached.
  x.setZero();
  const GmresResult short_of_steps = gmres(Counted{A}, identity, b, x, 1e-10, 3, 30);
  CHECK_FALSE(short_of_steps.converged);
  CHECK(short_of_steps.iterations == 3);
  CHECK(short_of_steps.relative_residual > 1e-10);
  CHECK(short_of_steps.relative_residual < 1.0);
  CHECK(short_of_steps.relative_residual == Approx((b - A * x).norm() / b.norm()).epsilon(1e-9));
}

TEST_CASE("GMRES ends unconverged, x unchanged, where no step can lower the residual", "[solver]") {
  // A singular system with the right-hand side partly outside its range: the first Krylov
  // vector maps to zero, so the cycle has no column to solve with.
  MatrixXd A = MatrixXd::Zero(3, 3);
  A(1, 1) = 2.0, A(2, 2) = 3.0;
  const VectorXd b = VectorXd::Unit(3, 0);
  VectorXd x = VectorXd::Zero(3);
  const GmresResult r = gmres(Counted{A}, identity, b, x, 1e-10, 100, 30);
  CHECK_FALSE(r.converged);
  CHECK(r.iterations == 1);
  CHECK(x.isZero());
  CHECK(r.relative_residual == Approx(1.0));

  // Partly in the range: the reachable part is solved, then the cycle that cannot go further ends it.
  VectorXd b2(3);
  b2 << 1.0, 2.0, 3.0;
  x.setZero();
  const GmresResult partly = gmres(Counted{A}, identity, b2, x, 1e-10, 100, 30);
  CHECK_FALSE(partly.converged);
  CHECK(x.allFinite());
  CHECK(partly.relative_residual == Approx(1.0 / b2.norm()).epsilon(1e-8));
  CHECK(partly.relative_residual == Approx((b2 - A * x).norm() / b2.norm()).epsilon(1e-12));
}

TEST_CASE("GMRES returns zero for a zero right-hand side and stops on a non-finite product", "[solver]") {
  const int n = 10;
  const MatrixXd A = non_symmetric(n, 0.3, 1);
  VectorXd x = VectorXd::Ones(n);
  const GmresResult zero = gmres(Counted{A}, identity, VectorXd::Zero(n), x, 1e-10, 100, 30);
  CHECK(zero.converged);
  CHECK(x.isZero());

  const auto broken = [](const VectorXd& v, VectorXd& out) {
    out = v;
    out[0] = std::numeric_limits<double>::quiet_NaN();
  };
  x.setZero();
  const GmresResult r = gmres(broken, identity, VectorXd::Ones(n), x, 1e-10, 100, 30);
  CHECK_FALSE(r.converged);
  CHECK(r.iterations <= 100);

  // A product that turns non-finite inside a cycle: stopped there, x still the start.
  int products = 0;
  const auto breaks_later = [&](const VectorXd& v, VectorXd& out) {
    out = A * v;
    if (++products > 3) out[0] = std::numeric_limits<double>::infinity();
  };
  x.setZero();
  const GmresResult later = gmres(breaks_later, identity, VectorXd::Ones(n), x, 1e-14, 100, 30);
  CHECK_FALSE(later.converged);
  CHECK(later.iterations == 3);
  CHECK(x.isZero());

  // A non-finite right-hand side: not converged, nothing done.
  VectorXd nan_b = VectorXd::Ones(n);
  nan_b[2] = std::numeric_limits<double>::quiet_NaN();
  x.setOnes();
  const GmresResult nan_rhs = gmres(Counted{A}, identity, nan_b, x, 1e-10, 100, 30);
  CHECK_FALSE(nan_rhs.converged);
  CHECK(nan_rhs.iterations == 0);
}
