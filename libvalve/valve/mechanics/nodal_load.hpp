#pragma once
// Dead nodal loads scaled by the load factor: f_i = λ F_i. Used for the biaxial edge loads
// (seed 3.2.2.5): a Lagrangian (first Piola-Kirchhoff) normal stress P on a boundary edge
// of rest length L and thickness H is a fixed force P H L along the edge's rest outward
// normal, split equally between the edge's two nodes. Constant ratio P_x : P_y is kept by
// scaling both with the same λ.
#include <vector>

#include "valve/mechanics/force_term.hpp"
#include "valve/mesh/tri_mesh.hpp"

namespace valve {

class NodalLoadTerm final : public ForceTerm {
 public:
  explicit NodalLoadTerm(VecX forces) : forces_(std::move(forces)) {}
  bool is_external_load() const override { return true; }
  std::string name() const override { return "edge_loads"; }
  void couplings(std::vector<std::pair<int, int>>&) const override {}
  void add(const State& s, VecX& f, BlockJacobian*, BlockJacobian*) const override { f += s.load * forces_; }
  bool energy(const State& s, double& e) const override {
    e -= s.load * forces_.dot(s.x);
    return true;
  }
  const VecX& forces() const { return forces_; }

 private:
  VecX forces_;
};

/// Biaxial edge loads on a planar patch in the xy plane: stress_x acts on boundary edges
/// whose rest outward normal is ±x (|n_x| > 0.99), stress_y on ±y. Stresses in MPa.
VecX biaxial_edge_forces(const TriMesh& mesh, double stress_x, double stress_y, double thickness);

}  // namespace valve
