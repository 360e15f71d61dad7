#pragma once
// A central force between two nodes, shared by the mass-spring springs and the chordae
// rods: with n = (x_b − x_a)/l and F(l) the pulling force (dF its derivative),
//   f_a = F n,  f_b = −F n,  ∂f_a/∂x_b = K = dF n nᵀ + (F / l)(I − n nᵀ),  ∂f_a/∂x_a = −K.
#include "valve/mechanics/jacobian.hpp"

namespace valve {

/// `slots`, if given, are the pair's four blocks in the order (a, a), (b, b), (a, b), (b, a)
/// (from a BlockSlotCache): they spare the pattern look-ups.
inline void add_axial_pair(int a, int b, const Vec3& n, double l, double F, double dF, VecX& f, BlockJacobian* dfdx,
                           const BlockSlot* slots = nullptr) {
  f.segment<3>(3 * a) += F * n;
  f.segment<3>(3 * b) -= F * n;
  if (!dfdx) return;
  const Mat3 nn = n * n.transpose();
  const Mat3 K = dF * nn + (F / l) * (Mat3::Identity() - nn);
  if (slots) {
    dfdx->add(slots[0], -K);
    dfdx->add(slots[1], -K);
    dfdx->add(slots[2], K);
    dfdx->add(slots[3], K);
    return;
  }
  dfdx->add(a, a, -K);
  dfdx->add(b, b, -K);
  dfdx->add(a, b, K);
  dfdx->add(b, a, K);
}

}  // namespace valve
