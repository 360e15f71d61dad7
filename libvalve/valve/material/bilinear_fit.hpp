#pragma once
// Bilinear approximation of the equibiaxial stress-strain curves (seed 3.2.2.3,
// Fig. 3.2B): one segment of slope m1 through the origin, a second of slope m2 that
// meets it at the critical stretch λ*. The mass-spring model uses one fit for the fiber
// direction and one for the cross-fiber direction.
#include <vector>

#include "valve/material/material_law.hpp"

namespace valve {

struct BilinearCurve {
  double m1 = 0;           // MPa, slope below λ*
  double m2 = 0;           // MPa, slope above λ*
  double lambda_star = 1;  // critical stretch
};

struct BilinearParameters {
  BilinearCurve fiber, cross;
};

/// Which stress and strain measures the straight segments are fitted in.
/// The default, second Piola-Kirchhoff stress vs Green strain sampled evenly in strain up to
/// 60 kPa (the top of the seed's biaxial protocol), reproduces the seed's mitral Table 5.1
/// closely for m2 and λ* (see tests/material/bilinear_fit_test.cpp for the figures).
enum class FitMeasure {
  pk2_vs_green,        // second Piola-Kirchhoff vs Green strain (default)
  nominal_vs_stretch,  // first Piola-Kirchhoff (force per undeformed area) vs λ - 1
};

struct BilinearFitOptions {
  double max_stress = 0.06;  // MPa: top of the equibiaxial curve that is fitted
  int samples = 400;         // points on the curve, evenly spaced in strain
  FitMeasure measure = FitMeasure::pk2_vs_green;
};

/// One sampled equibiaxial curve: strain x and stress y in the chosen measures.
struct SampledCurve {
  std::vector<double> x, y;
};

/// Samples the equibiaxial loading (S11 = S22, S12 = 0) of `law` and returns the
/// fiber (index 0) and cross-fiber (index 1) curves.
std::vector<SampledCurve> equibiaxial_curves(const MaterialLaw& law, const BilinearFitOptions& opt);

/// Least-squares continuous bilinear fit y ≈ m1 x (x ≤ x*), m1 x* + m2 (x - x*) (x > x*)
/// with the breakpoint x* optimised by golden-section search over the sampled range.
/// Returns {m1, m2, x*}.
Eigen::Vector3d fit_bilinear(const SampledCurve& curve);

/// Fits both directions of `law`; λ* is returned as a stretch.
BilinearParameters fit_bilinear_equibiaxial(const MaterialLaw& law, const BilinearFitOptions& opt = {});

/// Stress of the bilinear curve at stretch λ in the fit's measure (for plots and tests).
double bilinear_stress(const BilinearCurve& c, double lambda);

}  // namespace valve
