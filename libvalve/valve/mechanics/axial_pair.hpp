#pragma once
// A central force between two nodes, shared by the mass-spring springs and the chordae
// rods: with n = (x_b − x_a)/l and F(l) the pulling force (dF its derivative),
//   f_a = F n,  f_b = −F n,  ∂f_a/∂x_b = K = dF n nᵀ + (F / l)(I − n nᵀ),  ∂f_a/∂x_a = −K.
#include "valve/mechanics/jacobian.hpp"

namespace valve {

inline void add_axial_pair(int a, int b, const Vec3& n, double l, double F, double dF, VecX& f, BlockJacobian* dfdx) {
  f.segment<3>(3 * a) += F * n;
  f.segment<3>(3 * b) -= F * n;
  if (!dfdx) return;
  const Mat3 nn = n * n.transpose();
  const Mat3 K = dF * nn + (F / l) * (Mat3::Identity() - nn);
  dfdx->add(a, a, -K);
  dfdx->add(b, b, -K);
  dfdx->add(a, b, K);
  dfdx->add(b, a, K);
}

}  // namespace valve
