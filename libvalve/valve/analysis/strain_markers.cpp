#include "valve/analysis/strain_markers.hpp"

#include <Eigen/Dense>
#include <cmath>

#include "valve/core/error.hpp"

namespace valve {

StrainMarkers::StrainMarkers(const TriMesh& mesh, double side) : mesh_(mesh) {
  const Vec3 centre = mesh.points.colwise().mean();
  const SurfacePoint c = closest_surface_point(mesh, centre);
  Vec3 f = mesh.fiber.row(c.triangle).transpose();
  f.z() = 0;
  if (f.norm() < 1e-12) throw InputError("strain markers: expected an in-plane fiber direction at the patch centre");
  f.normalize();
  const Vec3 g(-f.y(), f.x(), 0);
  Q_ << f.x(), g.x(), f.y(), g.y();
  const double h = side / 2;
  const Vec3 corners[4] = {centre - h * f - h * g, centre + h * f - h * g, centre + h * f + h * g, centre - h * f + h * g};
  for (int k = 0; k < 4; ++k) {
    markers_.push_back(closest_surface_point(mesh, corners[k]));
    rest_.col(k) = (corners[k] - centre).head<2>();
  }
}

Mat2 StrainMarkers::deformation_gradient(const VecX& x) const {
  Eigen::Matrix<double, 2, 4> cur;
  for (int k = 0; k < 4; ++k) cur.col(k) = evaluate(mesh_, markers_[k], x).head<2>();
  const Vec2 mean = cur.rowwise().mean();
  for (int k = 0; k < 4; ++k) cur.col(k) -= mean;
  // Least squares x_k - x̄ = F (X_k - X̄): F = (Σ x Xᵀ)(Σ X Xᵀ)⁻¹.
  return (cur * rest_.transpose()) * (rest_ * rest_.transpose()).inverse();
}

Eigen::Vector3d StrainMarkers::green_strain(const VecX& x) const {
  const Mat2 F = deformation_gradient(x);
  const Mat2 E = 0.5 * (F.transpose() * F - Mat2::Identity());
  const Mat2 Em = Q_.transpose() * E * Q_;
  return {Em(0, 0), Em(1, 1), 2 * Em(0, 1)};
}

Eigen::Vector3d StrainMarkers::pk2_stress(const VecX& x, double Px, double Py) const {
  const Mat2 F = deformation_gradient(x);
  Mat2 P;
  P << Px, 0, 0, Py;
  Mat2 S = F.inverse() * P;
  S = 0.5 * (S + S.transpose());  // equal up to the discretization error
  const Mat2 Sm = Q_.transpose() * S * Q_;
  return {Sm(0, 0), Sm(1, 1), Sm(0, 1)};
}

std::vector<StrainComparison> compare_with_law(const Eigen::Vector3d& E_sim, const Eigen::Vector3d& S,
                                               const MaterialLaw& law, double min_strain) {
  Voigt E_law;
  if (!invert_stress(law, S, E_law)) throw NumericalError("strain markers: the law cannot reach the marker stress");
  const char* names[3] = {"E11", "E22", "E12"};
  std::vector<StrainComparison> out;
  for (int k = 0; k < 3; ++k) {
    // Report the tensor shear E12 = γ/2 (the Voigt vectors carry γ).
    const double scale = k == 2 ? 0.5 : 1.0;
    const double sim = scale * E_sim[k], lw = scale * E_law[k];
    if (std::abs(lw) < min_strain) continue;
    out.push_back({names[k], sim, lw, 100.0 * std::abs(sim - lw) / std::abs(lw)});
  }
  return out;
}

}  // namespace valve
