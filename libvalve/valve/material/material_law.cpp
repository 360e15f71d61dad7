#include "valve/material/material_law.hpp"

#include <Eigen/Dense>
#include <cmath>

namespace valve {

double FungLaw::Q(const Voigt& E) const {
  const double e11 = E[0], e22 = E[1], e12 = 0.5 * E[2];
  return p_.A1 * e11 * e11 + p_.A2 * e22 * e22 + 2 * p_.A3 * e11 * e22 + p_.A4 * e12 * e12 +
         2 * p_.A5 * e11 * e12 + 2 * p_.A6 * e22 * e12;
}

Voigt FungLaw::dQ(const Voigt& E) const {
  const double e11 = E[0], e22 = E[1], e12 = 0.5 * E[2];
  // dQ/dγ = 1/2 dQ/dE12.
  return Voigt(2 * (p_.A1 * e11 + p_.A3 * e22 + p_.A5 * e12),
               2 * (p_.A2 * e22 + p_.A3 * e11 + p_.A6 * e12),
               p_.A4 * e12 + p_.A5 * e11 + p_.A6 * e22);
}

Mat3 FungLaw::d2Q() const {
  Mat3 H;
  H << 2 * p_.A1, 2 * p_.A3, p_.A5,  //
      2 * p_.A3, 2 * p_.A2, p_.A6,   //
      p_.A5, p_.A6, 0.5 * p_.A4;
  return H;
}

double FungLaw::energy(const Voigt& E) const { return 0.5 * p_.c * std::expm1(Q(E)); }

Voigt FungLaw::stress(const Voigt& E) const { return 0.5 * p_.c * std::exp(Q(E)) * dQ(E); }

Mat3 FungLaw::tangent(const Voigt& E) const {
  const Voigt g = dQ(E);
  return 0.5 * p_.c * std::exp(Q(E)) * (g * g.transpose() + d2Q());
}

void FungLaw::stress_and_tangent(const Voigt& E, Voigt& S, Mat3& D) const {
  const Voigt g = dQ(E);
  const double a = 0.5 * p_.c * std::exp(Q(E));
  S = a * g;
  D = a * (g * g.transpose() + d2Q());
}

bool invert_stress(const MaterialLaw& law, const Voigt& target, Voigt& E, double tol) {
  E.setZero();
  const double scale = std::max(target.norm(), 1e-30);
  for (int it = 0; it < 200; ++it) {
    Voigt S;
    Mat3 D;
    law.stress_and_tangent(E, S, D);
    const Voigt r = S - target;
    if (r.norm() <= tol * scale) return true;
    Voigt dE = D.partialPivLu().solve(-r);
    if (!dE.allFinite()) return false;
    // Backtrack on the residual norm: the exponential overshoots from E = 0.
    double step = 1.0;
    for (int k = 0; k < 40; ++k) {
      const Voigt trial = E + step * dE;
      const Voigt rt = law.stress(trial) - target;
      if (rt.allFinite() && rt.norm() < r.norm()) break;
      step *= 0.5;
    }
    E += step * dE;
  }
  return false;
}

}  // namespace valve
