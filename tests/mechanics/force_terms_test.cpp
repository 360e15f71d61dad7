// Every force term's analytic Jacobian against central finite differences, zero force at
// rest, invariance under rigid motion, and energy consistency (f = -dE/dx).
#include <Eigen/Geometry>
#include <catch2/catch.hpp>

#include "support/test_meshes.hpp"
#include "valve/material/bilinear_fit.hpp"
#include "valve/mechanics/damping.hpp"
#include "valve/mechanics/mass_spring.hpp"
#include "valve/mechanics/mechanical_system.hpp"
#include "valve/mechanics/membrane_fe.hpp"
#include "valve/mechanics/nodal_load.hpp"
#include "valve/mechanics/pressure.hpp"

using namespace valve;
using namespace valve::test;

namespace {
const FungParameters kAortic{9.7e-6, 49.558, 5.2871, -3.124, 16.031, -0.004, -0.02};
BilinearParameters table51() {
  return {{0.011, 2.3, 1.13}, {0.0033, 0.76, 1.33}};
}

// Rigid motion: rotation about an oblique axis plus a translation.
VecX rigid(const VecX& x) {
  const Mat3 R = Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()).toRotationMatrix();
  VecX y(x.size());
  for (int i = 0; i < x.size() / 3; ++i) node3(y, i) = R * node3(x, i) + Vec3(3, -1, 2);
  return y;
}

void check_jacobian(const ForceTerm& term, const TriMesh& m, const VecX& x, double tol) {
  const VecX v = VecX::Zero(x.size());
  const auto num = numeric_dfdx(term, x, v, 1.0, 1e-6);
  const auto ana = analytic_dfdx(term, m.num_nodes(), x, v, 1.0);
  INFO(term.name());
  CHECK(relative_difference(ana, num) < tol);
}

void check_energy_gradient(const ForceTerm& term, const VecX& x) {
  const VecX v = VecX::Zero(x.size());
  VecX f = VecX::Zero(x.size());
  term.add(State{x, v, 1.0, 0}, f, nullptr, nullptr);
  double e = 0;
  REQUIRE(term.energy(State{x, v, 1.0, 0}, e));
  const VecX g = numeric_energy_force(term, x, v, 1.0, 1e-6);
  INFO(term.name());
  CHECK((g - f).cwiseAbs().maxCoeff() <= 1e-5 * f.cwiseAbs().maxCoeff());
}
}  // namespace

TEST_CASE("mass-spring Jacobian matches finite differences in both stiffness regimes", "[mechanics][fd]") {
  const TriMesh m = grid_mesh();
  MassSpringTerm ms(m, table51(), 0.5);
  // Small stretch (below λ*) and large stretch (above λ* for fiber-aligned springs).
  check_jacobian(ms, m, perturbed(m, 0.05, 1, 1.05), 1e-6);
  check_jacobian(ms, m, perturbed(m, 0.05, 2, 1.25), 1e-6);
  check_energy_gradient(ms, perturbed(m, 0.05, 3, 1.25));
}

TEST_CASE("membrane FE Jacobian matches finite differences", "[mechanics][fd]") {
  const TriMesh m = grid_mesh();
  MembraneFETerm fe(m, std::make_shared<FungLaw>(kAortic), 0.5);
  for (unsigned seed : {1u, 2u, 3u}) check_jacobian(fe, m, perturbed(m, 0.08, seed, 1.2), 1e-5);
  check_energy_gradient(fe, perturbed(m, 0.08, 4, 1.2));
}

TEST_CASE("pressure Jacobian matches finite differences on a curved sheet", "[mechanics][fd]") {
  TriMesh m = grid_mesh();
  VecX x = perturbed(m, 0.2, 5, 1.1);
  for (int i = 0; i < m.num_nodes(); ++i) x[3 * i + 2] += 0.3 * std::sin(x[3 * i]);
  PressureTerm p(m, 0.0106, true);
  check_jacobian(p, m, x, 1e-7);
}

