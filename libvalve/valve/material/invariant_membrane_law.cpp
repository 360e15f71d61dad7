#include "valve/material/invariant_membrane_law.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace valve {

InvariantDerivatives IsotropicExponentialEnergy::evaluate(double I1, double) const {
  // W̄ = C0/2 (Ī1 − 3) + C1/2 (e^{C2 x²} − 1), x = Ī1 − 3:
  // W1 = C0/2 + C1 C2 x e^{C2 x²},  W11 = C1 C2 e^{C2 x²} (1 + 2 C2 x²)  (as the subroutine's ui1, ui2).
  const double x = I1 - 3, e = std::exp(p_.C2 * x * x);
  InvariantDerivatives d;
  d.W = 0.5 * p_.C0 * x + 0.5 * p_.C1 * std::expm1(p_.C2 * x * x);
  d.W1 = 0.5 * p_.C0 + p_.C1 * p_.C2 * x * e;
  d.W11 = p_.C1 * p_.C2 * e * (1 + 2 * p_.C2 * x * x);
  return d;
}

InvariantDerivatives ModifiedHgoEnergy::evaluate(double I1, double I4) const {
  InvariantDerivatives d;
  // Isotropic part C10 (e^{C01 (Ī1 − 3)} − 1).
  const double ei = std::exp(p_.C01 * (I1 - 3));
  d.W = p_.C10 * std::expm1(p_.C01 * (I1 - 3));
  d.W1 = p_.C10 * p_.C01 * ei;
  d.W11 = p_.C10 * p_.C01 * p_.C01 * ei;
  // Fiber part k1/(2 k2) (e^{k2 E²} − 1) with E = κ (Ī1 − 3) + (1 − 3κ)(Ī4 − 1), for E > 0:
  // dW/dE = k1 E e^{k2 E²}, d²W/dE² = k1 (1 + 2 k2 E²) e^{k2 E²}.
  const double a = p_.kappa, b = 1 - 3 * p_.kappa;
  const double E = a * (I1 - 3) + b * (I4 - 1);
  if (E > 0 && p_.k1 > 0 && p_.k2 > 0) {
    const double ef = std::exp(p_.k2 * E * E);
    const double WE = p_.k1 * E * ef, WEE = p_.k1 * (1 + 2 * p_.k2 * E * E) * ef;
    d.W += p_.k1 / (2 * p_.k2) * std::expm1(p_.k2 * E * E);
    d.W1 += a * WE;
    d.W4 += b * WE;
    d.W11 += a * a * WEE;
    d.W14 += a * b * WEE;
    d.W44 += b * b * WEE;
  }
  return d;
}

InvariantMembraneLaw::InvariantMembraneLaw(std::shared_ptr<const IsochoricEnergy> energy, double D)
    : energy_(std::move(energy)), D_(D) {}

namespace {

// dc/dÊ = diag(2, 2, 1).
const Voigt kVoigtScale(2, 2, 1);

// det C > 0 for every orientation-preserving in-plane deformation; the floor only keeps a
// crushed triangle from dividing by zero (its energy is then huge, and the step is rejected).
constexpr double kMinDet = 1e-6;

}  // namespace

InvariantMembraneLaw::Evaluation InvariantMembraneLaw::incompressible(double C11, double C22, double C12,
                                                                      bool with_hessian) const {
  const double d = std::max(C11 * C22 - C12 * C12, kMinDet);
  const Voigt dd(C22, C11, -2 * C12);
  Mat3 d2d;
  d2d << 0, 1, 0, 1, 0, 0, 0, 0, -2;
  // Ī1 = C11 + C22 + 1/d: d(1/d) = −dd/d², d²(1/d) = 2 dd ddᵀ/d³ − d2d/d².
  const double I1 = C11 + C22 + 1 / d, I4 = C11;
  const Voigt dI1 = Voigt(1, 1, 0) - dd / (d * d);
  const Voigt dI4(1, 0, 0);
  const InvariantDerivatives w = energy_->evaluate(I1, I4);
  Evaluation ev;
  ev.W = w.W;
  ev.C33 = 1 / d;
  ev.gradient = w.W1 * dI1 + w.W4 * dI4;
  if (with_hessian) {
    const Mat3 d2I1 = 2 * dd * dd.transpose() / (d * d * d) - d2d / (d * d);
    ev.hessian = w.W11 * dI1 * dI1.transpose() + w.W14 * (dI1 * dI4.transpose() + dI4 * dI1.transpose()) +
                 w.W44 * dI4 * dI4.transpose() + w.W1 * d2I1;
  }
  return ev;
}

