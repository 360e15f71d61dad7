#pragma once
// Membrane laws from an energy in the isochoric invariants, the form of Abaqus's
// VUANISOHYPER_INV (formulation=invariant) as the Texas TriValve deck's subroutine
// Leaflet_Material.f writes it:
//   W = W̄(Ī1, Ī4) + U(J),   Ī1 = J^(−2/3) I1,   Ī4 = J^(−2/3) a0·C a0,   U = (J − 1)² / D.
// Two energies W̄, each with the subroutine's own property order:
//   VUANISO_ISO, props (C0, D, C1, C2) — isotropic exponential in Ī1:
//     W̄ = C0/2 (Ī1 − 3) + C1/2 (exp(C2 (Ī1 − 3)²) − 1)
//   VUANISO_HGO, props (C10, D, k1, k2, κ, C01) — modified Holzapfel–Gasser–Ogden:
//     W̄ = C10 (exp(C01 (Ī1 − 3)) − 1) + k1/(2 k2) (exp(k2 <E>²) − 1),
//     E = κ (Ī1 − 3) + (1 − 3κ)(Ī4 − 1),  <x> = max(x, 0) (the fibers carry tension only).
//
// Plane stress of a sheet whose fiber frame has the in-plane right Cauchy–Green tensor
// C = I + 2E (direction 1 the fiber, so a0·C a0 = C11) and thickness stretch² C33 = t:
// * incompressible (D = 0): J = 1, so t = 1 / det C and Ī1 = C11 + C22 + 1/det C, Ī4 = C11;
//   the pressure that holds S33 = 0 is eliminated by writing W as a function of the in-plane
//   C alone (the standard reduction for incompressible membranes).
// * compressible (D > 0): t solves S33 = 2 ∂W/∂t = 0 (Newton, bracketed); with
//   J = sqrt(det C · t) the in-plane stress is the partial gradient at that t (envelope
//   theorem), and the tangent is condensed: H = H_cc − h_ct h_ctᵀ / H_tt.
// Voigt convention of material_law.hpp: Ê = (E11, E22, γ12), C11 = 1 + 2 E11, C22 = 1 + 2 E22,
// C12 = γ12; derivatives with respect to Ê are those with respect to (C11, C22, C12) scaled
// by diag(2, 2, 1).
#include <memory>

#include "valve/material/material_law.hpp"

namespace valve {

/// W̄ and its derivatives with respect to the isochoric invariants.
struct InvariantDerivatives {
  double W = 0, W1 = 0, W4 = 0, W11 = 0, W14 = 0, W44 = 0;
};

class IsochoricEnergy {
 public:
  virtual ~IsochoricEnergy() = default;
  virtual std::string name() const = 0;
  virtual InvariantDerivatives evaluate(double I1, double I4) const = 0;
};

/// VUANISO_ISO of Leaflet_Material.f, property line (C0, D, C1, C2).
struct IsotropicExponentialParameters {
  double C0 = 0;  // MPa
  double D = 0;   // 1/MPa (0: incompressible)
  double C1 = 0;  // MPa
  double C2 = 0;  // dimensionless
};

/// VUANISO_HGO of Leaflet_Material.f, property line (C10, D, k1, k2, κ, C01).
struct ModifiedHgoParameters {
  double C10 = 0;    // MPa
  double D = 0;      // 1/MPa (0: incompressible)
  double k1 = 0;     // MPa
  double k2 = 0;     // dimensionless
  double kappa = 0;  // fiber dispersion, 0 (aligned) .. 1/3 (isotropic)
  double C01 = 0;    // dimensionless exponent of the isotropic part
};

class IsotropicExponentialEnergy final : public IsochoricEnergy {
 public:
  explicit IsotropicExponentialEnergy(const IsotropicExponentialParameters& p) : p_(p) {}
  std::string name() const override { return "iso_exponential"; }
  InvariantDerivatives evaluate(double I1, double I4) const override;

 private:
  IsotropicExponentialParameters p_;
};

class ModifiedHgoEnergy final : public IsochoricEnergy {
 public:
  explicit ModifiedHgoEnergy(const ModifiedHgoParameters& p) : p_(p) {}
  std::string name() const override { return "hgo"; }
  InvariantDerivatives evaluate(double I1, double I4) const override;

 private:
  ModifiedHgoParameters p_;
};

class InvariantMembraneLaw final : public MaterialLaw {
 public:
  /// `D` (1/MPa) > 0 makes the sheet compressible with U = (J − 1)² / D; 0 keeps J = 1.
  InvariantMembraneLaw(std::shared_ptr<const IsochoricEnergy> energy, double D);
  std::string name() const override { return energy_->name() + (D_ > 0 ? "_compressible" : ""); }
  double energy(const Voigt& E) const override;
  Voigt stress(const Voigt& E) const override;
  Mat3 tangent(const Voigt& E) const override;
  void stress_and_tangent(const Voigt& E, Voigt& S, Mat3& D) const override;
  /// The squared thickness stretch C33 of the plane-stress state at E.
  double thickness_stretch_squared(const Voigt& E) const;
  bool compressible() const { return D_ > 0; }

 private:
  struct Evaluation {
    double W = 0, C33 = 1;
    Voigt gradient = Voigt::Zero();  // dW/d(C11, C22, C12)
    Mat3 hessian = Mat3::Zero();
  };
  Evaluation evaluate(const Voigt& E, bool with_hessian) const;
  Evaluation incompressible(double C11, double C22, double C12, bool with_hessian) const;
  Evaluation compressible(double C11, double C22, double C12, bool with_hessian) const;
  std::shared_ptr<const IsochoricEnergy> energy_;
  double D_ = 0;
};

/// The laws of the two subroutine branches; `compressible` false drops D (J = 1).
std::shared_ptr<const MaterialLaw> make_isotropic_exponential_law(const IsotropicExponentialParameters& p, bool compressible);
std::shared_ptr<const MaterialLaw> make_modified_hgo_law(const ModifiedHgoParameters& p, bool compressible);

}  // namespace valve
