#include "valve/material/bilinear_fit.hpp"

#include <cmath>

#include "valve/core/error.hpp"

namespace valve {
namespace {

// Sum of squared residuals and slopes for a fixed breakpoint xs.
double fit_fixed_break(const SampledCurve& c, double xs, double& m1, double& m2) {
  // Model y = m1 * a(x) + m2 * b(x), a = min(x, xs), b = max(x - xs, 0): linear in m1, m2.
  double saa = 0, sab = 0, sbb = 0, say = 0, sby = 0;
  for (size_t i = 0; i < c.x.size(); ++i) {
    const double a = std::min(c.x[i], xs), b = std::max(c.x[i] - xs, 0.0);
    saa += a * a;
    sab += a * b;
    sbb += b * b;
    say += a * c.y[i];
    sby += b * c.y[i];
  }
  const double det = saa * sbb - sab * sab;
  if (std::abs(det) < 1e-300 * std::max(1.0, saa * sbb)) {
    m1 = say / saa;
    m2 = m1;
  } else {
    m1 = (say * sbb - sby * sab) / det;
    m2 = (saa * sby - sab * say) / det;
  }
  double r2 = 0;
  for (size_t i = 0; i < c.x.size(); ++i) {
    const double a = std::min(c.x[i], xs), b = std::max(c.x[i] - xs, 0.0);
    const double r = c.y[i] - m1 * a - m2 * b;
    r2 += r * r;
  }
  return r2;
}

}  // namespace

std::vector<SampledCurve> equibiaxial_curves(const MaterialLaw& law, const BilinearFitOptions& opt) {
  if (opt.max_stress <= 0 || opt.samples < 4)
    throw InputError("bilinear fit: expected max_stress > 0 and samples >= 4");
  // Trace the curve densely in stress (the law is inverted stress -> strain), then
  // resample evenly in strain so the toe region weighs as much as the stiff region.
  const int dense = 20 * opt.samples;
  std::vector<SampledCurve> traced(2), out(2);
  for (int k = 1; k <= dense; ++k) {
    const double s = opt.max_stress * k / dense;
    Voigt E;
    if (!invert_stress(law, Voigt(s, s, 0), E))
      throw InputError("bilinear fit: the material law cannot reach the equibiaxial stress " +
                       std::to_string(s) + " MPa");
    for (int d = 0; d < 2; ++d) {
      const double lambda = std::sqrt(1 + 2 * E[d]);
      if (opt.measure == FitMeasure::nominal_vs_stretch) {
        traced[d].x.push_back(lambda - 1);
        traced[d].y.push_back(lambda * s);  // P = F S for a diagonal stretch
      } else {
        traced[d].x.push_back(E[d]);
        traced[d].y.push_back(s);
      }
    }
  }
  for (int d = 0; d < 2; ++d) {
    const auto& t = traced[d];
    if (t.x.front() <= 0 || !(t.x.back() > t.x.front()))
      throw InputError("bilinear fit: the equibiaxial curve is not monotone in direction " +
                       std::to_string(d + 1));
    size_t i = 0;
    for (int k = 1; k <= opt.samples; ++k) {
      const double x = t.x.back() * k / opt.samples;
      while (i + 1 < t.x.size() && t.x[i + 1] < x) ++i;
      double y;
      if (x <= t.x.front()) {
        y = t.y.front() * x / t.x.front();
      } else {
        const double w = (x - t.x[i]) / (t.x[i + 1] - t.x[i]);
        y = t.y[i] + w * (t.y[i + 1] - t.y[i]);
      }
      out[d].x.push_back(x);
      out[d].y.push_back(y);
    }
  }
  return out;
}

Eigen::Vector3d fit_bilinear(const SampledCurve& c) {
  double lo = c.x.front(), hi = c.x.back();
  const double g = 0.5 * (std::sqrt(5.0) - 1);
  double m1, m2;
  // The residual as a function of the breakpoint is piecewise smooth; scan, then refine.
  const int scan = 200;
  double best = lo, best_r = 1e300;
  for (int i = 0; i <= scan; ++i) {
    const double xs = lo + (hi - lo) * i / scan;
    const double r = fit_fixed_break(c, xs, m1, m2);
    if (r < best_r) best_r = r, best = xs;
  }
  double a = std::max(lo, best - (hi - lo) / scan), b = std::min(hi, best + (hi - lo) / scan);
  double x1 = b - g * (b - a), x2 = a + g * (b - a);
  double f1 = fit_fixed_break(c, x1, m1, m2), f2 = fit_fixed_break(c, x2, m1, m2);
  for (int it = 0; it < 100; ++it) {
    if (f1 < f2) {
      b = x2, x2 = x1, f2 = f1, x1 = b - g * (b - a), f1 = fit_fixed_break(c, x1, m1, m2);
    } else {
      a = x1, x1 = x2, f1 = f2, x2 = a + g * (b - a), f2 = fit_fixed_break(c, x2, m1, m2);
    }
  }
  const double xs = 0.5 * (a + b);
  fit_fixed_break(c, xs, m1, m2);
  return {m1, m2, xs};
}

BilinearParameters fit_bilinear_equibiaxial(const MaterialLaw& law, const BilinearFitOptions& opt) {
  const auto curves = equibiaxial_curves(law, opt);
  BilinearParameters p;
  BilinearCurve* dst[2] = {&p.fiber, &p.cross};
  for (int d = 0; d < 2; ++d) {
    const Eigen::Vector3d f = fit_bilinear(curves[d]);
    dst[d]->m1 = f[0];
    dst[d]->m2 = f[1];
    dst[d]->lambda_star =
        opt.measure == FitMeasure::nominal_vs_stretch ? 1 + f[2] : std::sqrt(1 + 2 * f[2]);
  }
  return p;
}

double bilinear_stress(const BilinearCurve& c, double lambda) {
  const double x = lambda - 1, xs = c.lambda_star - 1;
  return x <= xs ? c.m1 * x : c.m1 * xs + c.m2 * (x - xs);
}

}  // namespace valve
