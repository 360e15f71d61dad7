// Quadratic hinge bending: the hinge vector against the geometry of a rigid fold, forces
// against the energy's gradient, the Jacobian against finite differences, and the energy
// of an equilateral sheet wrapped onto a cylinder against the plate's ½ D κ² per unit area.
#include <catch2/catch.hpp>
#include <Eigen/Geometry>
#include <cmath>

#include "support/test_meshes.hpp"
#include "valve/mechanics/bending.hpp"

using namespace valve;

namespace {

/// Equilateral lattice of nx × ny nodes with edge l, rotated by `angle` in its plane (z = 0).
TriMesh equilateral_sheet(int nx, int ny, double l, double angle) {
  TriMesh m;
  m.points.resize(nx * ny, 3);
  const double c = std::cos(angle), s = std::sin(angle);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const double x = (i + 0.5 * (j % 2)) * l, y = j * l * std::sqrt(3.0) / 2;
      m.points.row(j * nx + i) << c * x - s * y, s * x + c * y, 0.0;
    }
  for (int j = 0; j + 1 < ny; ++j)
    for (int i = 0; i + 1 < nx; ++i) {
      const int a = j * nx + i, b = a + 1, u = a + nx, v = u + 1;
      if (j % 2 == 0) {
        m.triangles.emplace_back(a, b, u);
        m.triangles.emplace_back(b, v, u);
      } else {
        m.triangles.emplace_back(a, v, u);
        m.triangles.emplace_back(a, b, v);
      }
    }
  m.fiber.resize(m.num_triangles(), 3);
  for (int t = 0; t < m.num_triangles(); ++t) m.fiber.row(t) << 1, 0, 0;
  m.fill_defaults();
  return m;
}

VecX positions(const TriMesh& m) {
  VecX x(3 * m.num_nodes());
  for (int i = 0; i < m.num_nodes(); ++i) node3(x, i) = m.points.row(i).transpose();
  return x;
}

}  // namespace

TEST_CASE("hinge vector: zero for a flat hinge moved rigidly, 2 sin(θ/2) when folded by θ", "[bending]") {
  // One hinge: edge (0, 1) along +x, node 2 above it (+y), node 3 below (−y), flat in z = 0.
  TriMesh m;
  m.points.resize(4, 3);
  m.points << 0, 0, 0, 2, 0, 0, 0.7, 1.5, 0, 1.1, -1.2, 0;
  m.triangles = {Tri(0, 1, 2), Tri(1, 0, 3)};
  m.fiber.resize(2, 3);
  m.fiber << 1, 0, 0, 1, 0, 0;
  m.fill_defaults();
  const BendingTerm term(m, 1.0);
  REQUIRE(term.hinges().size() == 1);
  const Hinge& h = term.hinges()[0];
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.8, Vec3(1, 2, -1).normalized()).toRotationMatrix();
  VecX x(12);
  for (int i = 0; i < 4; ++i) node3(x, i) = R * m.points.row(i).transpose() + Vec3(3, -1, 2);
  CHECK(hinge_vector(x, h).norm() < 1e-14);
  for (double theta : {0.3, 1.2, 2.5}) {
    // Fold triangle (1, 0, 3) about the hinge by θ, then move the whole hinge rigidly.
    const Eigen::Matrix3d F = Eigen::AngleAxisd(theta, Vec3::UnitX()).toRotationMatrix();
    for (int i = 0; i < 4; ++i) {
      const Vec3 p = m.points.row(i).transpose();
      node3(x, i) = R * (i == 3 ? Vec3(F * p) : p) + Vec3(3, -1, 2);
    }
    CHECK(hinge_vector(x, h).norm() == Approx(2 * std::sin(theta / 2)).epsilon(1e-12));
  }
}

TEST_CASE("bending force is minus the energy gradient and the Jacobian matches finite differences", "[bending]") {
  TriMesh m = equilateral_sheet(4, 4, 1.0, 0.3);
  for (int i = 0; i < m.num_nodes(); ++i) m.points(i, 2) = 0.15 * m.points(i, 0) * m.points(i, 0) - 0.1 * m.points(i, 1);
  const BendingTerm term(m, 0.05);
  REQUIRE(term.hinges().size() == 21);  // 33 edges of a 4 × 4 equilateral lattice, 12 on its boundary
  VecX x = positions(m), v = VecX::Zero(x.size());
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-0.3, 0.3);
  for (int i = 0; i < x.size(); ++i) x[i] += u(rng);
  VecX f = VecX::Zero(x.size());
  term.add(State{x, v, 1, 0}, f, nullptr, nullptr);
  REQUIRE(f.norm() > 1e-3);
  const VecX g = test::numeric_energy_force(term, x, v, 1, 1e-6);
  for (int i = 0; i < x.size(); ++i) CHECK(f[i] == Approx(g[i]).margin(1e-7));
  const Eigen::MatrixXd A = test::analytic_dfdx(term, m.num_nodes(), x, v, 1);
  const Eigen::MatrixXd N = test::numeric_dfdx(term, x, v, 1, 1e-6);
  CHECK(test::relative_difference(A, N) < 1e-6);
}

TEST_CASE("an equilateral sheet wrapped onto a cylinder stores the plate energy ½ D κ² per area", "[bending]") {
  // Plate theory: a flat plate bent to curvature κ = 1/R stores ½ D κ² per unit area. Each
  // hinge owns a third of its two triangles; the sum of those areas is the area compared.
  const double D = 0.02, R = 40.0, l = 0.5;
  for (double angle : {0.0, 0.29, 0.61}) {
    const TriMesh m = equilateral_sheet(30, 30, l, angle);
    const BendingTerm term(m, D);
    VecX x = positions(m), v = VecX::Zero(x.size());
    double owned = 0;
    for (const Hinge& h : term.hinges()) {
      const Vec3 a = node3(x, h.nodes[0]), b = node3(x, h.nodes[1]);
      owned += 0.5 * ((b - a).cross(node3(x, h.nodes[2]) - a).norm() + (node3(x, h.nodes[3]) - a).cross(b - a).norm()) / 3;
    }
    for (int i = 0; i < m.num_nodes(); ++i) {  // isometric wrap about an axis parallel to y
      const double px = m.points(i, 0);
      node3(x, i) = Vec3(R * std::sin(px / R), m.points(i, 1), R * (1 - std::cos(px / R)));
    }
    double e = 0;
    term.energy(State{x, v, 1, 0}, e);
    INFO("lattice angle " << angle);
    // Hinge counts per direction differ by the boundary rows only: within 5 %.
    CHECK(e == Approx(0.5 * D / (R * R) * owned).epsilon(0.05));
  }
}
