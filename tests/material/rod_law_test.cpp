// Chord laws (rod_law.hpp): the linear rod, and Abaqus's Ogden law under uniaxial stress
// against the neo-Hookean closed form, finite differences of its energy, the lateral
// stress-free condition on the 3-D energy written out here, and the small-strain modulus.
#include <catch2/catch.hpp>
#include <cmath>

#include "valve/material/rod_law.hpp"

using namespace valve;

namespace {
// Healthy_QuasiStatic.inp *Hyperelastic, OGDEN, N=3: μ1, α1, μ2, α2, μ3, α3, D1, D2, D3.
OgdenParameters anterior_chordae() {
  OgdenParameters p;
  p.mu = {18.884147787615671, 22.682992286286954, 19.502933935159177};
  p.alpha = {98.253655062498183, 98.251894443391549, 98.253228660027887};
  p.D = {3.2760e-05, 0, 0};
  return p;
}
OgdenParameters septal_chordae() {
  OgdenParameters p;
  p.mu = {33.7534784879460, 0.0000145962860, 0.0203430173299};
  p.alpha = {0.0001531670654, 0.0003488130193, 113.4473866780919};
  p.D = {5.9237e-05, 0, 0};
  return p;
}

// The Ogden energy of principal stretches (λ, μ, μ), from Abaqus's definition; x^α − 1 as
// expm1(α ln x), which the septal chordae's α ~ 1e-4 needs.
double ogden_3d(const OgdenParameters& p, double l, double m) {
  const double J = l * m * m, lnf = -std::log(J) / 3;
  double W = 0;
  for (int k = 0; k < p.terms; ++k)
    W += 2 * p.mu[k] / (p.alpha[k] * p.alpha[k]) *
         (std::expm1(p.alpha[k] * (lnf + std::log(l))) + 2 * std::expm1(p.alpha[k] * (lnf + std::log(m))));
  for (int k = 1; k <= p.terms; ++k)
    if (p.D[k - 1] > 0) W += std::pow(J - 1, 2 * k) / p.D[k - 1];
  return W;
}
}  // namespace

TEST_CASE("linear chord: P = E (λ - 1) in tension, nothing in compression", "[material][chordae]") {
  const LinearRodLaw law(40.0);
  CHECK(law.response(1.05).nominal_stress == Approx(2.0));
  CHECK(law.response(1.05).energy == Approx(0.5 * 40 * 0.0025));
  CHECK(law.response(1.05).stiffness == Approx(40.0));
  CHECK(law.response(0.9).nominal_stress == 0);
  CHECK(law.response(0.9).energy == 0);
}

TEST_CASE("Ogden N = 1, α = 2, incompressible is the neo-Hookean rod", "[material][chordae]") {
  // W = μ/2 (λ² + 2/λ − 3), P = μ (λ − λ⁻²), dP/dλ = μ (1 + 2 λ⁻³).
  OgdenParameters p;
  p.terms = 1;
  p.mu = {0.5, 0, 0};
  p.alpha = {2, 0, 0};
  const OgdenRodLaw law(p);
  for (double l : {1.01, 1.2, 1.7}) {
    CHECK(law.response(l).energy == Approx(0.25 * (l * l + 2 / l - 3)).epsilon(1e-12));
    CHECK(law.response(l).nominal_stress == Approx(0.5 * (l - 1 / (l * l))).epsilon(1e-12));
    CHECK(law.response(l).stiffness == Approx(0.5 * (1 + 2 / (l * l * l))).epsilon(1e-12));
    CHECK(law.lateral_stretch(l) == Approx(1 / std::sqrt(l)).epsilon(1e-12));
  }
  CHECK(law.response(0.95).nominal_stress == 0);
}

TEST_CASE("the deck's Ogden chords: P = dW/dλ, stiffness = dP/dλ, lateral stress free", "[material][chordae][fd]") {
  for (bool compressible : {true, false}) {
    for (OgdenParameters p : {anterior_chordae(), septal_chordae()}) {
      if (!compressible) p.D = {0, 0, 0};
      const OgdenRodLaw law(p);
      for (double l : {1.002, 1.01, 1.03}) {
        const double h = 1e-6;  // the truncation error of α ≈ 113 and the rounding of α ≈ 1e-4 both below 1e-6
        const RodResponse r = law.response(l);
        const double P_fd = (law.response(l + h).energy - law.response(l - h).energy) / (2 * h);
        const double K_fd = (law.response(l + h).nominal_stress - law.response(l - h).nominal_stress) / (2 * h);
        CHECK(r.nominal_stress == Approx(P_fd).epsilon(1e-6));
        CHECK(r.stiffness == Approx(K_fd).epsilon(1e-5));
        // The 3-D energy at (λ, μ, μ) has the same value; compressible, it is least at the law's
        // lateral stretch μ (lateral stress free), which the incompressible law fixes at λ^(−1/2).
        INFO("compressible " << compressible << ", stretch " << l);
        const double m = law.lateral_stretch(l);
        // 1e-6: a rounding e of ln J costs 2μe/α, 2e-7 of W, in the α ~ 1e-4 terms of the reference.
        CHECK(r.energy == Approx(ogden_3d(p, l, m)).epsilon(1e-6));
        if (compressible)
          for (double dm : {-1e-4, -1e-6, 1e-6, 1e-4}) CHECK(ogden_3d(p, l, m * (1 + dm)) > ogden_3d(p, l, m));
        else
          CHECK(m == Approx(1 / std::sqrt(l)).epsilon(1e-14));
      }
    }
  }
}

TEST_CASE("Ogden chords: the small-strain Young's modulus is 9Kμ0/(3K + μ0)", "[material][chordae]") {
  for (const OgdenParameters& p : {anterior_chordae(), septal_chordae()}) {
    const OgdenRodLaw law(p);
    double mu0 = 0;
    for (double m : p.mu) mu0 += m;
    const double K = 2 / p.D[0], Y = 9 * K * mu0 / (3 * K + mu0);
    CHECK(law.initial_youngs_modulus() == Approx(Y));
    const double e = 1e-6;
    CHECK(law.response(1 + e).nominal_stress / e == Approx(Y).epsilon(1e-3));
  }
}
