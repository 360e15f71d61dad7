#include "valve/material/rod_law.hpp"

#include <cmath>
#include <limits>

namespace valve {

RodResponse LinearRodLaw::response(double stretch) const {
  RodResponse r;
  if (stretch <= 1) return r;
  const double e = stretch - 1;
  r.energy = 0.5 * E_ * e * e;
  r.nominal_stress = E_ * e;
  r.stiffness = E_;
  return r;
}

namespace {

// W̄(u), W̄'(u), W̄''(u) of the deviatoric Ogden energy in u = ln(λ̄1 / λ̄2) (rod_law.hpp);
// expm1 keeps the terms with tiny α (the deck's septal chordae) accurate.
struct Deviatoric {
  double W = 0, W1 = 0, W2 = 0;
};

Deviatoric deviatoric(const OgdenParameters& p, double u) {
  Deviatoric d;
  for (int k = 0; k < p.terms; ++k) {
    const double mu = p.mu[k], al = p.alpha[k];
    if (mu == 0 || al == 0) continue;
    const double x = 2 * al * u / 3, y = -al * u / 3;
    d.W += 2 * mu / (al * al) * (std::expm1(x) + 2 * std::expm1(y));
    d.W1 += 4 * mu / (3 * al) * (std::expm1(x) - std::expm1(y));
    d.W2 += 4 * mu / 9 * (2 * std::exp(x) + std::exp(y));
  }
  return d;
}

struct Volumetric {
  double U = 0, Uv = 0, Uvv = 0;  // U and its derivatives in v = ln J
};

Volumetric volumetric(const OgdenParameters& p, double v) {
  Volumetric r;
  const double J = std::exp(v), x = J - 1;
  double U1 = 0, U2 = 0;
  for (int k = 1; k <= p.terms; ++k) {
    const double D = p.D[k - 1];
    if (D <= 0) continue;
    r.U += std::pow(x, 2 * k) / D;
    U1 += 2 * k * std::pow(x, 2 * k - 1) / D;
    U2 += 2 * k * (2 * k - 1) * std::pow(x, 2 * k - 2) / D;
  }
  r.Uv = U1 * J;
  r.Uvv = U2 * J * J + U1 * J;
  return r;
}

}  // namespace

OgdenRodLaw::Log OgdenRodLaw::solve(double a) const {
  Log out;
  if (p_.D[0] <= 0) {
    const Deviatoric d = deviatoric(p_, 1.5 * a);
    out.W = d.W;
    out.Wa = 1.5 * d.W1;
    out.Waa = 2.25 * d.W2;
    out.b = -0.5 * a;
    return out;
  }
  // W_b = −W̄'(a − b) + 2 U_v(a + 2b) rises from −∞ to +∞ in b: Newton from the
  // incompressible b = −a/2 inside the bracket it builds, bisecting where Newton leaves it.
  double b = -0.5 * a, lo = -std::numeric_limits<double>::infinity(), hi = std::numeric_limits<double>::infinity();
  Deviatoric d;
  Volumetric v;
  for (int it = 0; it < 200; ++it) {
    d = deviatoric(p_, a - b);
    v = volumetric(p_, a + 2 * b);
    const double Wb = -d.W1 + 2 * v.Uv, Wbb = d.W2 + 4 * v.Uvv;
    if (Wb == 0) break;
    if (Wb < 0) lo = b;
    else hi = b;
    double next = Wbb > 0 ? b - Wb / Wbb : std::numeric_limits<double>::quiet_NaN();
    if (!(next > lo && next < hi))
      next = std::isfinite(lo) && std::isfinite(hi) ? 0.5 * (lo + hi) : (std::isfinite(lo) ? b + 0.1 : b - 0.1);
    const bool converged = std::abs(next - b) <= 1e-15;
    b = next;
    if (converged) {
      d = deviatoric(p_, a - b);
      v = volumetric(p_, a + 2 * b);
      break;
    }
  }
  const double Wa = d.W1 + v.Uv, Waa = d.W2 + v.Uvv, Wab = -d.W2 + 2 * v.Uvv, Wbb = d.W2 + 4 * v.Uvv;
  out.W = d.W + v.U;
  out.Wa = Wa;
  out.Waa = Waa - Wab * Wab / Wbb;
  out.b = b;
  return out;
}

RodResponse OgdenRodLaw::response(double stretch) const {
  RodResponse r;
  if (stretch <= 1) return r;
  const Log l = solve(std::log(stretch));
  r.energy = l.W;
  r.nominal_stress = l.Wa / stretch;
  r.stiffness = (l.Waa - l.Wa) / (stretch * stretch);
  return r;
}

double OgdenRodLaw::lateral_stretch(double stretch) const { return std::exp(solve(std::log(stretch)).b); }

double OgdenRodLaw::initial_youngs_modulus() const {
  double mu0 = 0;
  for (int k = 0; k < p_.terms; ++k) mu0 += p_.mu[k];
  if (p_.D[0] <= 0) return 3 * mu0;
  const double K = 2 / p_.D[0];
  return 9 * K * mu0 / (3 * K + mu0);
}

}  // namespace valve
