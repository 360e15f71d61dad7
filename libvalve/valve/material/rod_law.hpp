#pragma once
// Uniaxial laws of a chord (a rod under uniaxial stress that carries tension only), as a
// strain energy W(λ) per reference volume of the axial stretch λ = L / L0, its nominal
// (first Piola–Kirchhoff) stress P = dW/dλ and stiffness dP/dλ. A rod of reference section
// A0 pulls with T = A0 P(λ) and stores A0 L0 W(λ). For λ <= 1 all three are 0: a slack chord
// never pushes a leaflet.
#include <array>
#include <memory>
#include <string>

namespace valve {

struct RodResponse {
  double energy = 0;          // W, MPa
  double nominal_stress = 0;  // P = dW/dλ, MPa
  double stiffness = 0;       // dP/dλ, MPa
};

class RodLaw {
 public:
  virtual ~RodLaw() = default;
  virtual std::string name() const = 0;
  virtual RodResponse response(double stretch) const = 0;
};

/// Linear elastic in the engineering strain: W = E/2 (λ − 1)², P = E (λ − 1) (seed Table 5.1,
/// E = 40 MPa).
class LinearRodLaw final : public RodLaw {
 public:
  explicit LinearRodLaw(double youngs_modulus) : E_(youngs_modulus) {}
  std::string name() const override { return "linear"; }
  RodResponse response(double stretch) const override;
  double youngs_modulus() const { return E_; }

 private:
  double E_;
};

/// Abaqus's Ogden law (*Hyperelastic, OGDEN, N): in the deviatoric principal stretches
/// λ̄i = J^(−1/3) λi,
///   W = Σk 2 μk/αk² (λ̄1^αk + λ̄2^αk + λ̄3^αk − 3) + Σk (J − 1)^(2k) / Dk,
/// data line μ1, α1, …, μN, αN, D1, …, DN; D1 = 0 makes it incompressible (every Dk = 0 term
/// is left out). Under uniaxial stress the lateral stretches are equal, λ2 = λ3 = μ.
/// In a = ln λ, b = ln μ: J = e^(a + 2b), λ̄1 = e^(2u/3), λ̄2 = λ̄3 = e^(−u/3) with u = a − b, so
///   W(a, b) = W̄(u) + U(e^v),  v = a + 2b,
///   W̄(u) = Σ 2μk/αk² (e^(2αk u/3) + 2 e^(−αk u/3) − 3).
/// Incompressible: v = 0, u = 3a/2. Compressible: b solves the lateral stress-free condition
/// ∂W/∂b = 0 (Newton), and d²W/da² is condensed: W_aa − W_ab² / W_bb. Then
/// P = W_a / λ and dP/dλ = (W_aa − W_a) / λ².
struct OgdenParameters {
  std::array<double, 3> mu{0, 0, 0};     // MPa
  std::array<double, 3> alpha{0, 0, 0};  // dimensionless, non-zero where mu is
  std::array<double, 3> D{0, 0, 0};      // 1/MPa (D1 = 0: incompressible)
  int terms = 3;                         // N, 1..3
};

class OgdenRodLaw final : public RodLaw {
 public:
  explicit OgdenRodLaw(const OgdenParameters& p) : p_(p) {}
  std::string name() const override { return "ogden"; }
  RodResponse response(double stretch) const override;
  const OgdenParameters& parameters() const { return p_; }
  /// The lateral stretch μ of the uniaxial stress state at λ (λ^(−1/2) when incompressible).
  double lateral_stretch(double stretch) const;
  /// Initial Young's modulus: 3 Σ μk when incompressible (the small-strain limit).
  double initial_youngs_modulus() const;

 private:
  struct Log {
    double W = 0, Wa = 0, Waa = 0, b = 0;
  };
  Log solve(double a) const;
  OgdenParameters p_;
};

}  // namespace valve
