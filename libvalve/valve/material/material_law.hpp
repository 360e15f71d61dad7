#pragma once
// In-plane (membrane) constitutive laws W(E) in the material (fiber) frame.
//
// Voigt convention used throughout: strain Ê = (E11, E22, γ12) with γ12 = 2 E12 the
// engineering shear; stress Ŝ = (S11, S22, S12) with S12 the tensor component, so that
// dW = Ŝ · dÊ. Direction 1 is the fiber direction, 2 the cross-fiber direction.
#include <memory>
#include <string>

#include "valve/core/types.hpp"

namespace valve {

using Voigt = Eigen::Vector3d;

class MaterialLaw {
 public:
  virtual ~MaterialLaw() = default;
  virtual std::string name() const = 0;
  /// Strain energy per reference volume (MPa = mJ/mm^3).
  virtual double energy(const Voigt& E) const = 0;
  /// Second Piola-Kirchhoff stress Ŝ = dW/dÊ (MPa).
  virtual Voigt stress(const Voigt& E) const = 0;
  /// Tangent dŜ/dÊ (MPa), symmetric.
  virtual Mat3 tangent(const Voigt& E) const = 0;
  /// Stress and tangent together (laws may share work between them).
  virtual void stress_and_tangent(const Voigt& E, Voigt& S, Mat3& D) const {
    S = stress(E);
    D = tangent(E);
  }
};

/// Fung exponential law (seed Eq. 3.1-3.3):
///   W = c/2 (exp(Q) - 1),
///   Q = A1 E11² + A2 E22² + 2 A3 E11 E22 + A4 E12² + 2 A5 E11 E12 + 2 A6 E22 E12,
/// with E12 the tensor shear strain. With γ = 2 E12:
///   S11 = c e^Q (A1 E11 + A3 E22 + A5 E12)
///   S22 = c e^Q (A2 E22 + A3 E11 + A6 E12)
///   S12 = c/2 e^Q (A4 E12 + A5 E11 + A6 E22)
struct FungParameters {
  double c = 0;  // MPa
  double A1 = 0, A2 = 0, A3 = 0, A4 = 0, A5 = 0, A6 = 0;
};

class FungLaw final : public MaterialLaw {
 public:
  explicit FungLaw(const FungParameters& p) : p_(p) {}
  std::string name() const override { return "fung"; }
  double energy(const Voigt& E) const override;
  Voigt stress(const Voigt& E) const override;
  Mat3 tangent(const Voigt& E) const override;
  void stress_and_tangent(const Voigt& E, Voigt& S, Mat3& D) const override;
  const FungParameters& parameters() const { return p_; }

  /// Q and its gradient g = dQ/dÊ and (constant) Hessian, exposed for tests.
  double Q(const Voigt& E) const;
  Voigt dQ(const Voigt& E) const;
  Mat3 d2Q() const;

 private:
  FungParameters p_;
};

/// Solves Ŝ(Ê) = target for Ê by damped Newton from Ê = 0. Returns false if it does
/// not converge (the law is monotone for the presets, so this signals bad input).
bool invert_stress(const MaterialLaw& law, const Voigt& target, Voigt& E, double tol = 1e-12);

}  // namespace valve
