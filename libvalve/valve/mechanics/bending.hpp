#pragma once
// Bending stiffness of the leaflet, a quadratic hinge energy toward a flat sheet (the
// isometric bending model of Bergou et al. 2006). Neither the seed's M-S model nor the
// membrane FE resists bending, so a free-edge triangle can fold over its neighbour at no
// cost; under a follower pressure the folded triangle is pushed the wrong way and the fold
// never settles (measured on the sample mitral closure: a free-edge node between two chord
// insertions, its three triangles folded to normals 90–150° apart, kept orbiting on a ~1 mm
// loop). Contact cannot stop it: triangles sharing a vertex are excluded from contact.
//
// Hinge edge (a, b) with opposite nodes c (triangle a, b, c) and d (triangle b, a, d). With
// rest heights h_c, h_d of c and d over the hinge and their rest projection parameters
// s = (p − a)·(b − a)/|b − a|² on it, the hinge vector
//     v = w_a x_a + w_b x_b + w_c x_c + w_d x_d,
//     w_c = −1/h_c,  w_d = −1/h_d,  w_a = (1 − s_c)/h_c + (1 − s_d)/h_d,  w_b = s_c/h_c + s_d/h_d
// is minus the sum of the unit vectors from the hinge to c and to d: zero when the two
// triangles lie flat, 2 sin(θ/2) n̂ when rigidly folded by θ (≈ θ n̂, the linearised
// dihedral angle). Energy W = ½ k |v|², force f_i = −k w_i v, Jacobian −k w_i w_j I:
// constant, exact and negative semi-definite.
//
// Why not the dihedral angle θ itself (discrete shells): its gradient grows as 1/h, and
// on the sample mitral closure it collapsed folded triangles to zero area, where θ jumps
// by π (measured: residual 1e11). Why flat: v is rotation invariant only for a flat reference.
// The open leaflet's rest curvature is therefore not kept, and the term moves the unloaded
// leaflet (measured: 2.2 mm at most on the 648-triangle sample mitral membrane with
// E_b = 100 kPa, t = 1 mm, zero-pressure static solve; Table 5.1's small-strain fibre slope
// is 11 kPa, so the soft membrane gives way). In-plane strain that is not isometric also
// changes v, stiffening the membrane slightly at small strain.
//
// Stiffness from the flexural rigidity D = E_b t³ / 12: k = D |ē|² / (Ā1 + Ā2) (rest
// lengths and areas), calibrated so that an equilateral sheet wrapped onto a cylinder of
// curvature κ stores the plate's ½ D κ² per unit area, whatever the lattice orientation
// (tests/mechanics/bending_test.cpp).
#include <vector>

#include "valve/mechanics/force_term.hpp"
#include "valve/mesh/tri_mesh.hpp"

namespace valve {

struct Hinge {
  int nodes[4];       // a, b (the hinge), c, d (opposite)
  double weights[4];  // w_a, w_b, w_c, w_d (1/mm)
  double stiffness = 0;  // k, N·mm
};

/// The hinge vector v = Σ w_i x_i at positions x.
Vec3 hinge_vector(const VecX& x, const Hinge& h);

class BendingTerm final : public ForceTerm {
 public:
  /// `flexural_rigidity` D in N·mm (E_b t³ / 12 with E_b in MPa and t in mm).
  BendingTerm(const TriMesh& mesh, double flexural_rigidity);
  std::string name() const override { return "bending"; }
  void couplings(std::vector<std::pair<int, int>>& pairs) const override;
  void add(const State& s, VecX& f, BlockJacobian* dfdx, BlockJacobian* dfdv) const override;
  bool energy(const State& s, double& e) const override;
  const std::vector<Hinge>& hinges() const { return hinges_; }

 private:
  std::vector<Hinge> hinges_;
  mutable BlockSlotCache slots_;  // 16 per hinge: (nodes[i], nodes[j]), i major
};

}  // namespace valve