TEST_CASE("pressure force equals p times area along the normal", "[mechanics]") {
  const TriMesh m = grid_mesh(2.0);
  const VecX x = flatten(m.points), v = VecX::Zero(x.size());
  VecX f = VecX::Zero(x.size());
  PressureTerm(m, 0.01, true).add(State{x, v, 1.0, 0}, f, nullptr, nullptr);
  Vec3 total = Vec3::Zero();
  for (int i = 0; i < m.num_nodes(); ++i) total += node3(f, i);
  CHECK(total.z() == Approx(0.01 * 4.0).epsilon(1e-12));  // p * area, area = 2 x 2 mm
  CHECK(std::abs(total.x()) < 1e-15);
  VecX g = VecX::Zero(x.size());
  PressureTerm(m, 0.01, false).add(State{x, v, 0.5, 0}, g, nullptr, nullptr);
  CHECK((g + 0.5 * f).norm() < 1e-15);
}

TEST_CASE("internal forces vanish at rest and are invariant under rigid motion", "[mechanics]") {
  const TriMesh m = grid_mesh();
  MassSpringTerm ms(m, table51(), 0.5);
  MembraneFETerm fe(m, std::make_shared<FungLaw>(kAortic), 0.5);
  const VecX X = flatten(m.points), v = VecX::Zero(X.size());
  for (const ForceTerm* t : std::vector<const ForceTerm*>{&ms, &fe}) {
    VecX f0 = VecX::Zero(X.size()), f1 = VecX::Zero(X.size());
    t->add(State{X, v, 1, 0}, f0, nullptr, nullptr);
    t->add(State{rigid(X), v, 1, 0}, f1, nullptr, nullptr);
    INFO(t->name());
    CHECK(f0.cwiseAbs().maxCoeff() < 1e-15);
    CHECK(f1.cwiseAbs().maxCoeff() < 1e-15);
    // Deformed state: forces rotate with the body, their sum is zero.
    const VecX x = perturbed(m, 0.05, 9, 1.2);
    VecX fa = VecX::Zero(X.size()), fb = VecX::Zero(X.size());
    t->add(State{x, v, 1, 0}, fa, nullptr, nullptr);
    t->add(State{rigid(x), v, 1, 0}, fb, nullptr, nullptr);
    const Mat3 R = Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()).toRotationMatrix();
    double err = 0;
    Vec3 sum = Vec3::Zero();
    for (int i = 0; i < m.num_nodes(); ++i) {
      err = std::max(err, (node3(fb, i) - R * node3(fa, i)).norm());
      sum += node3(fa, i);
    }
    CHECK(err < 1e-10 * fa.cwiseAbs().maxCoeff());
    CHECK(sum.norm() < 1e-10 * fa.cwiseAbs().maxCoeff());
  }
}

TEST_CASE("FE membrane under homogeneous uniaxial stretch gives the Fung stress", "[mechanics]") {
  // Stretch along the fiber (x) by λ with no cross strain: S11 from Eq. 3.1-3.3 directly,
  // and the x-force on the right edge equals P11 * H * L = λ S11 H L.
  TriMesh m = grid_mesh(2.0, 0.0);
  const FungLaw law(kAortic);
  MembraneFETerm fe(m, std::make_shared<FungLaw>(kAortic), 0.5);
  const double lambda = 1.2;
  VecX x = flatten(m.points);
  for (int i = 0; i < m.num_nodes(); ++i) x[3 * i] *= lambda;
  VecX f = VecX::Zero(x.size());
  const VecX v = VecX::Zero(x.size());
  fe.add(State{x, v, 1, 0}, f, nullptr, nullptr);
  double right = 0;
  for (int i : {2, 5, 8}) right += f[3 * i];
  const double E11 = 0.5 * (lambda * lambda - 1);
  const double S11 = law.stress(Voigt(E11, 0, 0))[0];
  CHECK(-right == Approx(lambda * S11 * 0.5 * 2.0).epsilon(1e-10));
}

TEST_CASE("spring force follows the bilinear law of Eq. 3.5-3.6", "[mechanics]") {
  Spring sp{0, 1, 2.0, 3.0, 30.0, 1.1};
  double F, dF;
  MassSpringTerm::force(sp, 2.1, F, dF);  // λ = 1.05 < λ*
  CHECK(F == Approx(3.0 * 0.1));
  CHECK(dF == 3.0);
  MassSpringTerm::force(sp, 2.4, F, dF);  // λ = 1.2 > λ*: k1 l0 (λ*-1) + k2 (l - λ* l0)
  CHECK(F == Approx(3.0 * 2.0 * 0.1 + 30.0 * (2.4 - 2.2)));
  CHECK(dF == 30.0);
}

