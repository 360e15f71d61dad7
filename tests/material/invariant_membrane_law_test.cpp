// The two laws of the Texas TriValve deck's subroutine (Leaflet_Material.f) as membranes:
// stress and tangent against finite differences of the energy, closed forms of the
// incompressible sheet, the small-strain limit of the compressible one, and its plane-stress
// condition S33 = 0 checked on the 3-D energy written out here independently.
#include <catch2/catch.hpp>
#include <cmath>

#include "law_derivatives.hpp"
#include "valve/material/invariant_membrane_law.hpp"

using namespace valve;

namespace {
// Healthy_QuasiStatic.inp, VUANISO_ISO_Anterior_Leaflet and _Septal_Leaflet: C0, D, C1, C2.
const IsotropicExponentialParameters kAnterior{0.001, 20.066890, 0.000124, 4.568202};
const IsotropicExponentialParameters kSeptal{0.001, 20.066890, 0.000191, 17.751490};
// A modified HGO law with fibers and dispersion (C10, D, k1, k2, κ, C01).
const ModifiedHgoParameters kHgo{0.001, 20.0, 0.0002, 10.0, 0.1, 20.0};
const Voigt kStrains[] = {Voigt(0.05, 0.08, 0.02), Voigt(0.1, -0.03, -0.05), Voigt(-0.02, 0.06, 0.1)};

// The 3-D energy of the isotropic exponential law at in-plane C (fiber frame) and C33 = t,
// written from the subroutine's formula: Ī1 = J^(−2/3)(C11 + C22 + t), J² = det C · t.
double iso_energy_3d(const IsotropicExponentialParameters& p, const Voigt& E, double t) {
  const double C11 = 1 + 2 * E[0], C22 = 1 + 2 * E[1], C12 = E[2];
  const double J = std::sqrt((C11 * C22 - C12 * C12) * t);
  const double I1 = std::pow(J, -2.0 / 3) * (C11 + C22 + t), x = I1 - 3;
  return 0.5 * p.C0 * x + 0.5 * p.C1 * (std::exp(p.C2 * x * x) - 1) + (J - 1) * (J - 1) / p.D;
}
}  // namespace

TEST_CASE("the deck's laws: stress is the gradient of W and the tangent its Hessian", "[material][fd]") {
  for (bool compressible : {false, true}) {
    for (const auto& p : {kAnterior, kSeptal}) {
      const auto law = make_isotropic_exponential_law(p, compressible);
      for (const Voigt& E : kStrains) check_law_derivatives(*law, E, 1e-12);
    }
    const auto hgo = make_modified_hgo_law(kHgo, compressible);
    for (const Voigt& E : kStrains) check_law_derivatives(*hgo, E, 1e-12);
  }
}

TEST_CASE("isotropic exponential law as an incompressible membrane: closed forms", "[material]") {
  const auto law = make_isotropic_exponential_law(kAnterior, false);
  // At rest W1 = C0/2, so the shear modulus is μ = 2 W1 = C0 and the incompressible
  // plane-stress tangent is 2μ [[2, 1, 0], [1, 2, 0], [0, 0, 1/2]] (Voigt γ12).
  const double mu = kAnterior.C0;
  const Mat3 D0 = law->tangent(Voigt::Zero());
  CHECK(D0(0, 0) == Approx(4 * mu));
  CHECK(D0(0, 1) == Approx(2 * mu));
  CHECK(D0(1, 1) == Approx(4 * mu));
  CHECK(D0(2, 2) == Approx(mu));
  CHECK(law->stress(Voigt::Zero()).norm() == Approx(0).margin(1e-15));
  // Equibiaxial stretch λ: I1 = 2λ² + λ⁻⁴, S11 = 2 W1(I1)(1 − λ⁻⁶) with
  // W1 = C0/2 + C1 C2 (I1 − 3) exp(C2 (I1 − 3)²) (the subroutine's ui1).
  const double lambda = 1.25, E = 0.5 * (lambda * lambda - 1);
  const double I1 = 2 * lambda * lambda + std::pow(lambda, -4), x = I1 - 3;
  const double W1 = 0.5 * kAnterior.C0 + kAnterior.C1 * kAnterior.C2 * x * std::exp(kAnterior.C2 * x * x);
  const Voigt S = law->stress(Voigt(E, E, 0));
  CHECK(S[0] == Approx(2 * W1 * (1 - std::pow(lambda, -6))).epsilon(1e-12));
  CHECK(S[1] == Approx(S[0]).epsilon(1e-12));
  CHECK(S[2] == Approx(0).margin(1e-15));
  CHECK(law->energy(Voigt(E, E, 0)) ==
        Approx(0.5 * kAnterior.C0 * x + 0.5 * kAnterior.C1 * std::expm1(kAnterior.C2 * x * x)).epsilon(1e-12));
}

