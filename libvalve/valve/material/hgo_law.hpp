#pragma once
// Exponential Holzapfel–Gasser–Ogden type law for an incompressible membrane, the leaflet
// law of the Texas TriValve deck (Mathur et al. 2022; its *anisotropic hyperelastic
// property lines C10, C01, k1, k2):
//   W = C10 (exp(C01 (I1 − 3)) − 1) + k1 / (2 k2) (exp(k2 <Ef>²) − 1),
//   Ef = κ (I1 − 3) + (1 − 3κ)(I4 − 1),   <x> = max(x, 0) (fibers carry tension only).
// Plane stress of an incompressible sheet: with the in-plane right Cauchy–Green tensor
// C = I + 2E (fiber frame), C33 = 1 / det C, so
//   I1 = C11 + C22 + 1 / (C11 C22 − C12²),   I4 = C11 (direction 1 is the fiber).
// The hydrostatic pressure that holds S33 = 0 is eliminated by writing W as a function of
// the in-plane C alone; S = dW/dÊ is then the in-plane second Piola–Kirchhoff stress of the
// plane-stress state (the standard reduction for incompressible membranes).
// Voigt convention of material_law.hpp: Ê = (E11, E22, γ12), so C11 = 1 + 2 E11,
// C22 = 1 + 2 E22, C12 = γ12; derivatives with respect to Ê are those with respect to
// c = (C11, C22, C12) scaled by diag(2, 2, 1).
#include "valve/material/material_law.hpp"

namespace valve {

struct HgoParameters {
  double C10 = 0;    // MPa
  double C01 = 0;    // dimensionless exponent of the isotropic part
  double k1 = 0;     // MPa
  double k2 = 0;     // dimensionless
  double kappa = 0;  // fiber dispersion, 0 (aligned) .. 1/3 (isotropic)
};

class HgoLaw final : public MaterialLaw {
 public:
  explicit HgoLaw(const HgoParameters& p) : p_(p) {}
  std::string name() const override { return "hgo"; }
  double energy(const Voigt& E) const override;
  Voigt stress(const Voigt& E) const override;
  Mat3 tangent(const Voigt& E) const override;
  void stress_and_tangent(const Voigt& E, Voigt& S, Mat3& D) const override;
  const HgoParameters& parameters() const { return p_; }

 private:
  /// The stress, and the tangent where D is given.
  void evaluate(const Voigt& E, Voigt& S, Mat3* D) const;
  HgoParameters p_;
};

}  // namespace valve