TEST_CASE("van Gelder spring constants", "[mechanics]") {
  // k_c = E h Σ area / |c|² (Eq. 3.4); for a fiber-aligned edge E = m1 of the fiber curve.
  TriMesh m = grid_mesh(2.0, 0.0);
  MassSpringTerm ms(m, table51(), 0.5);
  for (const auto& s : ms.springs()) {
    if (s.a == 0 && s.b == 1) {  // bottom edge along x: one triangle of area 0.5
      CHECK(s.k1 == Approx(0.011 * 0.5 * 0.5 / 1.0));
      CHECK(s.k2 == Approx(2.3 * 0.5 * 0.5 / 1.0));
      CHECK(s.lambda_star == Approx(1.13));
    }
    if (s.a == 0 && s.b == 3) {  // left edge along y: cross-fiber
      CHECK(s.k1 == Approx(0.0033 * 0.5 * 0.5 / 1.0));
      CHECK(s.lambda_star == Approx(1.33));
    }
  }
}

TEST_CASE("damping and edge loads", "[mechanics]") {
  const TriMesh m = grid_mesh(2.0, 0.0);
  DampingTerm d(std::vector<double>(9, 2.0), DampingTerm::Mode::mass_proportional, 0.5);
  const VecX x = flatten(m.points);
  const VecX v = VecX::Constant(27, 3.0);
  VecX f = VecX::Zero(27);
  BlockJacobian Jv(9, {});
  d.add(State{x, v, 1, 0}, f, nullptr, &Jv);
  CHECK(f[0] == Approx(-3.0));
  CHECK(Jv.matrix().coeff(4, 4) == Approx(-1.0));
  // Edge loads: total x force on the +x edge = P H L.
  const VecX e = biaxial_edge_forces(m, 0.06, 0.02, 0.5);
  double fx = 0, fy = 0;
  for (int i : {2, 5, 8}) fx += e[3 * i];
  for (int i : {6, 7, 8}) fy += e[3 * i + 1];
  CHECK(fx == Approx(0.06 * 0.5 * 2.0));
  CHECK(fy == Approx(0.02 * 0.5 * 2.0));
  CHECK(std::abs(e.sum()) < 1e-15);
}

TEST_CASE("without the load stiffness, the system Jacobian is the stored energy's Hessian alone", "[mechanics]") {
  // The quasi-static solver's fallback direction: Φ_k freezes the follower pressure, so its
  // Hessian has the membrane's stiffness and not the pressure's. The forces stay whole.
  const TriMesh m = grid_mesh();
  VecX x = perturbed(m, 0.08, 6, 1.2);
  for (int i = 0; i < m.num_nodes(); ++i) x[3 * i + 2] += 0.3 * std::sin(x[3 * i]);
  const VecX v = VecX::Zero(x.size());
  MechanicalSystem sys(m, 1e-3, 0.5);
  auto fe = std::make_unique<MembraneFETerm>(m, std::make_shared<FungLaw>(kAortic), 0.5);
  auto p = std::make_unique<PressureTerm>(m, 0.0106, true);
  const Eigen::MatrixXd membrane = analytic_dfdx(*fe, m.num_nodes(), x, v, 1.0);
  const Eigen::MatrixXd pressure = analytic_dfdx(*p, m.num_nodes(), x, v, 1.0);
  REQUIRE(pressure.cwiseAbs().maxCoeff() > 1e-3 * membrane.cwiseAbs().maxCoeff());
  sys.add_term(std::move(fe));
  sys.add_term(std::move(p));
  sys.finalize();
  VecX with, without;
  REQUIRE(sys.evaluate(State{x, v, 1.0, 0}, with, true, false));
  const Eigen::MatrixXd whole(sys.dfdx().matrix());
  REQUIRE(sys.evaluate(State{x, v, 1.0, 0}, without, true, false, false));
  const Eigen::MatrixXd stored(sys.dfdx().matrix());
  CHECK(relative_difference(whole, membrane + pressure) < 1e-12);
  CHECK(relative_difference(stored, membrane) < 1e-12);
  CHECK((with - without).cwiseAbs().maxCoeff() == 0.0);
}
