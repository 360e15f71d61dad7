#pragma once
// Per-triangle membrane kinematics in material axes (fiber = axis 1), shared by the FE
// term and by output/analysis: the rest frame, the deformation gradient and Green strain.
#include <vector>

#include "valve/core/types.hpp"
#include "valve/mesh/tri_mesh.hpp"

namespace valve {

using Mat32 = Eigen::Matrix<double, 3, 2>;

/// Inverse of Dm = [ΔX21 ΔX31] written in the triangle's rest frame (e1 along the fiber
/// projected into the plane, e2 = n × e1); `area` receives the rest area.
Mat2 material_frame_inverse(const TriMesh& mesh, int t, double* area);

/// F = [Δx21 Δx31] Dm⁻¹ for triangle nodes `tri` at positions x (3N).
Mat32 deformation_gradient(const VecX& x, const Tri& tri, const Mat2& Dm_inv);

/// Green strain (E11, E22, γ12 = 2 E12) of F.
Eigen::Vector3d green_strain(const Mat32& F);

struct TriangleKinematics {
  Eigen::Vector3d green;  // Voigt, engineering shear
  double stretch_fiber, stretch_cross, area_ratio;
};
std::vector<TriangleKinematics> triangle_kinematics(const TriMesh& mesh, const VecX& x);

}  // namespace valve
