#include <catch2/catch.hpp>

#include "valve/material/bilinear_fit.hpp"
#include "valve/material/material_law.hpp"
#include "law_derivatives.hpp"

using namespace valve;

namespace {
const FungParameters kAortic{9.7e-6, 49.558, 5.2871, -3.124, 16.031, -0.004, -0.02};
const FungParameters kMitral{9e-6, 80, 23, -3, 16, 0, 0};
}  // namespace

TEST_CASE("Fung stress is the gradient of W and the tangent its Hessian", "[material][fd]") {
  const FungLaw law(kAortic);
  for (const Voigt E : {Voigt(0.1, 0.2, 0.05), Voigt(0.15, 0.4, -0.1), Voigt(-0.02, 0.1, 0.2)})
    check_law_derivatives(law, E, 1e-14);
}

TEST_CASE("Fung law matches Eq. 3.1-3.3 written out by hand", "[material]") {
  // Independent evaluation: S11 = c e^Q (A1 E11 + A3 E22 + A5 E12), E12 tensor shear.
  const FungLaw law(kAortic);
  const double E11 = 0.12, E22 = 0.3, E12 = 0.04;
  const auto& p = kAortic;
  const double Q = p.A1 * E11 * E11 + p.A2 * E22 * E22 + 2 * p.A3 * E11 * E22 + p.A4 * E12 * E12 +
                   2 * p.A5 * E11 * E12 + 2 * p.A6 * E22 * E12;
  const Voigt S = law.stress(Voigt(E11, E22, 2 * E12));
  CHECK(S[0] == Approx(p.c * std::exp(Q) * (p.A1 * E11 + p.A3 * E22 + p.A5 * E12)));
  CHECK(S[1] == Approx(p.c * std::exp(Q) * (p.A2 * E22 + p.A3 * E11 + p.A6 * E12)));
  CHECK(S[2] == Approx(0.5 * p.c * std::exp(Q) * (p.A4 * E12 + p.A5 * E11 + p.A6 * E22)));
  CHECK(law.energy(Voigt(E11, E22, 2 * E12)) == Approx(0.5 * p.c * (std::exp(Q) - 1)));
}

TEST_CASE("stress inversion recovers the strain", "[material]") {
  const FungLaw law(kMitral);
  const Voigt E0(0.12, 0.35, 0.05);
  Voigt E;
  REQUIRE(invert_stress(law, law.stress(E0), E));
  CHECK((E - E0).norm() < 1e-9);
}

TEST_CASE("bilinear fit of the mitral Fung law against seed Table 5.1", "[material][seed]") {
  // Table 5.1: fiber 0.011 / 2.3 MPa, λ* 1.13; cross-fiber 0.0033 / 0.76 MPa, λ* 1.33. The seed
  // does not say how it fitted; our least-squares fit of the equibiaxial S-E curves up to
  // 60 kPa reproduces m2 within 10 % and λ* within 0.02. m1, set by the toe of an exponential,
  // is ill-determined by any fit: ours is about twice the Table's, and is reported.
  const auto p = fit_bilinear_equibiaxial(FungLaw(kMitral));
  CHECK(p.fiber.m2 == Approx(2.3).epsilon(0.10));
  CHECK(p.cross.m2 == Approx(0.76).epsilon(0.10));
  CHECK(p.fiber.lambda_star == Approx(1.13).margin(0.02));
  CHECK(p.cross.lambda_star == Approx(1.33).margin(0.02));
  CHECK(p.fiber.m1 > 0.011 * 0.5);
  CHECK(p.fiber.m1 < 0.011 * 3);
  CHECK(p.cross.m1 < 0.0033 * 3);
  // The fiber direction is stiffer than the cross-fiber direction.
  CHECK(p.fiber.m2 > 2 * p.cross.m2);
}

TEST_CASE("bilinear fit is exact for a bilinear curve", "[material]") {
  SampledCurve c;
  for (int k = 1; k <= 200; ++k) {
    const double x = 0.3 * k / 200;
    c.x.push_back(x);
    c.y.push_back(x <= 0.1 ? 0.02 * x : 0.02 * 0.1 + 3.0 * (x - 0.1));
  }
  const auto f = fit_bilinear(c);
  CHECK(f[0] == Approx(0.02).epsilon(1e-3));
  CHECK(f[1] == Approx(3.0).epsilon(1e-4));
  CHECK(f[2] == Approx(0.1).epsilon(1e-3));
}
