#pragma once
// Virtual strain markers of the seed's biaxial test (3.2.2.5): four markers at the corners
// of a square (1.5 mm side) at the centre of the patch with sides along the fiber and
// cross-fiber directions, each located by barycentric coordinates in its rest triangle.
// The Green strain in material axes comes from the affine map that best fits the four
// marker positions; the applied Lagrangian stress is converted to second Piola-Kirchhoff
// stress with that deformation (S = F⁻¹ P), and the constitutive law is inverted at that
// stress to give the strain the law predicts. Planar (xy) patches only.
#include <vector>

#include "valve/analysis/leaflet_metrics.hpp"
#include "valve/material/material_law.hpp"
#include "valve/mesh/tri_mesh.hpp"

namespace valve {

class StrainMarkers {
 public:
  /// Markers around `centre` (default: the patch centroid) with the fiber direction of the
  /// triangle under the centre.
  StrainMarkers(const TriMesh& mesh, double side);
  /// Deformation gradient (2x2, reference xy -> current xy) fitted to the markers at x.
  Mat2 deformation_gradient(const VecX& x) const;
  /// Green strain in material axes (E11, E22, γ12 = 2 E12).
  Eigen::Vector3d green_strain(const VecX& x) const;
  /// Second Piola-Kirchhoff stress in material axes (S11, S22, S12) for the Lagrangian
  /// normal stresses Px (on ±x edges) and Py (on ±y edges) at deformation x.
  Eigen::Vector3d pk2_stress(const VecX& x, double Px, double Py) const;
  const Mat2& material_axes() const { return Q_; }  // columns: fiber, cross-fiber (xy)

 private:
  const TriMesh& mesh_;
  std::vector<SurfacePoint> markers_;
  Eigen::Matrix<double, 2, 4> rest_;  // marker rest positions relative to their centroid
  Mat2 Q_;
};

/// One strain component of the final increment against the law.
struct StrainComparison {
  std::string component;  // E11 | E22 | E12 (material axes, E12 the tensor shear)
  double simulated, law, error_pct;
};
/// Compares marker strains with the law at the marker stress. Components whose law value
/// is below `min_strain` in magnitude (e.g. shear with fibers along x) are left out.
std::vector<StrainComparison> compare_with_law(const Eigen::Vector3d& E_sim, const Eigen::Vector3d& S,
                                               const MaterialLaw& law, double min_strain = 1e-6);

}  // namespace valve
