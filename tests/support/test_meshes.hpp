#pragma once
// Small meshes and helpers shared by the tests.
#include <Eigen/Dense>
#include <random>

#include "valve/mechanics/force_term.hpp"
#include "valve/mesh/tri_mesh.hpp"

namespace valve::test {

/// A 3x3-node square grid in the z = 0 plane (8 triangles), fibers at `fiber_deg` from +x.
inline TriMesh grid_mesh(double size = 2.0, double fiber_deg = 30.0) {
  TriMesh m;
  m.points.resize(9, 3);
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i) m.points.row(3 * j + i) << size * i / 2.0, size * j / 2.0, 0.0;
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 2; ++i) {
      const int a = 3 * j + i, b = a + 1, c = a + 3, d = a + 4;
      m.triangles.emplace_back(a, b, d);
      m.triangles.emplace_back(a, d, c);
    }
  const double f = fiber_deg * 3.14159265358979 / 180;
  m.fiber.resize(m.num_triangles(), 3);
  for (int t = 0; t < m.num_triangles(); ++t) m.fiber.row(t) << std::cos(f), std::sin(f), 0;
  m.fill_defaults();
  return m;
}

/// Two one-triangle leaflets. Leaflet 0: triangle (0, 1, 2) in z = 0, normal +z.
/// Leaflet 1: triangle (3, 4, 5) whose node 3 sits at (0.5, 0.5, h) over the first one's
/// face, nodes 4 and 5 far outside its footprint and well above it.
inline TriMesh two_sheets(double h) {
  TriMesh m;
  m.points.resize(6, 3);
  m.points << 0, 0, 0, 2, 0, 0, 0, 2, 0,  //
      0.5, 0.5, h, 5, 0.5, h + 3, 0.5, 5, h + 2;
  m.triangles = {Tri(0, 1, 2), Tri(3, 4, 5)};
  m.leaflet = {0, 1};
  m.fill_defaults();
  return m;
}

/// Rest positions displaced by a random perturbation of size `amp` plus a stretch, so that
/// springs and elements are in a generic (tension, shear, out-of-plane) state.
inline VecX perturbed(const TriMesh& m, double amp, unsigned seed = 7, double stretch = 1.15) {
  std::mt19937 g(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  VecX x = flatten(m.points);
  for (int i = 0; i < x.size(); ++i) x[i] = x[i] * (i % 3 == 1 ? 1.05 : stretch) + amp * u(g);
  return x;
}

/// Central-difference df/dx (dense) of a force term at x.
inline Eigen::MatrixXd numeric_dfdx(const ForceTerm& term, const VecX& x, const VecX& v, double load, double h) {
  const int n = static_cast<int>(x.size());
  Eigen::MatrixXd J(n, n);
  for (int j = 0; j < n; ++j) {
    VecX xp = x, xm = x, fp = VecX::Zero(n), fm = VecX::Zero(n);
    xp[j] += h;
    xm[j] -= h;
    term.add(State{xp, v, load, 0}, fp, nullptr, nullptr);
    term.add(State{xm, v, load, 0}, fm, nullptr, nullptr);
    J.col(j) = (fp - fm) / (2 * h);
  }
  return J;
}

/// Minus the central-difference gradient of a term's energy at x (the force it should give).
inline VecX numeric_energy_force(const ForceTerm& term, const VecX& x, const VecX& v, double load, double h) {
  VecX g(x.size());
  for (int j = 0; j < x.size(); ++j) {
    VecX xp = x, xm = x;
    xp[j] += h;
    xm[j] -= h;
    double ep = 0, em = 0;
    term.energy(State{xp, v, load, 0}, ep);
    term.energy(State{xm, v, load, 0}, em);
    g[j] = -(ep - em) / (2 * h);
  }
  return g;
}

inline Eigen::MatrixXd analytic_dfdx(const ForceTerm& term, int num_nodes, const VecX& x, const VecX& v, double load) {
  std::vector<std::pair<int, int>> pairs;
  term.couplings(pairs);
  BlockJacobian J(num_nodes, pairs);
  VecX f = VecX::Zero(x.size());
  term.add(State{x, v, load, 0}, f, &J, nullptr);
  return Eigen::MatrixXd(J.matrix());
}

/// Max |A - B| / max|B|.
inline double relative_difference(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B) {
  return (A - B).cwiseAbs().maxCoeff() / std::max(B.cwiseAbs().maxCoeff(), 1e-300);
}

// Two rings of n nodes (radii 12 and 6 mm) in z = 0 joined by triangles; outer ring fixed.
inline TriMesh annulus_membrane(int n, double scale) {
  TriMesh m;
  m.points.resize(3 * n, 3);
  for (int r = 0; r < 3; ++r)
    for (int i = 0; i < n; ++i) {
      const double t = 2 * M_PI * (i + 0.5 * r) / n, radius = scale * (12.0 - 3.0 * r);
      m.points.row(r * n + i) << radius * std::cos(t), radius * std::sin(t), 0;
    }
  for (int r = 0; r < 2; ++r)
    for (int i = 0; i < n; ++i) {
      const int j = (i + 1) % n, a = r * n + i, b = r * n + j, c = (r + 1) * n + i, d = (r + 1) * n + j;
      m.triangles.emplace_back(a, b, c);
      m.triangles.emplace_back(b, d, c);
    }
  m.fill_defaults();
  for (int i = 0; i < n; ++i) m.roles[i] = NodeRole::fixed;
  return m;
}

}  // namespace valve::test
