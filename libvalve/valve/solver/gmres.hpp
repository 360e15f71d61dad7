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

#include <cmath>
#include <vector>

namespace valve {

struct GmresResult {
  bool converged = false;
  int iterations = 0;          // Arnoldi steps, one operator product and one preconditioner solve each
  double relative_residual = 0;  // |b − A x| / |b| as the last restart measured it, or the Arnoldi estimate
};

/// Solves A x = b from the start `x`, to |b − A x| ≤ tol |b|. `apply(v, out)` sets out = A v;
/// `precondition(v, out)` sets out = M⁻¹ v. Restarts every `restart` steps; at most
/// `max_iterations` steps in all. A non-finite product or solve ends it unconverged.
template <class Apply, class Precondition>
GmresResult gmres(const Apply& apply, const Precondition& precondition, const Eigen::VectorXd& b, Eigen::VectorXd& x,
                  double tol, int max_iterations, int restart = 30) {
  using Eigen::VectorXd;
  GmresResult result;
  const Eigen::Index n = b.size();
  const double b_norm = b.norm();
  if (!(b_norm > 0)) {
    x.setZero();
    result.converged = true;
    return result;
  }
  const double target = tol * b_norm;
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
      cs(k) = rho > 0 ? a / rho : 1.0;
      sn(k) = rho > 0 ? c / rho : 0.0;
      hessenberg(k, k) = rho;
      hessenberg(k + 1, k) = 0;
      g(k + 1) = -sn(k) * g(k);
      g(k) = cs(k) * g(k);
      // Happy breakdown (h_next = 0): the Krylov space holds the solution.
      const bool done = std::abs(g(k + 1)) <= target || !(h_next > 0);
      if (h_next > 0) basis[k + 1] = w / h_next;
      if (done) {
        ++k;
        break;
      }
    }
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
