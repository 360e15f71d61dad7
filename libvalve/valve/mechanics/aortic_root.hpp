#pragma once
// The aortic root as an elastic tube acting on the leaflet attachment (seed 4.2.1).
//
// Each attached node i stands for a portion of a thin-walled tube (radius r, unloaded
// radius r0, wall thickness t, Young's modulus E) of wall area A_i measured at the mesh
// radius R. Its angular span times height is A_i / R, so the hoop stress σ = E (r − r0)/r0
// pulls it toward the axis with σ t A_i / R and the pressure P pushes it out with P r A_i / R:
//     f_i = (A_i / R) [P r − E t (r − r0) / r0] e_r                          (radial)
// The spring (hoop) part is RootSpringTerm, the pressure part RootPressureTerm (an external
// load, so load continuation ramps it and residuals are scaled by it). Without leaflets the
// tube settles at r = r0 / (1 − P r0 / (E t)).
// The wall also holds each node's axial and circumferential position with the hoop
// stiffness k_i = E t A_i / (R r0), a linear spring in the plane normal to the rest radial
// direction; otherwise the attachment could slide along the wall at no cost.
// Jacobians: with q = (I − u uᵀ)(p − a), r = |q|, e_r = q / r and φ(r) the radial magnitude,
//     df/dp = φ'(r) e_r e_rᵀ + φ(r) / r (I − u uᵀ − e_r e_rᵀ).
//
// Stiffening (optional). The linear tube's radius diverges as P r0 / (E t) nears 1: with the
// shipped wall it is 20.3 mm across at 80 mmHg, 22.2 at 120 and 27.3 at 200, where no
// leaflets of the valve's size can meet. Arteries stiffen instead; the clinical stiffness
// index β = ln(P / P_s) / (D / D_s − 1) (Kawasaki et al. 1987) is near constant over the
// physiological range. Given a stiffening radius r_s (the free tube's radius at a pressure
// P_s), the hoop tension per unit length N = σ t is, beyond r_s,
//     N(r) = N_s (r / r_s) exp(β (r / r_s − 1)),   N_s = E t (r_s − r0) / r0,
// so that the free tube follows P = N / r = P_s exp(β (r / r_s − 1)); below r_s it stays
// E t (r − r0) / r0. By default β = r0 / (r_s − r0), which makes N and dN/dr continuous at
// r_s: the linear tube's own stiffness index at P_s, kept constant above it instead of
// falling. A β of the user's (a measured stiffness index) keeps N continuous and lets its
// slope jump at r_s.
#include <optional>
#include <vector>

#include "valve/mechanics/force_term.hpp"
#include "valve/mesh/tri_mesh.hpp"

namespace valve {

struct RootGeometry {
  Vec3 axis_point = Vec3::Zero();
  Vec3 axis_direction = Vec3::UnitZ();  // unit
  std::vector<int> nodes;               // attached nodes
  std::vector<double> wall_area;        // A_i, mm²
  double mesh_radius = 0;               // R, mm: mean radius of the attached nodes where sewn
};

/// Attached nodes (BoundaryType attached) and their share of the root wall: the tube between
/// the lowest and highest attached node, split in proportion to each node's half-length of
/// attachment boundary edges, all at the mesh's start positions (where the leaflets are sewn).
/// Throws InputError when the mesh has no attached node.
RootGeometry root_geometry(const TriMesh& mesh, const Vec3& axis_point, const Vec3& axis_direction);

/// Radius of a point from the axis.
double radius_from_axis(const RootGeometry& g, const Vec3& p);

class RootSpringTerm final : public ForceTerm {
 public:
  /// `E` MPa, `t` mm, `r0` unloaded radius mm; rest positions from `points`; `stiffening_radius`
  /// r_s > r0 (mm) where the hoop tension turns exponential (see above), or none;
  /// `stiffness_index` β above r_s (none: the linear tube's own, root_stiffness_index).
  RootSpringTerm(const RootGeometry& g, const MatX3& points, double E, double t, double r0,
                 std::optional<double> stiffening_radius = std::nullopt,
                 std::optional<double> stiffness_index = std::nullopt);
  /// The stiffness index β above r_s (0 without stiffening).
  double stiffness_index() const { return beta_; }
  std::string name() const override { return "root_springs"; }
  void couplings(std::vector<std::pair<int, int>>& pairs) const override;
  void add(const State& s, VecX& f, BlockJacobian* dfdx, BlockJacobian* dfdv) const override;

 private:
  RootGeometry g_;
  std::vector<double> k_;    // hoop stiffness per node, N/mm
  std::vector<Vec3> rest_;   // rest position
  std::vector<Mat3> tangential_;  // I − e_r0 e_r0ᵀ at rest
  double r0_;
  std::optional<double> rs_;  // stiffening radius
  double beta_ = 0;
};

/// The stiffness index above the stiffening radius r_s: the `given` one, else the one that keeps
/// the hoop tension and its slope continuous there, β = r0 / (r_s − r0) (see above).
inline double root_stiffness_index(double r0, double stiffening_radius, std::optional<double> given = std::nullopt) {
  return given ? *given : r0 / (stiffening_radius - r0);
}

/// Radius of the free tube (no leaflets) at pressure P (MPa): r0 / (1 − P r0 / (E t)) while
/// the linear law holds; beyond the stiffening radius r_s (when given), r_s (1 + ln(P / P_s) / β)
/// with β `stiffness_index` (none: the linear tube's own).
/// Throws NumericalError when the linear tube has no equilibrium (P r0 ≥ E t).
double free_tube_radius(double pressure, double E, double t, double r0, std::optional<double> stiffening_radius,
                        std::optional<double> stiffness_index = std::nullopt);

class RootPressureTerm final : public ForceTerm {
 public:
  RootPressureTerm(const RootGeometry& g, double pressure);
  std::string name() const override { return "root_pressure"; }
  bool is_external_load() const override { return true; }
  void couplings(std::vector<std::pair<int, int>>& pairs) const override;
  void add(const State& s, VecX& f, BlockJacobian* dfdx, BlockJacobian* dfdv) const override;

 private:
  RootGeometry g_;
  double pressure_;
};

}  // namespace valve