TEST_CASE("compressible plane stress: S33 = 0 on the 3-D energy, and the small-strain moduli", "[material]") {
  const auto law = make_isotropic_exponential_law(kAnterior, true);
  const auto& membrane = dynamic_cast<const InvariantMembraneLaw&>(*law);
  for (const Voigt& E : kStrains) {
    const double t = membrane.thickness_stretch_squared(E), h = 1e-7 * t;
    // ∂W/∂t of the independent 3-D energy vanishes at the law's t (relative to its scale).
    const double dWdt = (iso_energy_3d(kAnterior, E, t + h) - iso_energy_3d(kAnterior, E, t - h)) / (2 * h);
    const double scale = (iso_energy_3d(kAnterior, E, 1.1 * t) - iso_energy_3d(kAnterior, E, 0.9 * t)) / (0.2 * t);
    CHECK(std::abs(dWdt) < 1e-6 * std::abs(scale) + 1e-12);
    CHECK(law->energy(E) == Approx(iso_energy_3d(kAnterior, E, t)).epsilon(1e-12));
  }
  // Small strain: an isotropic solid with μ = C0 and K = 2/D in plane stress,
  // Y = 9Kμ/(3K + μ), ν = (3K − 2μ)/(2(3K + μ)): D11 = Y/(1 − ν²), D12 = ν Y/(1 − ν²), D33 = μ.
  const double mu = kAnterior.C0, K = 2 / kAnterior.D;
  const double Y = 9 * K * mu / (3 * K + mu), nu = (3 * K - 2 * mu) / (2 * (3 * K + mu));
  const Mat3 D0 = law->tangent(Voigt::Zero());
  CHECK(D0(0, 0) == Approx(Y / (1 - nu * nu)).epsilon(1e-9));
  CHECK(D0(0, 1) == Approx(nu * Y / (1 - nu * nu)).epsilon(1e-9));
  CHECK(D0(2, 2) == Approx(mu).epsilon(1e-9));
  // A nearly incompressible sheet (D → 0) approaches the incompressible membrane.
  IsotropicExponentialParameters stiff = kAnterior;
  stiff.D = 1e-6;
  const Voigt E(0.08, 0.05, 0.03);
  const Voigt Sc = make_isotropic_exponential_law(stiff, true)->stress(E);
  const Voigt Si = make_isotropic_exponential_law(stiff, false)->stress(E);
  CHECK((Sc - Si).norm() < 1e-4 * Si.norm());
}

TEST_CASE("modified HGO: fibers along direction 1 carry tension only", "[material]") {
  // Isotropic part negligible, κ = 0: E = I4 − 1 = 2 E11 under uniaxial fiber strain with
  // incompressibility, S11 = 2 k1 E exp(k2 E²) + the (negligible) isotropic stress.
  const ModifiedHgoParameters p{1e-12, 0, 0.000124, 4.568202, 0.0, 1e-9};
  const auto law = make_modified_hgo_law(p, false);
  const double E11 = 0.06, Ef = 2 * E11;
  const Voigt S = law->stress(Voigt(E11, 0, 0));
  CHECK(S[0] == Approx(2 * p.k1 * Ef * std::exp(p.k2 * Ef * Ef)).epsilon(1e-6));
  CHECK(std::abs(S[1]) < 1e-12);
  CHECK(std::abs(law->stress(Voigt(-0.05, 0, 0))[0]) < 1e-12);
  CHECK(law->energy(Voigt(-0.05, 0, 0)) == Approx(0).margin(1e-15));
  // With the isotropic part on, the fiber direction is the stiffer one.
  const auto hgo = make_modified_hgo_law(kHgo, false);
  CHECK(hgo->stress(Voigt(0.08, 0, 0))[0] > hgo->stress(Voigt(0, 0.08, 0))[1]);
}

TEST_CASE("modified HGO with κ = 1/3 is isotropic", "[material]") {
  // E = (Ī1 − 3)/3 has no Ī4 term: swapping the in-plane axes swaps the stresses.
  ModifiedHgoParameters p = kHgo;
  p.kappa = 1.0 / 3;
  for (bool compressible : {false, true}) {
    const auto law = make_modified_hgo_law(p, compressible);
    const Voigt a = law->stress(Voigt(0.07, 0.02, 0.01)), b = law->stress(Voigt(0.02, 0.07, 0.01));
    CHECK(a[0] == Approx(b[1]).epsilon(1e-12));
    CHECK(a[1] == Approx(b[0]).epsilon(1e-12));
  }
}
