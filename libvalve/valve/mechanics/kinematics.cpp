#include "valve/mechanics/kinematics.hpp"

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <cmath>

#include "valve/core/error.hpp"

namespace valve {

Mat2 material_frame_inverse(const TriMesh& mesh, int t, double* area) {
  const Tri& tri = mesh.triangles[t];
  const Vec3 X1 = mesh.points.row(tri[0]), X2 = mesh.points.row(tri[1]), X3 = mesh.points.row(tri[2]);
  const Vec3 n = (X2 - X1).cross(X3 - X1).normalized();
  Vec3 e1 = mesh.fiber.rows() == mesh.num_triangles() ? Vec3(mesh.fiber.row(t).transpose()) : Vec3(X2 - X1);
  e1 -= e1.dot(n) * n;  // fiber projected into the triangle's plane
  if (e1.norm() < 1e-12) e1 = X2 - X1;  // fiber normal to the triangle: any in-plane axis
  e1.normalize();
  const Vec3 e2 = n.cross(e1);
  Mat2 Dm;
  Dm << (X2 - X1).dot(e1), (X3 - X1).dot(e1), (X2 - X1).dot(e2), (X3 - X1).dot(e2);
  const double a = 0.5 * Dm.determinant();
  if (!(a > 0)) throw InputError("triangle " + std::to_string(t) + ": expected a positive area, found zero");
  if (area) *area = a;
  return Dm.inverse();
}

Mat32 deformation_gradient(const VecX& x, const Tri& tri, const Mat2& Dm_inv) {
  Mat32 Ds;
  Ds.col(0) = node3(x, tri[1]) - node3(x, tri[0]);
  Ds.col(1) = node3(x, tri[2]) - node3(x, tri[0]);
  return Ds * Dm_inv;
}

Eigen::Vector3d green_strain(const Mat32& F) {
  const Mat2 C = F.transpose() * F;
  return {0.5 * (C(0, 0) - 1), 0.5 * (C(1, 1) - 1), C(0, 1)};
}

std::vector<TriangleKinematics> triangle_kinematics(const TriMesh& mesh, const VecX& x) {
  std::vector<TriangleKinematics> out;
  out.reserve(mesh.triangles.size());
  for (int t = 0; t < mesh.num_triangles(); ++t) {
    const Mat32 F = deformation_gradient(x, mesh.triangles[t], material_frame_inverse(mesh, t, nullptr));
    const Mat2 C = F.transpose() * F;
    out.push_back({green_strain(F), std::sqrt(C(0, 0)), std::sqrt(C(1, 1)), std::sqrt(std::max(C.determinant(), 0.0))});
  }
  return out;
}

}  // namespace valve
