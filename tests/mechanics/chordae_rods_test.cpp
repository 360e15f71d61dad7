// Tension-only chordae rods (seed 5.2.2, Table 5.1): the force of a stretched rod against
// Hooke's law, nothing when slack, the Jacobian against finite differences and the force
// against the energy's gradient, for the linear and the Ogden law.
#include <catch2/catch.hpp>

#include "support/test_meshes.hpp"
#include "valve/mechanics/chordae_rods.hpp"

using namespace valve;

namespace {
// The seed's chord: E = 40 MPa, D = 0.5 mm, so EA = 40 · π · 0.5² / 4 = 7.854 N.
const double kArea = M_PI * 0.5 * 0.5 / 4;
const double kEA = 40.0 * kArea;
const auto kLinear = std::make_shared<LinearRodLaw>(40.0);
Rod linear_rod(int a, int b, double rest_length) { return Rod{a, b, rest_length, kArea, kLinear}; }
// The Texas TriValve deck's Anterior_Chordae (*Hyperelastic, OGDEN, N=3), incompressible.
std::shared_ptr<const RodLaw> deck_ogden() {
  OgdenParameters p;
  p.mu = {18.884147787615671, 22.682992286286954, 19.502933935159177};
  p.alpha = {98.253655062498183, 98.251894443391549, 98.253228660027887};
  return std::make_shared<OgdenRodLaw>(p);
}
}

TEST_CASE("a stretched chord pulls with EA (L - L0) / L0 along itself; a slack one does nothing", "[chordae]") {
  ChordaeTerm term({linear_rod(0, 1, 10.0)});
  VecX x(6), v = VecX::Zero(6), f = VecX::Zero(6);
  const Vec3 dir = Vec3(1, 2, 2) / 3.0;
  node3(x, 0) = Vec3(1, -1, 2);
  node3(x, 1) = node3(x, 0) + 10.5 * dir;  // 5 % stretch
  term.add(State{x, v, 1, 0}, f, nullptr, nullptr);
  const double T = kEA * 0.05;  // 0.3927 N
  CHECK((node3(f, 0) - T * dir).norm() < 1e-12);
  CHECK((node3(f, 1) + T * dir).norm() < 1e-12);
  CHECK(term.tensions(x)[0] == Approx(T).epsilon(1e-12));
  node3(x, 1) = node3(x, 0) + 9.0 * dir;  // slack
  f.setZero();
  term.add(State{x, v, 1, 0}, f, nullptr, nullptr);
  CHECK(f.norm() == 0);
  double e = 0;
  term.energy(State{x, v, 1, 0}, e);
  CHECK(e == 0);
}

TEST_CASE("chordae Jacobian matches finite differences and force is minus the energy gradient", "[chordae]") {
  // A branch point (node 1) between a tip (0) and two insertions (2, 3); one rod slack.
  const auto ogden = deck_ogden();
  // The Ogden rod stretched 1.1 %, where the deck's law is already steep (α ≈ 98).
  std::vector<Rod> rods{linear_rod(0, 1, 8.0), Rod{1, 2, 3.30, 0.356, ogden}, linear_rod(1, 3, 5.0)};
  ChordaeTerm term(rods);
  VecX x(12), v = VecX::Zero(12);
  x << 0, 0, -20, 0.3, 0.2, -11.5, 2.5, 0.4, -9.0, -1.0, 0.5, -9.5;
  REQUIRE(term.tensions(x)[0] > 0);
  REQUIRE(term.tensions(x)[1] > 0);
  REQUIRE(term.tensions(x)[2] == 0);
  const Eigen::MatrixXd A = test::analytic_dfdx(term, 4, x, v, 1);
  const Eigen::MatrixXd N = test::numeric_dfdx(term, x, v, 1, 1e-6);
  CHECK(test::relative_difference(A, N) < 1e-6);
  VecX f = VecX::Zero(12);
  term.add(State{x, v, 1, 0}, f, nullptr, nullptr);
  const VecX g = test::numeric_energy_force(term, x, v, 1, 1e-6);
  for (int i = 0; i < x.size(); ++i) CHECK(f[i] == Approx(g[i]).margin(1e-6));
}

TEST_CASE("a chord with a bad law, area or rest length is refused", "[chordae]") {
  CHECK_THROWS(ChordaeTerm({Rod{0, 1, 10.0, kArea, nullptr}}));
  CHECK_THROWS(ChordaeTerm({Rod{0, 1, 10.0, 0.0, kLinear}}));
  CHECK_THROWS(ChordaeTerm({Rod{0, 1, 0.0, kArea, kLinear}}));
}
