#include "valve/material/hgo_law.hpp"

#include <algorithm>
#include <cmath>

namespace valve {
namespace {

// Invariants and their first and second derivatives with respect to c = (C11, C22, C12).
struct Invariants {
  double I1 = 3, I4 = 1, Ef = 0;
  Voigt dI1, dEf;
  Mat3 d2I1, d2Ef;
};

Invariants invariants(const HgoParameters& p, const Voigt& E) {
  const double C11 = 1 + 2 * E[0], C22 = 1 + 2 * E[1], C12 = E[2];
  // det C > 0 for every orientation-preserving in-plane deformation; the floor only keeps a
  // crushed triangle from dividing by zero (its energy is then huge, and the step is rejected).
  const double J = std::max(C11 * C22 - C12 * C12, 1e-6);
  const Voigt dJ(C22, C11, -2 * C12);
  Mat3 d2J;
  d2J << 0, 1, 0, 1, 0, 0, 0, 0, -2;
  Invariants v;
  // u = 1/J = C33: du = −dJ/J², d²u = 2 dJ dJᵀ/J³ − d²J/J².
  v.I1 = C11 + C22 + 1 / J;
  v.dI1 = Voigt(1, 1, 0) - dJ / (J * J);
  v.d2I1 = 2 * dJ * dJ.transpose() / (J * J * J) - d2J / (J * J);
  v.I4 = C11;
  v.Ef = p.kappa * (v.I1 - 3) + (1 - 3 * p.kappa) * (v.I4 - 1);
  v.dEf = p.kappa * v.dI1 + (1 - 3 * p.kappa) * Voigt(1, 0, 0);
  v.d2Ef = p.kappa * v.d2I1;
  return v;
}

// dc/dÊ = diag(2, 2, 1).
const Voigt kVoigtScale(2, 2, 1);

}  // namespace

double HgoLaw::energy(const Voigt& E) const {
  const Invariants v = invariants(p_, E);
  const double Ef = std::max(v.Ef, 0.0);
  double W = p_.C10 * std::expm1(p_.C01 * (v.I1 - 3));
  if (p_.k1 > 0 && p_.k2 > 0) W += p_.k1 / (2 * p_.k2) * std::expm1(p_.k2 * Ef * Ef);
  return W;
}

Voigt HgoLaw::stress(const Voigt& E) const {
  Voigt S;
  evaluate(E, S, nullptr);  // the force-only path of the FE term: no tangent
  return S;
}

Mat3 HgoLaw::tangent(const Voigt& E) const {
  Voigt S;
  Mat3 D;
  evaluate(E, S, &D);
  return D;
}

void HgoLaw::stress_and_tangent(const Voigt& E, Voigt& S, Mat3& D) const { evaluate(E, S, &D); }

void HgoLaw::evaluate(const Voigt& E, Voigt& S, Mat3* D) const {
  const Invariants v = invariants(p_, E);
  // Isotropic part: W1 = dW/dI1, W11 = d²W/dI1².
  const double e = std::exp(p_.C01 * (v.I1 - 3));
  const double W1 = p_.C10 * p_.C01 * e, W11 = p_.C10 * p_.C01 * p_.C01 * e;
  Voigt g = W1 * v.dI1;
  Mat3 H = Mat3::Zero();
  if (D) H = W11 * v.dI1 * v.dI1.transpose() + W1 * v.d2I1;
  // Fiber part (tension only): Wf = k1 Ef e^{k2 Ef²}, Wff = k1 (1 + 2 k2 Ef²) e^{k2 Ef²}.
  if (v.Ef > 0 && p_.k1 > 0) {
    const double ef = std::exp(p_.k2 * v.Ef * v.Ef);
    const double Wf = p_.k1 * v.Ef * ef, Wff = p_.k1 * (1 + 2 * p_.k2 * v.Ef * v.Ef) * ef;
    g += Wf * v.dEf;
    if (D) H += Wff * v.dEf * v.dEf.transpose() + Wf * v.d2Ef;
  }
  S = kVoigtScale.cwiseProduct(g);
  if (D) *D = kVoigtScale.asDiagonal() * H * kVoigtScale.asDiagonal();
}

}  // namespace valve
