#pragma once
// Restarted GMRES, right-preconditioned (Saad, "Iterative Methods for Sparse Linear Systems",
// 2nd ed., Algorithm 9.5), with modified Gram-Schmidt Arnoldi and Givens rotations.
//
// Why not Eigen's unsupported GMRES: it preconditions on the left, so the residual it
// minimises and tests is M⁻¹(b − A x) relative to the start's, not b − A x relative to b. The
// Newton directions need the true relative residual: the forcing terms (Eisenstat-Walker)
// bound |f + J Δ| / |f|, and BiCGStab, which this replaces where it is chosen, tests the same.
// With right preconditioning the residual GMRES minimises is the true one, so the test needs
// no extra work.
#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <vector>

namespace valve {

struct GmresResult {
  bool converged = false;
  int iterations = 0;            // Arnoldi steps, one operator product and one preconditioner solve each
  double relative_residual = 0;  // |b − A x| / |b| at the x returned
};

/// Solves A x = b from the start `x`, to |b − A x| ≤ tol |b|. `apply(v, out)` sets out = A v;
/// `precondition(v, out)` sets out = M⁻¹ v. Restarts every `restart` steps; at most
/// `max_iterations` steps in all. A non-finite right-hand side, product or solve ends it
/// unconverged, as does a cycle that cannot lower the residual (A M⁻¹ singular on its Krylov
/// space); x is then the last iterate measured.
template <class Apply, class Precondition>
GmresResult gmres(const Apply& apply, const Precondition& precondition, const Eigen::VectorXd& b, Eigen::VectorXd& x,
                  double tol, int max_iterations, int restart = 30) {
  using Eigen::VectorXd;
  GmresResult result;
  const Eigen::Index n = b.size();
  const double b_norm = b.norm();
  if (!std::isfinite(b_norm)) return result;
  if (b_norm == 0) {
    x.setZero();
    result.converged = true;
    return result;
  }
  const double target = tol * b_norm;
  constexpr double kRoundingLevel = 1e-13;
  const int m = std::max(1, restart);
  std::vector<VectorXd> basis(m + 1, VectorXd(n));
  Eigen::MatrixXd hessenberg = Eigen::MatrixXd::Zero(m + 1, m);
  VectorXd cs(m), sn(m), g(m + 1), w(n), z(n), r(n);
  while (true) {
    apply(x, r);
    r = b - r;
    double beta = r.norm();
    result.relative_residual = beta / b_norm;
    if (!std::isfinite(beta)) return result;
    if (beta <= target) {
      result.converged = true;
      return result;
    }
    if (result.iterations >= max_iterations) return result;
    basis[0] = r / beta;
    g.setZero();
    g(0) = beta;
    int k = 0;  // Arnoldi steps in this cycle
    for (; k < m && result.iterations < max_iterations; ++k) {
      ++result.iterations;
      precondition(basis[k], z);
      apply(z, w);
      const double product_norm = w.norm();
      for (int i = 0; i <= k; ++i) {  // modified Gram-Schmidt
        hessenberg(i, k) = w.dot(basis[i]);
        w -= hessenberg(i, k) * basis[i];
      }
      const double h_next = w.norm();
      hessenberg(k + 1, k) = h_next;
      if (!std::isfinite(h_next)) return result;
      for (int i = 0; i < k; ++i) {  // earlier rotations on the new column
        const double a = hessenberg(i, k), c = hessenberg(i + 1, k);
        hessenberg(i, k) = cs(i) * a + sn(i) * c;
        hessenberg(i + 1, k) = -sn(i) * a + cs(i) * c;
      }
      const double a = hessenberg(k, k), c = hessenberg(k + 1, k);
      const double rho = std::hypot(a, c);
      // A diagonal at rounding level against the product it came from: A M⁻¹ is singular on the
      // Krylov space, this step cannot lower the residual (its column would only amplify
      // rounding), and the cycle ends with the columns before it.
      if (!(rho > kRoundingLevel * product_norm)) break;
      cs(k) = a / rho;
      sn(k) = c / rho;
      hessenberg(k, k) = rho;
      hessenberg(k + 1, k) = 0;
      g(k + 1) = -sn(k) * g(k);
      g(k) = cs(k) * g(k);
      // Breakdown (nothing of the product left outside the basis): the Krylov space holds the
      // solution, or as much of it as it can.
      const bool breakdown = !(h_next > kRoundingLevel * product_norm);
      const bool done = std::abs(g(k + 1)) <= target || breakdown;
      if (!breakdown) basis[k + 1] = w / h_next;
      if (done) {
        ++k;
        break;
      }
    }
    if (k == 0) return result;  // nothing in this cycle lowers the residual
    // x += M⁻¹ V y with H y = g: one more preconditioner solve per cycle, so that only V is kept.
    const VectorXd y =
        hessenberg.topLeftCorner(k, k).triangularView<Eigen::Upper>().solve(g.head(k));
    w.setZero();
    for (int i = 0; i < k; ++i) w += y(i) * basis[i];
    precondition(w, z);
    x += z;
  }
}

}  // namespace valve
