#include <catch2/catch.hpp>
#include <cmath>

#include "law_derivatives.hpp"
#include "valve/material/hgo_law.hpp"

using namespace valve;

namespace {
// Texas TriValve 1.1, anterior leaflet (*anisotropic hyperelastic property line).
const HgoParameters kAnterior{0.001, 20.066890, 0.000124, 4.568202, 0.0};
}  // namespace

TEST_CASE("HGO stress is the gradient of W and the tangent its Hessian", "[material][fd]") {
  for (const HgoParameters p : {kAnterior, HgoParameters{0.001, 20.0, 0.0002, 10.0, 0.1}}) {
    const HgoLaw law(p);
    for (const Voigt E : {Voigt(0.05, 0.08, 0.02), Voigt(0.1, -0.03, -0.05), Voigt(-0.02, 0.06, 0.1)})
      check_law_derivatives(law, E, 1e-12);
  }
}

TEST_CASE("HGO isotropic part is an incompressible plane-stress membrane", "[material]") {
  // Without fibers W = C10 (exp(C01 (I1 − 3)) − 1) has W1 = C10 C01 at rest, i.e. the
  // neo-Hookean shear modulus μ = 2 W1. Small strain, plane stress, incompressible:
  // σ11 = 2μ (2 ε11 + ε22), σ12 = 2μ ε12 = μ γ12.
  const HgoParameters p{0.001, 20.0, 0.0, 0.0, 0.0};
  const HgoLaw law(p);
  const double mu = 2 * p.C10 * p.C01;
  const Mat3 D0 = law.tangent(Voigt::Zero());
  CHECK(D0(0, 0) == Approx(4 * mu));
  CHECK(D0(0, 1) == Approx(2 * mu));
  CHECK(D0(1, 1) == Approx(4 * mu));
  CHECK(D0(2, 2) == Approx(mu));
  CHECK(law.stress(Voigt::Zero()).norm() == Approx(0).margin(1e-15));
  // Equibiaxial stretch λ: I1 = 2λ² + λ⁻⁴ and S11 = 2 W1(I1) (1 − λ⁻⁶), the exponential
  // neo-Hookean membrane written out by hand.
  const double lambda = 1.12, E = 0.5 * (lambda * lambda - 1);
  const double I1 = 2 * lambda * lambda + std::pow(lambda, -4);
  const double W1 = p.C10 * p.C01 * std::exp(p.C01 * (I1 - 3));
  const Voigt S = law.stress(Voigt(E, E, 0));
  CHECK(S[0] == Approx(2 * W1 * (1 - std::pow(lambda, -6))).epsilon(1e-12));
  CHECK(S[1] == Approx(S[0]).epsilon(1e-12));
  CHECK(S[2] == Approx(0).margin(1e-15));
}

TEST_CASE("HGO fibers carry tension only, along direction 1", "[material]") {
  // Isotropic part switched off (C01 → tiny, C10 tiny) to isolate the fiber term with κ = 0:
  // Ef = I4 − 1 = 2 E11, S11 = 2 k1 Ef exp(k2 Ef²), S22 = 0.
  const HgoParameters p{1e-12, 1e-9, 0.000124, 4.568202, 0.0};
  const HgoLaw law(p);
  const double E11 = 0.06, Ef = 2 * E11;
  const Voigt S = law.stress(Voigt(E11, 0, 0));
  CHECK(S[0] == Approx(2 * p.k1 * Ef * std::exp(p.k2 * Ef * Ef)).epsilon(1e-6));
  CHECK(std::abs(S[1]) < 1e-12);
  // Compressed fibers: no fiber stress, and no energy.
  CHECK(std::abs(law.stress(Voigt(-0.05, 0, 0))[0]) < 1e-12);
  CHECK(law.energy(Voigt(-0.05, 0, 0)) == Approx(0).margin(1e-15));
  // The fiber direction is the stiffer one.
  const HgoLaw anterior(kAnterior);
  CHECK(anterior.stress(Voigt(0.08, 0, 0))[0] > anterior.stress(Voigt(0, 0.08, 0))[1]);
}
