#include "valve/mechanics/aortic_root.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "valve/core/error.hpp"
#include "valve/mesh/topology.hpp"

namespace valve {
namespace {

constexpr double kPi = 3.14159265358979323846;

struct Radial {
  Vec3 e;    // unit radial direction
  double r;  // distance from the axis
  Mat3 P;    // I − u uᵀ
};

Radial radial(const RootGeometry& g, const Vec3& p) {
  Radial out;
  const Vec3& u = g.axis_direction;
  out.P = Mat3::Identity() - u * u.transpose();
  const Vec3 q = out.P * (p - g.axis_point);
  out.r = q.norm();
  out.e = out.r > 0 ? Vec3(q / out.r) : Vec3::Zero();
  return out;
}

// Adds φ(r) e_r and its Jacobian; phi_of(r) gives {φ(r), φ'(r)}.
template <class Phi>
void add_radial(const RootGeometry& g, int i, const VecX& x, const Phi& phi_of, VecX& f, BlockJacobian* dfdx) {
  const Radial rd = radial(g, node3(x, i));
  if (rd.r <= 0) return;
  const auto [phi, dphi] = phi_of(rd.r);
  node3(f, i) += phi * rd.e;
  if (dfdx) dfdx->add(i, i, dphi * rd.e * rd.e.transpose() + phi / rd.r * (rd.P - rd.e * rd.e.transpose()));
}

// φ(r) = a + b r.
auto affine(double a, double b) {
  return [a, b](double r) { return std::pair<double, double>(a + b * r, b); };
}

}  // namespace

double radius_from_axis(const RootGeometry& g, const Vec3& p) { return radial(g, p).r; }

RootGeometry root_geometry(const TriMesh& mesh, const Vec3& axis_point, const Vec3& axis_direction) {
  RootGeometry g;
  g.axis_point = axis_point;
  g.axis_direction = axis_direction.normalized();
  // Where the leaflets are sewn: their start positions (a graft's rest shape lies on a wider
  // cylinder than the root it is sewn into).
  const MatX3& sewn = mesh.start_positions();
  std::vector<double> half_length(mesh.num_nodes(), 0.0);
  const Topology topo = build_topology(mesh.triangles, mesh.num_nodes());
  auto attached = [&](int i) { return !mesh.boundary.empty() && mesh.boundary[i] == BoundaryType::attached; };
  for (const auto& e : topo.edges) {
    if (e.tris[1] >= 0 || !attached(e.a) || !attached(e.b)) continue;
    const double l = (sewn.row(e.a) - sewn.row(e.b)).norm();
    half_length[e.a] += 0.5 * l;
    half_length[e.b] += 0.5 * l;
  }
  double total = 0, lo = 1e300, hi = -1e300, radius = 0;
  for (int i = 0; i < mesh.num_nodes(); ++i) {
    if (!attached(i)) continue;
    g.nodes.push_back(i);
    total += half_length[i];
    const Vec3 p = sewn.row(i);
    const double h = (p - g.axis_point).dot(g.axis_direction);
    lo = std::min(lo, h), hi = std::max(hi, h);
    radius += radius_from_axis(g, p);
  }
  if (g.nodes.empty() || total <= 0 || hi <= lo)
    throw InputError("aortic_root: expected a mesh with attached boundary nodes (BoundaryType 1) spanning a height, found none");
  g.mesh_radius = radius / g.nodes.size();
  const double wall = 2 * kPi * g.mesh_radius * (hi - lo);
  for (int i : g.nodes) g.wall_area.push_back(wall * half_length[i] / total);
  return g;
}

RootSpringTerm::RootSpringTerm(const RootGeometry& g, const MatX3& points, double E, double t, double r0,
                               std::optional<double> stiffening_radius, std::optional<double> stiffness_index)
    : g_(g), r0_(r0), rs_(stiffening_radius) {
  if (rs_) {
    if (!(std::isfinite(*rs_) && *rs_ > r0))
      throw InputError("aortic_root: expected a stiffening radius above the unloaded radius " + format_number(r0) +
                       " mm, found " + format_number(*rs_) + " mm");
    beta_ = root_stiffness_index(r0, *rs_, stiffness_index);
    if (!(std::isfinite(beta_) && beta_ > 0))
      throw InputError("aortic_root.stiffness_index: expected a positive number, found " + format_number(beta_));
  }
  for (size_t k = 0; k < g_.nodes.size(); ++k) {
    k_.push_back(E * t * g_.wall_area[k] / (g_.mesh_radius * r0));
    rest_.push_back(points.row(g_.nodes[k]).transpose());
    const Vec3 e = radial(g_, rest_.back()).e;
    tangential_.push_back(Mat3::Identity() - e * e.transpose());
  }
}

void RootSpringTerm::couplings(std::vector<std::pair<int, int>>&) const {}

void RootSpringTerm::add(const State& s, VecX& f, BlockJacobian* dfdx, BlockJacobian*) const {
  for (size_t k = 0; k < g_.nodes.size(); ++k) {
    const int i = g_.nodes[k];
    // −N(r) A_i/R = −k_i n(r) with n = N r0 / (E t): r − r0 on the linear branch,
    // (r_s − r0)(r / r_s) exp(β (r / r_s − 1)) beyond r_s.
    const double ki = k_[k];
    add_radial(g_, i, s.x, [&](double r) {
      if (!rs_ || r <= *rs_) return std::pair<double, double>(-ki * (r - r0_), -ki);
      const double rho = r / *rs_, grow = std::exp(beta_ * (rho - 1)), ns = *rs_ - r0_;
      return std::pair<double, double>(-ki * ns * rho * grow, -ki * ns / *rs_ * grow * (1 + beta_ * rho));
    }, f, dfdx);
    node3(f, i) -= k_[k] * tangential_[k] * (node3(s.x, i) - rest_[k]);
    if (dfdx) dfdx->add(i, i, -k_[k] * tangential_[k]);
  }
}

RootPressureTerm::RootPressureTerm(const RootGeometry& g, double pressure) : g_(g), pressure_(pressure) {}

void RootPressureTerm::couplings(std::vector<std::pair<int, int>>&) const {}

void RootPressureTerm::add(const State& s, VecX& f, BlockJacobian* dfdx, BlockJacobian*) const {
  for (size_t k = 0; k < g_.nodes.size(); ++k)
    add_radial(g_, g_.nodes[k], s.x, affine(0.0, s.load * pressure_ * g_.wall_area[k] / g_.mesh_radius), f, dfdx);
}

double free_tube_radius(double pressure, double E, double t, double r0, std::optional<double> stiffening_radius,
                        std::optional<double> stiffness_index) {
  const double c = pressure * r0 / (E * t);
  const double linear = c < 1 ? r0 / (1 - c) : std::numeric_limits<double>::infinity();
  if (stiffening_radius && linear > *stiffening_radius) {
    const double rs = *stiffening_radius, beta = root_stiffness_index(r0, rs, stiffness_index);
    const double ps = E * t * (rs - r0) / (r0 * rs);  // the linear tube's pressure at r_s
    return rs * (1 + std::log(pressure / ps) / beta);
  }
  if (!std::isfinite(linear))
    throw NumericalError("aortic_root: the linear tube has no equilibrium at " + format_number(pressure) +
                         " MPa (P r0 >= E t)");
  return linear;
}

}  // namespace valve