InvariantMembraneLaw::Evaluation InvariantMembraneLaw::compressible(double C11, double C22, double C12,
                                                                    bool with_hessian) const {
  using Vec4 = Eigen::Vector4d;
  using Mat4 = Eigen::Matrix4d;
  // Variables x = (C11, C22, C12, t), t = C33.
  const double d = std::max(C11 * C22 - C12 * C12, kMinDet);
  const Vec4 dd(C22, C11, -2 * C12, 0);
  Mat4 d2d = Mat4::Zero();
  d2d(0, 1) = d2d(1, 0) = 1;
  d2d(2, 2) = -2;
  const Vec4 et(0, 0, 0, 1), e1(1, 0, 0, 0), ds(1, 1, 0, 1);
  struct Point {
    double W, g_t, h_tt;
    Vec4 g;
    Mat4 H;
  };
  auto at = [&](double t) {
    // P = d t = J²; f = P^(−1/3) = J^(−2/3); Ī1 = f (C11 + C22 + t); Ī4 = f C11.
    const double P = d * t;
    const Vec4 dP = t * dd + d * et;
    const Mat4 d2P = t * d2d + dd * et.transpose() + et * dd.transpose();
    const double f = std::cbrt(1 / P), J = std::sqrt(P);
    const Vec4 df = -f / (3 * P) * dP;
    const Mat4 d2f = 4 * f / (9 * P * P) * dP * dP.transpose() - f / (3 * P) * d2P;
    const Vec4 dJ = 0.5 / J * dP;
    const Mat4 d2J = -0.25 / (J * P) * dP * dP.transpose() + 0.5 / J * d2P;
    const double s = C11 + C22 + t;
    const double I1 = f * s, I4 = f * C11;
    const Vec4 dI1 = s * df + f * ds, dI4 = C11 * df + f * e1;
    const Mat4 d2I1 = s * d2f + df * ds.transpose() + ds * df.transpose();
    const Mat4 d2I4 = C11 * d2f + df * e1.transpose() + e1 * df.transpose();
    const InvariantDerivatives w = energy_->evaluate(I1, I4);
    const double U = (J - 1) * (J - 1) / D_, U1 = 2 * (J - 1) / D_, U11 = 2 / D_;
    Point p;
    p.W = w.W + U;
    p.g = w.W1 * dI1 + w.W4 * dI4 + U1 * dJ;
    p.H = w.W11 * dI1 * dI1.transpose() + w.W14 * (dI1 * dI4.transpose() + dI4 * dI1.transpose()) +
          w.W44 * dI4 * dI4.transpose() + w.W1 * d2I1 + w.W4 * d2I4 + U11 * dJ * dJ.transpose() + U1 * d2J;
    p.g_t = p.g[3];
    p.h_tt = p.H(3, 3);
    return p;
  };
  // S33 = 2 ∂W/∂t tends to −∞ as t → 0 (Ī1 grows without bound) and to +∞ as t → ∞ (the
  // volumetric term), so a root exists; Newton from the incompressible guess, kept inside
  // the bracket it builds, with bisection where Newton leaves it.
  double t = 1 / d, lo = 0, hi = std::numeric_limits<double>::infinity();
  Point p = at(t);
  for (int it = 0; it < 100; ++it) {
    if (p.g_t < 0) lo = t;
    else hi = t;
    double next = p.h_tt > 0 ? t - p.g_t / p.h_tt : -1;
    if (!(next > lo && next < hi)) next = std::isfinite(hi) ? 0.5 * (lo + hi) : 2 * t;
    const bool converged = std::abs(next - t) <= 1e-14 * t;
    t = next;
    p = at(t);
    if (converged || p.g_t == 0) break;
  }
  Evaluation ev;
  ev.W = p.W;
  ev.C33 = t;
  ev.gradient = p.g.head<3>();
  if (with_hessian) {
    const Vec4 h = p.H.col(3);
    ev.hessian = p.H.topLeftCorner<3, 3>() - h.head<3>() * h.head<3>().transpose() / p.h_tt;
  }
  return ev;
}

InvariantMembraneLaw::Evaluation InvariantMembraneLaw::evaluate(const Voigt& E, bool with_hessian) const {
  const double C11 = 1 + 2 * E[0], C22 = 1 + 2 * E[1], C12 = E[2];
  return D_ > 0 ? compressible(C11, C22, C12, with_hessian) : incompressible(C11, C22, C12, with_hessian);
}

double InvariantMembraneLaw::energy(const Voigt& E) const { return evaluate(E, false).W; }

Voigt InvariantMembraneLaw::stress(const Voigt& E) const {
  return kVoigtScale.cwiseProduct(evaluate(E, false).gradient);
}

Mat3 InvariantMembraneLaw::tangent(const Voigt& E) const {
  return kVoigtScale.asDiagonal() * evaluate(E, true).hessian * kVoigtScale.asDiagonal();
}

void InvariantMembraneLaw::stress_and_tangent(const Voigt& E, Voigt& S, Mat3& D) const {
  const Evaluation ev = evaluate(E, true);
  S = kVoigtScale.cwiseProduct(ev.gradient);
  D = kVoigtScale.asDiagonal() * ev.hessian * kVoigtScale.asDiagonal();
}

double InvariantMembraneLaw::thickness_stretch_squared(const Voigt& E) const { return evaluate(E, false).C33; }

std::shared_ptr<const MaterialLaw> make_isotropic_exponential_law(const IsotropicExponentialParameters& p, bool compressible) {
  return std::make_shared<InvariantMembraneLaw>(std::make_shared<IsotropicExponentialEnergy>(p), compressible ? p.D : 0.0);
}

std::shared_ptr<const MaterialLaw> make_modified_hgo_law(const ModifiedHgoParameters& p, bool compressible) {
  return std::make_shared<InvariantMembraneLaw>(std::make_shared<ModifiedHgoEnergy>(p), compressible ? p.D : 0.0);
}

}  // namespace valve
