#pragma once
// Finite-deformation membrane triangles after Taylor et al. (seed 3.2.2.4, Eq. 3.7-3.15).
//
// Each triangle gets a rest frame in its own plane with e1 along the fiber direction
// (projected into the plane) and e2 = n × e1, and Dm = [ΔX21 ΔX31] in that frame. With the
// current edges Ds = [Δx21 Δx31] (3x2), F = Ds Dm⁻¹ and C = FᵀF = Gᵀ g G of Eq. 3.8-3.9
// (g = DsᵀDs, G = Dm⁻¹). Because the frame is already aligned with the fiber, Green strain
// E = (C - I)/2 (Eq. 3.7) is in material axes and the rotation R of Eq. 3.10-3.11 is the
// identity. With Ŝ = dW/dÊ from the material law and ∇N_a the gradients of the linear
// shape functions in the rest frame (rows of Dm⁻¹; ∇N_1 = -∇N_2 - ∇N_3):
//     f_a = -A H B_aᵀ Ŝ                                                    (3.12-3.15)
//     B_a = [∇N_a1 F_1ᵀ ; ∇N_a2 F_2ᵀ ; ∇N_a2 F_1ᵀ + ∇N_a1 F_2ᵀ]  (F_I: columns of F)
//     df_a/dx_b = -A H [ (∇N_aᵀ S ∇N_b) I + B_aᵀ D B_b ],  D = dŜ/dÊ
// A and H are the rest area and thickness.
#include <memory>
#include <vector>

#include "valve/material/material_law.hpp"
#include "valve/mechanics/force_term.hpp"
#include "valve/mesh/tri_mesh.hpp"

namespace valve {

class MembraneFETerm final : public ForceTerm {
 public:
  MembraneFETerm(const TriMesh& mesh, std::shared_ptr<const MaterialLaw> law, double thickness);
  std::string name() const override { return "membrane_fe"; }
  void couplings(std::vector<std::pair<int, int>>& pairs) const override;
  void add(const State& s, VecX& f, BlockJacobian* dfdx, BlockJacobian* dfdv) const override;
  bool energy(const State& s, double& e) const override;

  /// Green strain (material axes, Voigt with engineering shear) of triangle t at x.
  Voigt green_strain(const VecX& x, int t) const;
  /// Second Piola-Kirchhoff stress (material axes) of triangle t at x.
  Voigt stress(const VecX& x, int t) const { return law_->stress(green_strain(x, t)); }
  int num_triangles() const { return static_cast<int>(elements_.size()); }

 private:
  struct Element {
    Tri nodes;
    Mat2 Dm_inv;
    double volume;  // A H
  };
  std::vector<Element> elements_;
  std::shared_ptr<const MaterialLaw> law_;
  mutable BlockSlotCache slots_;  // 9 per element: (nodes[a], nodes[b]), a major
};

}  // namespace valve
