// Penalty contact (mechanics/penalty_contact.hpp): the closest-point queries against dense
// sampling, forces as the exact negative gradient of the energy, action and reaction,
// the Gauss-Newton Jacobian where it is exact, exclusions, and the edge-on crossing that
// node-face contact alone cannot see.
#include <Eigen/Geometry>
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <random>

#include "support/test_meshes.hpp"
#include "valve/core/error.hpp"
#include "valve/mechanics/penalty_contact.hpp"
#include "valve/mesh/closest_point.hpp"

using namespace valve;
using namespace valve::test;

namespace {

VecX forces(const PenaltyContactTerm& c, const VecX& x) {
  VecX f = VecX::Zero(x.size());
  c.add(State{x, VecX::Zero(x.size()), 1.0, 0}, f, nullptr, nullptr);
  return f;
}

double energy_of(const PenaltyContactTerm& c, const VecX& x) {
  double e = 0;
  REQUIRE(c.energy(State{x, VecX::Zero(x.size()), 1.0, 0}, e));
  return e;
}

// Contact forces at x of a term built with `without` and one built with `with` (options),
// after each has seen x: the first must see nothing.
VecX forces_seen_only_with(const TriMesh& m, const PenaltyContactOptions& without, const PenaltyContactOptions& with) {
  const VecX x = flatten(m.points);
  const std::vector<char> free(3 * m.num_nodes(), 0);
  PenaltyContactTerm blind(m, without, free), seeing(m, with, free);
  blind.update_couplings(x);
  seeing.update_couplings(x);
  CHECK(forces(blind, x).norm() == 0);
  const VecX f = forces(seeing, x);
  CHECK(seeing.statistics().active_pairs == 1);  // one pair, counted once
  return f;
}

// Two edges crossing 0.1 mm apart along z at their midpoints: k (δ − d)² / δ = 0.09 N split
// half and half over each edge's two nodes, pushing the edges apart along z; nothing else.
void check_edges_pushed_apart(const VecX& f, std::initializer_list<int> upper, std::initializer_list<int> lower,
                              std::initializer_list<int> untouched) {
  for (int i : upper) CHECK(node3(f, i).z() == Approx(0.045).epsilon(1e-9));
  for (int i : lower) CHECK(node3(f, i).z() == Approx(-0.045).epsilon(1e-9));
  for (int i : untouched) CHECK(node3(f, i).norm() == 0);
}

// y with every node turned by one generic rotation (no closest feature along an axis).
VecX turned_generically(VecX y) {
  const Mat3 R = Eigen::AngleAxisd(0.7, Vec3(1, 2, -0.5).normalized()).toRotationMatrix();
  for (int i = 0; i < y.size() / 3; ++i) node3(y, i) = R * node3(y, i);
  return y;
}

// f = −dE/dx in generic positions of two_sheets' node 3 (over the face, an edge, a vertex),
// with node 1 lifted by `lift` and everything turned: central differences of the energy.
void check_force_is_minus_energy_gradient(PenaltyContactTerm& c, const VecX& x, double lift, double margin) {
  for (const Vec3& p : {Vec3(0.4, 0.7, 0.12), Vec3(1.2, -0.1, 0.1), Vec3(-0.08, -0.1, 0.1)}) {
    VecX y = x;
    node3(y, 3) = p;
    y[3 * 1 + 2] = lift;
    y = turned_generically(y);
    c.update_couplings(y);
    const VecX fy = forces(c, y);
    REQUIRE(fy.norm() > 0);
    const double h = 1e-7;
    for (int k = 0; k < y.size(); ++k) {
      VecX yp = y, ym = y;
      yp[k] += h;
      ym[k] -= h;
      INFO("p = " << p.transpose() << ", dof " << k);
      CHECK(fy[k] == Approx(-(energy_of(c, yp) - energy_of(c, ym)) / (2 * h)).margin(margin));
    }
  }
}

// Two triangles at right angles, one in y = 0 below z = 0, one in x = 0 above z = gap, whose
// free edges 0-1 (along x at z = 0) and 3-4 (along y at z = gap) cross gap mm apart.
TriMesh crossing_free_edges(double gap) {
  TriMesh m;
  m.points.resize(6, 3);
  m.points << -1, 0, 0, 1, 0, 0, 0, 0, -2,  //
      0, -1, gap, 0, 1, gap, 0, 0, 2 + gap;
  m.triangles = {Tri(0, 1, 2), Tri(3, 4, 5)};
  m.leaflet = {0, 1};
  m.fill_defaults();
  return m;
}

// Distance from node p to triangle (a, b, c), and between edges (a, b) and (c, d), at positions y.
double node_face_distance(const VecX& y, int p, int a, int b, int c) {
  const Vec3 w = closest_point_weights(node3(y, p), node3(y, a), node3(y, b), node3(y, c));
  return (node3(y, p) - (w[0] * node3(y, a) + w[1] * node3(y, b) + w[2] * node3(y, c))).norm();
}
double edge_edge_distance(const VecX& y, int a, int b, int c, int d) {
  const Vec3 xa = node3(y, a), xb = node3(y, b), xc = node3(y, c), xd = node3(y, d);
  const auto [s, u] = closest_segment_parameters(xa, xb, xc, xd);
  return (xa + s * (xb - xa) - xc - u * (xd - xc)).norm();
}

// The smallest `distance` at `samples` + 1 evenly spaced points of the straight step from x.
template <class Distance>
double smallest_along(const VecX& x, const VecX& step, Distance distance, int samples = 100) {
  double smallest = std::numeric_limits<double>::infinity();
  for (int k = 0; k <= samples; ++k) smallest = std::min(smallest, distance(VecX(x + (k / double(samples)) * step)));
  return smallest;
}

}  // namespace

TEST_CASE("closest point on a triangle and between segments match dense sampling", "[mechanics][penalty_contact]") {
  std::mt19937 gen(11);
  std::uniform_real_distribution<double> u(-2, 2);
  auto rnd = [&] { return Vec3(u(gen), u(gen), u(gen)); };
  const int n = 300;
  for (int trial = 0; trial < 200; ++trial) {
    const Vec3 p = rnd(), a = rnd(), b = rnd(), c = rnd();
    const Vec3 w = closest_point_weights(p, a, b, c);
    CHECK(w.minCoeff() >= -1e-12);
    CHECK(w.sum() == Approx(1).margin(1e-12));
    const double ours = (p - (w[0] * a + w[1] * b + w[2] * c)).norm();
    double best = 1e300;
    for (int i = 0; i <= n; ++i)
      for (int j = 0; i + j <= n; ++j) {
        const double s = double(i) / n, t = double(j) / n;
        best = std::min(best, (p - (a + s * (b - a) + t * (c - a))).norm());
      }
    // Sampling can only be worse than the true minimum, by at most the grid spacing.
    const double spacing = std::max({(b - a).norm(), (c - a).norm(), (c - b).norm()}) / n;
    CHECK(ours <= best + 1e-12);
    CHECK(ours >= best - spacing);

    const Vec3 d = rnd();
    const auto [s, t] = closest_segment_parameters(a, b, c, d);
    CHECK(s >= 0);
    CHECK(s <= 1);
    CHECK(t >= 0);
    CHECK(t <= 1);
    const double seg = ((a + s * (b - a)) - (c + t * (d - c))).norm();
    double seg_best = 1e300;
    for (int i = 0; i <= 2000; ++i)
      for (int j = 0; j <= 200; ++j) {
        const double si = i / 2000.0, tj = j / 200.0;
        seg_best = std::min(seg_best, ((a + si * (b - a)) - (c + tj * (d - c))).norm());
      }
    CHECK(seg <= seg_best + 1e-12);
    CHECK(seg >= seg_best - ((d - c).norm() / 200 + (b - a).norm() / 2000));
  }
}

TEST_CASE("penalty contact: force magnitude, reaction, energy gradient", "[mechanics][penalty_contact]") {
  PenaltyContactOptions opt;  // δ = 0.25 mm, k = 1 N/mm
  const TriMesh m = two_sheets(0.1);
  PenaltyContactTerm c(m, opt, std::vector<char>(18, 0));
  VecX x = flatten(m.points);
  c.update_couplings(x);
  const VecX f = forces(c, x);
  // Node 3 is 0.1 mm over the face: f = k (δ − d)² / δ = 0.0225 / 0.25 = 0.09 N along +z,
  // and the triangle takes the reaction in proportion to the closest point's weights
  // (0.5, 0.25, 0.25).
  CHECK(node3(f, 3).z() == Approx(0.09).epsilon(1e-12));
  CHECK(node3(f, 3).head<2>().norm() < 1e-14);
  CHECK(node3(f, 0).z() == Approx(-0.045).epsilon(1e-12));
  CHECK(node3(f, 1).z() == Approx(-0.0225).epsilon(1e-12));
  CHECK(node3(f, 2).z() == Approx(-0.0225).epsilon(1e-12));
  Vec3 total = Vec3::Zero();
  for (int i = 0; i < 6; ++i) total += node3(f, i);
  CHECK(total.norm() < 1e-14);
  CHECK(energy_of(c, x) == Approx(0.15 * 0.15 * 0.15 / 0.75));  // k (δ − d)³ / (3 δ)
  // energy() adds to what it is given, as every term's must for the system's sum.
  double running = 2.0;
  REQUIRE(c.energy(State{x, VecX::Zero(x.size()), 1.0, 0}, running));
  CHECK(running == Approx(2.0 + 0.15 * 0.15 * 0.15 / 0.75));
  // Beyond the separation: no force, no energy.
  VecX far = x;
  far[3 * 3 + 2] = 0.3;
  CHECK(forces(c, far).norm() == 0);
  CHECK(energy_of(c, far) == 0);

  // f = −dE/dx in generic positions: node over the face, over an edge, over a vertex.
  check_force_is_minus_energy_gradient(c, x, 0.05, 1e-7);
}

TEST_CASE("barrier contact: IPC's log barrier beyond the offset, its force the energy's gradient", "[mechanics][penalty_contact]") {
  PenaltyContactOptions opt;
  opt.potential = ContactPotential::barrier;
  opt.offset = 0.05;      // ξ
  opt.separation = 0.25;  // ŝ
  opt.stiffness = 0.1;    // κ
  // The barrier excludes pairs within its reach in the rest shape: the sheets rest 1 mm apart.
  const TriMesh m = two_sheets(0.1);
  PenaltyContactTerm c(two_sheets(1.0), opt, std::vector<char>(18, 0));
  VecX x = flatten(m.points);
  c.update_couplings(x);
  // d = 0.1, s = d − ξ = 0.05: E = −κ (s − ŝ)² ln(s / ŝ), force −κ b'(s) on node 3 along +z.
  const double s = 0.05, sh = 0.25;
  CHECK(energy_of(c, x) == Approx(-0.1 * (s - sh) * (s - sh) * std::log(s / sh)).epsilon(1e-12));
  const VecX f = forces(c, x);
  CHECK(node3(f, 3).z() == Approx(0.1 * (2 * (s - sh) * std::log(s / sh) + (s - sh) * (s - sh) / s)).epsilon(1e-12));
  Vec3 total = Vec3::Zero();
  for (int i = 0; i < 6; ++i) total += node3(f, i);
  CHECK(total.norm() < 1e-14);
  // Beyond ξ + ŝ nothing; at or below ξ the energy is infinite.
  VecX far = x, through = x;
  far[3 * 3 + 2] = 0.31;
  through[3 * 3 + 2] = 0.04;
  CHECK(forces(c, far).norm() == 0);
  CHECK(energy_of(c, far) == 0);
  CHECK(std::isinf(energy_of(c, through)));
  // f = −dE/dx in generic positions.
  check_force_is_minus_energy_gradient(c, x, 0.02, 1e-6);
  // A pair within the reach in the rest shape is a neighbour, not a contact.
  PenaltyContactTerm touching(m, opt, std::vector<char>(18, 0));
  touching.update_couplings(x);
  CHECK(forces(touching, x).norm() == 0);
  // The Jacobian is the pair's Hessian projected to positive semi-definite: as df/dx it is
  // symmetric and negative semi-definite, and along the node's own normal motion, where
  // κ b''(s) dominates, it is the finite-difference Jacobian.
  PenaltyContactTerm cf(two_sheets(1.0), opt, std::vector<char>(18, 0));
  VecX z = flatten(m.points);
  node3(z, 3) = Vec3(0.6, 0.4, 0.12);
  cf.update_couplings(z);
  const VecX v = VecX::Zero(z.size());
  const auto ana = analytic_dfdx(cf, m.num_nodes(), z, v, 1.0);
  CHECK((ana - ana.transpose()).norm() < 1e-9 * ana.norm());
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(ana);
  CHECK(eig.eigenvalues().maxCoeff() < 1e-9 * ana.norm());
  const auto num = numeric_dfdx(cf, z, v, 1.0, 1e-7);
  // The node's motion along the face normal: b''(s) dominates, the projection keeps it.
  CHECK(ana(11, 11) == Approx(num(11, 11)).epsilon(0.02));
  // In exact mode the Jacobian is the whole Hessian: every entry the finite-difference
  // Jacobian's, with the positive eigenvalue (the b'(s) ∇²d part, sliding over the face) the
  // projection clamps.
  cf.set_jacobian_mode(JacobianMode::exact);
  const auto exact = analytic_dfdx(cf, m.num_nodes(), z, v, 1.0);
  CHECK((exact - num).norm() < 1e-4 * num.norm());
  CHECK(Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(exact).eigenvalues().maxCoeff() > 1e-6 * exact.norm());
  CHECK((ana - num).norm() > 1e-3 * num.norm());
}

TEST_CASE("barrier contact: two leaflets that start within the reach act within half their start gap", "[mechanics][penalty_contact]") {
  // Rest 1 mm apart, the solve starting 0.1 mm apart (as two leaflets' attachments sewn onto
  // the same stretch of distended root wall): the pair's reach shrinks to half its start gap
  // (0.05 mm), so it does not push at the start, pushes once closer, and no step takes it
  // through the other sheet.
  PenaltyContactOptions opt;
  opt.potential = ContactPotential::barrier;
  opt.separation = 0.25;
  const VecX start = flatten(two_sheets(0.1).points);
  PenaltyContactTerm told(two_sheets(1.0), opt, std::vector<char>(18, 0));
  PenaltyContactTerm untold(two_sheets(1.0), opt, std::vector<char>(18, 0));
  told.start_at(start);
  told.update_couplings(start);
  untold.update_couplings(start);
  CHECK(told.statistics().narrow_pairs == 1);  // node 3 over the other sheet's triangle
  CHECK(untold.statistics().narrow_pairs == 0);
  CHECK(forces(untold, start).norm() > 0);
  CHECK(forces(told, start).norm() == 0);
  // The reach is half the start gap: idle at 0.06 mm, pushing at 0.04 mm.
  const VecX beyond_half = flatten(two_sheets(0.06).points), within_half = flatten(two_sheets(0.04).points);
  told.update_couplings(beyond_half);
  CHECK(forces(told, beyond_half).norm() == 0);
  told.update_couplings(within_half);
  CHECK(forces(told, within_half).norm() > 0);
  const VecX closer = flatten(two_sheets(0.03).points);
  told.update_couplings(closer);
  const VecX pushed = forces(told, closer);
  CHECK(pushed[3 * 3 + 2] > 0);  // node 3 pushed back up, away from the face below it
  CHECK(pushed.sum() == Approx(0).margin(1e-12 * pushed.norm()));  // with its reaction
  // The force is the narrowed energy's gradient (central differences along node 3's z).
  const double h = 1e-7;
  VecX up = closer, down = closer;
  up[3 * 3 + 2] += h;
  down[3 * 3 + 2] -= h;
  CHECK(pushed[3 * 3 + 2] == Approx(-(energy_of(told, up) - energy_of(told, down)) / (2 * h)).epsilon(1e-5));
  told.update_couplings(start);
  VecX through = VecX::Zero(18);
  through[3 * 3 + 2] = -0.2;  // to 0.1 mm past the face
  CHECK(told.step_ratio(start, through) > 1);
  // A pair beyond the reach at the start acts with the whole reach once it comes close.
  PenaltyContactTerm far_start(two_sheets(1.0), opt, std::vector<char>(18, 0));
  far_start.start_at(flatten(two_sheets(0.5).points));
  far_start.update_couplings(start);
  CHECK(far_start.statistics().narrow_pairs == 0);
  CHECK(forces(far_start, start).norm() > 0);
}

TEST_CASE("barrier contact: a chord point near a sheet is not a narrow pair", "[mechanics][penalty_contact]") {
  // Chord branch points are nodes without triangles (chordae_attachment.hpp): no contact
  // pair ever queries them, so one lying within the reach of a sheet where the solve starts
  // is neither a narrow pair nor counted as one.
  TriMesh m;
  m.points.resize(4, 3);
  m.points << 0, 0, 0, 2, 0, 0, 0, 2, 0, 0.5, 0.5, 0.1;
  m.triangles = {Tri(0, 1, 2)};
  m.leaflet = {0};
  m.fill_defaults();
  PenaltyContactOptions opt;
  opt.potential = ContactPotential::barrier;
  opt.separation = 0.25;
  PenaltyContactTerm c(m, opt, std::vector<char>(12, 0));
  const VecX x = flatten(m.points);
  c.update_couplings(x);
  CHECK(c.statistics().narrow_pairs == 0);
  CHECK(forces(c, x).norm() == 0);
}

TEST_CASE("barrier contact: a narrow pair's offset shrinks with its reach", "[mechanics][penalty_contact]") {
  // ξ = 0.02, ŝ = 0.25 mm, the pair starting 0.1 mm apart: both shrink by 0.1 / (2 · 0.27), so
  // the pair acts below 0.05 mm and keeps 0.0037 mm (its own offset), not 0.02 mm.
  PenaltyContactOptions opt;
  opt.potential = ContactPotential::barrier;
  opt.offset = 0.02;
  opt.separation = 0.25;
  PenaltyContactTerm c(two_sheets(1.0), opt, std::vector<char>(18, 0));
  const VecX start = flatten(two_sheets(0.1).points);
  c.start_at(start);
  const double offset = 0.02 * 0.1 / (2 * 0.27);
  for (double gap : {0.06, 0.03, 0.01, 0.005}) {
    const VecX x = flatten(two_sheets(gap).points);
    c.update_couplings(x);
    CHECK((forces(c, x).norm() > 0) == (gap < 0.05));
    CHECK(std::isfinite(energy_of(c, x)));
  }
  const VecX inside = flatten(two_sheets(0.9 * offset).points);
  c.update_couplings(inside);
  CHECK(std::isinf(energy_of(c, inside)));
  c.update_couplings(start);
  VecX to_offset = VecX::Zero(18);
  to_offset[3 * 3 + 2] = -(0.1 - offset);  // node 3 down to the narrow offset
  CHECK(c.step_ratio(start, to_offset) > 1);
}

TEST_CASE("barrier contact: pairs that start touching or within one leaflet are excluded", "[mechanics][penalty_contact]") {
  // Two leaflets starting closer than a thousandth of the reach (0.25 µm here) have no gap of
  // their own to keep; two parts of one leaflet within the reach are neighbours at a bend.
  PenaltyContactOptions opt;
  opt.potential = ContactPotential::barrier;
  opt.separation = 0.25;
  const VecX touching = flatten(two_sheets(1e-4).points), closer = flatten(two_sheets(1e-5).points);
  PenaltyContactTerm two_leaflets(two_sheets(1.0), opt, std::vector<char>(18, 0));
  two_leaflets.start_at(touching);
  two_leaflets.update_couplings(closer);
  CHECK(two_leaflets.statistics().narrow_pairs == 0);
  CHECK(forces(two_leaflets, closer).norm() == 0);  // a narrow pair would push here
  TriMesh one = two_sheets(1.0);
  one.leaflet = {0, 0};
  PenaltyContactTerm within(one, opt, std::vector<char>(18, 0));
  const VecX start = flatten(two_sheets(0.1).points);
  within.start_at(start);
  within.update_couplings(flatten(two_sheets(0.03).points));
  CHECK(within.statistics().narrow_pairs == 0);
  CHECK(forces(within, flatten(two_sheets(0.03).points)).norm() == 0);
}

TEST_CASE("barrier contact: two leaflets close at rest but apart where the mesh starts push back", "[mechanics][penalty_contact]") {
  // A graft's rest shape is its own cut shape, placed beside the others: the rest distance
  // between two leaflets means nothing, the start distance does. Within one leaflet the rest
  // shape still decides (neighbours at a sharp bend).
  PenaltyContactOptions opt;
  opt.potential = ContactPotential::barrier;
  opt.separation = 0.25;
  const VecX near = flatten(two_sheets(0.1).points);
  TriMesh apart_at_start = two_sheets(0.1);
  apart_at_start.initial = two_sheets(1.0).points;
  PenaltyContactTerm two_leaflets(apart_at_start, opt, std::vector<char>(18, 0));
  two_leaflets.update_couplings(near);
  CHECK(forces(two_leaflets, near).norm() > 0);
  TriMesh one_leaflet = apart_at_start;
  one_leaflet.leaflet = {0, 0};
  PenaltyContactTerm within(one_leaflet, opt, std::vector<char>(18, 0));
  within.update_couplings(near);
  CHECK(forces(within, near).norm() == 0);
  // Without start positions the rest shape is the start: two leaflets close at rest act only
  // within half their distance there.
  PenaltyContactTerm rest_only(two_sheets(0.1), opt, std::vector<char>(18, 0));
  rest_only.update_couplings(near);
  CHECK(rest_only.statistics().narrow_pairs > 0);
  CHECK(forces(rest_only, near).norm() == 0);
  const VecX closer = flatten(two_sheets(0.03).points);
  rest_only.update_couplings(closer);
  CHECK(forces(rest_only, closer).norm() > 0);
}

namespace {

// The barrier of the pair-Hessian tests: ξ = 0.05, ŝ = 0.25 mm, κ = 0.1 N/mm.
PenaltyContactOptions pair_hessian_barrier() {
  PenaltyContactOptions opt;
  opt.potential = ContactPotential::barrier;
  opt.offset = 0.05;
  opt.separation = 0.25;
  opt.stiffness = 0.1;
  return opt;
}

// two_sheets(1)'s node 3 moved to p, the lower face tilted by lifting node 1, all turned.
VecX sheets_with_node_3_at(const Vec3& p) {
  VecX y = flatten(two_sheets(1.0).points);
  node3(y, 3) = p;
  y[3 * 1 + 2] = 0.02;
  return turned_generically(y);
}

// crossing_free_edges(1)'s upper edge skewed and brought 0.12 mm from the lower one, shifted
// along x by `shift`, all turned.
VecX free_edges_skewed(double shift) {
  VecX y = flatten(crossing_free_edges(1.0).points);
  for (int i : {3, 4, 5}) node3(y, i) += Vec3(shift, 0.2 * (i - 3), -0.88);
  y[3 * 0 + 1] = 0.05;
  return turned_generically(y);
}

}  // namespace

TEST_CASE("barrier contact: the closed-form pair Hessian is the finite-difference one on every closest feature", "[mechanics][penalty_contact][fd]") {
  const VecX v = VecX::Zero(18);
  auto check_exact_jacobian = [&](PenaltyContactTerm& c, const VecX& y) {
    c.set_jacobian_mode(JacobianMode::exact);
    c.update_couplings(y);
    const auto exact = analytic_dfdx(c, 6, y, v, 1.0);
    REQUIRE(c.statistics().active_pairs >= 1);
    const auto num = numeric_dfdx(c, y, v, 1.0, 1e-7);
    CHECK(relative_difference(exact, num) < 1e-5);
  };
  // Node 3 over the lower face (interior), beyond its edge 1-2 (closest point on the edge) and
  // beyond its vertex 0.
  PenaltyContactTerm sheets(two_sheets(1.0), pair_hessian_barrier(), std::vector<char>(18, 0));
  for (const Vec3& p : {Vec3(0.4, 0.7, 0.12), Vec3(1.2, 0.95, 0.1), Vec3(-0.08, -0.1, 0.1)}) {
    INFO("node 3 at " << p.transpose());
    check_exact_jacobian(sheets, sheets_with_node_3_at(p));
  }
  // Two free edges: closest points inside both edges, then beyond node 1.
  PenaltyContactTerm edges(crossing_free_edges(1.0), pair_hessian_barrier(), std::vector<char>(18, 0));
  for (double shift : {0.3, 1.1}) {
    INFO("upper edge shifted along x by " << shift);
    check_exact_jacobian(edges, free_edges_skewed(shift));
  }
}

TEST_CASE("barrier contact: the projected pair Hessian is the exact one's positive semi-definite part", "[mechanics][penalty_contact]") {
  // One active pair, so the whole Jacobian is that pair's: its projection, computed here by a
  // dense eigendecomposition of the whole 18 × 18 matrix, is what the term's projected mode
  // (an eigenproblem in the ≤ 5-dimensional range of the pair's Hessian) must give.
  const VecX v = VecX::Zero(18);
  auto check_projection = [&](PenaltyContactTerm& c, const VecX& y) {
    c.set_jacobian_mode(JacobianMode::exact);
    c.update_couplings(y);
    const Eigen::MatrixXd hessian = -analytic_dfdx(c, 6, y, v, 1.0);
    REQUIRE(c.statistics().active_pairs == 1);
    c.set_jacobian_mode(JacobianMode::projected);
    c.update_couplings(y);
    const Eigen::MatrixXd projected = -analytic_dfdx(c, 6, y, v, 1.0);
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(hessian);
    REQUIRE(eig.eigenvalues().minCoeff() < -1e-3 * eig.eigenvalues().maxCoeff());  // something to clamp
    const Eigen::MatrixXd expected =
        eig.eigenvectors() * eig.eigenvalues().cwiseMax(0.0).asDiagonal() * eig.eigenvectors().transpose();
    CHECK((projected - expected).norm() < 1e-10 * expected.norm());
  };
  // Node 3 over the lower face and beyond its edge 1-2 (edge pairs off: near the rim node 3's
  // edges near that edge too). Not beyond a vertex: that vertex is as close to node 3's
  // triangle, a second pair.
  PenaltyContactOptions faces_only = pair_hessian_barrier();
  faces_only.edge_contact = false;
  PenaltyContactTerm sheets(two_sheets(1.0), faces_only, std::vector<char>(18, 0));
  for (const Vec3& p : {Vec3(0.4, 0.7, 0.12), Vec3(1.2, 0.95, 0.1)}) {
    INFO("node 3 at " << p.transpose());
    check_projection(sheets, sheets_with_node_3_at(p));
  }
  // Two edges, closest points inside both (beyond an end node, that node nears the other
  // edge's triangle: more pairs).
  PenaltyContactTerm edges(crossing_free_edges(1.0), pair_hessian_barrier(), std::vector<char>(18, 0));
  check_projection(edges, free_edges_skewed(0.3));
}

namespace {

// Node 3's step dx toward face (0, 1, 2), cut to the contact's step bound, keeps its whole
// straight path (sampled) beyond `offset`; false when the bound does not cut the step.
bool cut_step_keeps_node_3_off_face(const PenaltyContactTerm& c, const VecX& x, const VecX& dx, double offset) {
  const double ratio = c.step_ratio(x, dx);
  if (ratio <= 1) return false;
  const auto node_to_face = [](const VecX& y) { return node_face_distance(y, 3, 0, 1, 2); };
  CHECK(smallest_along(x, dx / ratio, node_to_face, 50) > offset);
  return true;
}

// The energy and forces at y of `kept` (a term whose candidate list was built elsewhere) are a
// fresh two_sheets(1.0) term's there, one that builds its list at y.
void check_kept_list_matches_fresh(const PenaltyContactTerm& kept, const VecX& y, const PenaltyContactOptions& opt) {
  PenaltyContactTerm fresh(two_sheets(1.0), opt, std::vector<char>(18, 0));
  fresh.update_couplings(y);
  CHECK(energy_of(kept, y) == Approx(energy_of(fresh, y)).margin(1e-12));
  CHECK((forces(kept, y) - forces(fresh, y)).norm() <= 1e-12);
}

}  // namespace

TEST_CASE("barrier contact: a step within the ratio keeps every pair beyond the offset", "[mechanics][penalty_contact]") {
  // Random steps of a node over a triangle, scaled to the step bound: the distance along the
  // whole straight path stays above ξ (sampled), and a step 1.5x the bound would get closer.
  PenaltyContactOptions opt;
  opt.potential = ContactPotential::barrier;
  opt.offset = 0.1;
  const TriMesh m = two_sheets(0.3);
  PenaltyContactTerm c(two_sheets(1.0), opt, std::vector<char>(18, 0));
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  int bounded = 0;
  for (int trial = 0; trial < 200; ++trial) {
    VecX x = flatten(m.points);
    node3(x, 3) = Vec3(0.3 + 0.3 * u(rng), 0.3 + 0.2 * u(rng), 0.12 + 0.15 * std::abs(u(rng)));
    c.update_couplings(x);
    VecX dx = VecX::Zero(x.size());
    for (int k = 0; k < 18; ++k) dx[k] = 0.3 * u(rng);
    node3(dx, 3).z() = -std::abs(node3(dx, 3).z()) - 0.2;  // toward the face
    bounded += cut_step_keeps_node_3_off_face(c, x, dx, opt.offset);
  }
  CHECK(bounded > 50);
}

TEST_CASE("barrier contact: a candidate list kept while nodes move finds the contacts a fresh one finds", "[mechanics][penalty_contact]") {
  // The list is built with node 3 1 mm over the lower face (beyond the reach ξ + ŝ = 0.35 mm);
  // node 3 then comes down 0.45-0.85 mm, within the list's tolerance (1.5 mm: no rebuild).
  // Where the pair is still beyond the reach its gap is recorded by a lower bound (the build's
  // distance less the move), not measured; where it has come within, it must act as in a term
  // built there. A bound that forgot the move (1 mm) would miss every pair that came within.
  // Steps toward the face, scaled to the step bound, keep the path above ξ either way.
  PenaltyContactOptions opt;
  opt.potential = ContactPotential::barrier;
  opt.offset = 0.1;
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1, 1);
  int within = 0, bounded = 0;
  for (int trial = 0; trial < 100; ++trial) {
    PenaltyContactTerm kept(two_sheets(1.0), opt, std::vector<char>(18, 0));
    VecX x = flatten(two_sheets(0.3).points);
    node3(x, 3) = Vec3(0.3 + 0.3 * u(rng), 0.3 + 0.2 * u(rng), 1.0);
    kept.update_couplings(x);
    node3(x, 3) += Vec3(0.1 * u(rng), 0.1 * u(rng), -1.0).normalized() * (0.65 + 0.2 * u(rng));
    kept.update_couplings(x);
    if (node_face_distance(x, 3, 0, 1, 2) < 0.35) ++within;
    check_kept_list_matches_fresh(kept, x, opt);

    VecX dx = VecX::Zero(x.size());
    for (int k = 0; k < 18; ++k) dx[k] = 0.05 * u(rng);
    node3(dx, 3) += Vec3(0.2 * u(rng), 0.2 * u(rng), -1.25 + 0.25 * u(rng));  // toward the face
    bounded += cut_step_keeps_node_3_off_face(kept, x, dx, opt.offset);
  }
  CHECK(within > 20);
  CHECK(within < 80);
  CHECK(bounded > 50);
}

TEST_CASE("barrier contact: a candidate list kept while both leaflets move finds the contacts a fresh one finds", "[mechanics][penalty_contact]") {
  // The list is built with node 3 1 mm over the lower face; then the upper leaflet moves down
  // and the lower one up, each as a whole, by 0.45-0.85 mm together (within the list's 1.5 mm
  // tolerance: no rebuild). A pair's gap bound is its build distance less its nodes' motion
  // relative to each other: a bound that counted one leaflet's motion only would miss the pairs
  // that came within. Then at trial states a little further on (no couplings refreshed there).
  PenaltyContactOptions opt;
  opt.potential = ContactPotential::barrier;
  opt.offset = 0.1;
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1, 1), share(0.2, 0.8);
  auto move_leaflet = [](VecX& y, int first, const Vec3& by) {
    for (int i = first; i < first + 3; ++i) node3(y, i) += by;
  };
  int within = 0;
  for (int trial = 0; trial < 100; ++trial) {
    PenaltyContactTerm kept(two_sheets(1.0), opt, std::vector<char>(18, 0));
    VecX x = flatten(two_sheets(1.0).points);
    move_leaflet(x, 3, Vec3(0.3 * u(rng), 0.2 * u(rng), 0));
    kept.update_couplings(x);
    const double approach = 0.65 + 0.2 * u(rng), down = share(rng) * approach;
    move_leaflet(x, 3, Vec3(0.05 * u(rng), 0.05 * u(rng), -down));
    move_leaflet(x, 0, Vec3(0.05 * u(rng), 0.05 * u(rng), approach - down));
    kept.update_couplings(x);
    if (node_face_distance(x, 3, 0, 1, 2) < 0.35) ++within;
    check_kept_list_matches_fresh(kept, x, opt);

    VecX y = x;
    move_leaflet(y, 3, Vec3(0, 0, -0.03 * share(rng)));
    move_leaflet(y, 0, Vec3(0, 0, 0.03 * share(rng)));
    check_kept_list_matches_fresh(kept, y, opt);
  }
  CHECK(within > 20);
  CHECK(within < 80);
}

TEST_CASE("barrier contact: a face hinging beside a node is measured along the step, not cut to the gap", "[mechanics][penalty_contact]") {
  // Node 3 hangs 0.1 mm over the lower face at barycentric weight 1/4 of its node 2. Raising
  // node 2 by a hinges the face about its edge 0-1: the face under the node rises by a/4, so
  // the gap is 0.1 − a/4 (less the tilt's small cosine). The supporting-plane bound alone
  // counts node 2's whole rise as closing: a / (0.8 · 0.1), 2.5 for a = 0.2, whose whole step
  // keeps 0.05 mm. Followed on past the step, the gap falls to 0.2 of its start at a rise of
  // 0.319 mm: the ratio lies between 0.2 / 0.319 = 0.627 and 1, well below 1 (BDF2 grows its
  // next step by what the ratio leaves). a = 0.6 reaches the face at t = 2/3, so the bound
  // must stay above 1.5.
  PenaltyContactOptions opt;
  opt.potential = ContactPotential::barrier;
  PenaltyContactTerm c(two_sheets(1.0), opt, std::vector<char>(18, 0));  // apart at rest
  const VecX x = flatten(two_sheets(0.1).points);
  c.update_couplings(x);
  auto gap_along = [&](const VecX& step) {
    return smallest_along(x, step, [](const VecX& y) { return node_face_distance(y, 3, 0, 1, 2); });
  };
  for (double rise : {0.2, 0.6}) {
    INFO("node 2 raised by " << rise << " mm");
    VecX hinge = VecX::Zero(18);
    hinge[3 * 2 + 2] = rise;
    const double ratio = c.step_ratio(x, hinge);
    if (rise < 0.4) {
      CHECK(ratio >= 0.2 / 0.319);
      CHECK(ratio <= 0.8);
      CHECK(gap_along(hinge / ratio) > 0.2 * 0.1);
      CHECK(gap_along(hinge) == Approx((0.1 - rise / 4) / std::sqrt(1 + rise * rise / 4)).epsilon(1e-3));
    } else {
      CHECK(ratio > 1.5);
      CHECK(gap_along(hinge / ratio) > 0.2 * 0.1);
    }
  }
}

TEST_CASE("barrier contact: a free edge tilting about the crossing point is measured along the step", "[mechanics][penalty_contact]") {
  // Leaflet 0 hangs below its edge (-1,0,0)-(1,0,0), leaflet 1 stands above its edge
  // (0,-1,h)-(0,1,h), h = 0.1 (1 mm apart at rest). Turning leaflet 1 by 30° about the x axis
  // through (0,0,h), taken as a straight step, keeps its edge's midpoint on the crossing: the
  // edges' distance falls only to h cos 30°. The supporting-plane bound counts the lower end's
  // drop of sin 30° as closing, 0.5 / (0.8 h) = 6.25; measured along the step the whole step
  // may go.
  const double h = 0.1, angle = std::acos(-1.0) / 6;
  PenaltyContactOptions opt;
  opt.potential = ContactPotential::barrier;
  PenaltyContactTerm c(crossing_free_edges(1.0), opt, std::vector<char>(18, 0));
  const VecX x = flatten(crossing_free_edges(h).points);
  c.update_couplings(x);
  VecX turn = VecX::Zero(18);
  for (int i : {3, 4, 5}) {
    const Vec3 r = node3(x, i) - Vec3(0, 0, h);
    const Vec3 turned(r.x(), std::cos(angle) * r.y() - std::sin(angle) * r.z(),
                      std::sin(angle) * r.y() + std::cos(angle) * r.z());
    node3(turn, i) = turned - r;
  }
  CHECK(c.step_ratio(x, turn) <= 1);
  const double smallest = smallest_along(x, turn, [](const VecX& y) { return edge_edge_distance(y, 0, 1, 3, 4); });
  CHECK(smallest == Approx(h * std::cos(angle)).epsilon(1e-3));
}

TEST_CASE("penalty contact Jacobian: exact over a fixed face, symmetric and non-positive", "[mechanics][penalty_contact][fd]") {
  const TriMesh m = two_sheets(0.1);
  std::vector<char> fixed(18, 0);
  for (int d = 0; d < 9; ++d) fixed[d] = 1;  // the lower triangle is fixed
  PenaltyContactTerm c(m, PenaltyContactOptions{}, fixed);
  VecX x = flatten(m.points);
  node3(x, 3) = Vec3(0.6, 0.4, 0.08);
  c.update_couplings(x);
  const VecX v = VecX::Zero(x.size());
  const auto num = numeric_dfdx(c, x, v, 1.0, 1e-7);
  const auto ana = analytic_dfdx(c, m.num_nodes(), x, v, 1.0);
  // Node 3's own block: for a node over the face of a triangle that does not move, d is
  // linear in the node's position and Gauss-Newton is exact.
  CHECK((ana.block<3, 3>(9, 9) - num.block<3, 3>(9, 9)).norm() < 1e-6);
  CHECK(ana.block<3, 3>(9, 9)(2, 2) == Approx(-2 * 0.17 / 0.25));  // −2 k (δ − d) / δ at d = 0.08
  CHECK((ana - ana.transpose()).norm() < 1e-14);
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(ana);
  CHECK(eig.eigenvalues().maxCoeff() < 1e-12);
}

TEST_CASE("penalty contact stops free edges crossing edge-on", "[mechanics][penalty_contact]") {
  // The free edges cross 0.1 mm apart while every node is at least 1 mm from the other
  // triangle: only the edge pair sees it.
  const TriMesh m = crossing_free_edges(0.1);
  PenaltyContactOptions faces_only;
  faces_only.edge_contact = false;
  check_edges_pushed_apart(forces_seen_only_with(m, faces_only, PenaltyContactOptions{}), {3, 4}, {0, 1}, {2, 5});
}

TEST_CASE("penalty contact with interior edges stops ridges crossing", "[mechanics][penalty_contact]") {
  // Two tents of two triangles each: A's ridge 0-1 along x at z = 0 with its slopes going
  // down to z = -2, B's ridge 4-5 along y at z = 0.1 with its slopes going up to z = 2.1.
  // The ridges (interior edges) cross 0.1 mm apart at the origin; every node lies at least
  // 0.78 mm from the other tent's faces and every boundary edge at least 0.9 mm from the other
  // tent: neither node-face nor free-edge pairs see it, only the interior edge pair.
  TriMesh m;
  m.points.resize(8, 3);
  m.points << -1, 0, 0, 1, 0, 0, 0, -2, -2, 0, 2, -2,  //
      0, -1, 0.1, 0, 1, 0.1, -2, 0, 2.1, 2, 0, 2.1;
  m.triangles = {Tri(0, 1, 2), Tri(1, 0, 3), Tri(4, 5, 6), Tri(5, 4, 7)};
  m.leaflet = {0, 0, 1, 1};
  m.fill_defaults();
  PenaltyContactOptions all_edges;
  all_edges.interior_edges = true;
  check_edges_pushed_apart(forces_seen_only_with(m, PenaltyContactOptions{}, all_edges), {4, 5}, {0, 1}, {2, 3, 6, 7});
}

TEST_CASE("penalty contact step ratio bounds each pair's closing along its normal", "[mechanics][penalty_contact]") {
  // Leaflet 1 is leaflet 0 lifted by h: every top node lies straight above a bottom vertex,
  // so every node-face pair's closest point is that vertex and its normal is ±z. Default
  // D = δ + 4 max(δ, mean edge / 2) with edges of 2, 2 and 2√2 mm, so L = (D − δ)/4 = mean
  // edge / 2, and a step may take a node 2L from where the candidate list was built.
  auto lifted_pair = [](double h) {
    TriMesh m;
    m.points.resize(6, 3);
    m.points << 0, 0, 0, 2, 0, 0, 0, 2, 0, 0, 0, h, 2, 0, h, 0, 2, h;
    m.triangles = {Tri(0, 1, 2), Tri(3, 4, 5)};
    m.leaflet = {0, 1};
    m.fill_defaults();
    return m;
  };
  const double delta = 0.25, L = (4 + 2 * std::sqrt(2.0)) / 3 / 2;
  CHECK(L == Approx(1.1381).margin(1e-4));
  auto move_top = [](const Vec3& d) {
    VecX dx = VecX::Zero(18);
    for (int i = 3; i < 6; ++i) dx.segment<3>(3 * i) = d;
    return dx;
  };
  PenaltyContactOptions faces_only;
  faces_only.edge_contact = false;
  for (double h : {0.1, 1.0, 3.5}) {
    INFO("h = " << h);
    const TriMesh m = lifted_pair(h);
    const VecX x = flatten(m.points);
    PenaltyContactTerm c(m, faces_only, std::vector<char>(18, 0));
    // No state seen yet: every node within 0.4 δ.
    CHECK(c.step_ratio(x, move_top(Vec3(0, 0, -0.05))) == Approx(0.05 / (0.4 * delta)));
    c.update_couplings(x);
    // Straight down by s: every pair closes by s, against 0.8 max(δ, h); and the top nodes
    // move s of their 2L.
    const double s = 0.05;
    CHECK(c.step_ratio(x, move_top(Vec3(0, 0, -s))) ==
          Approx(std::max(s / (0.8 * std::max(delta, h)), s / (2 * L))));
    // Moving apart closes nothing; sliding sideways neither (an absolute bound on each
    // node's move would give 0.3 / (0.8 max(δ, h)), 1.5 at h = 0.1).
    CHECK(c.step_ratio(x, move_top(Vec3(0, 0, 0.3))) == Approx(0.3 / (2 * L)));
    CHECK(c.step_ratio(x, move_top(Vec3(0.3, 0, 0))) == Approx(0.3 / (2 * L)));
    // The whole valve moving together closes nothing either.
    VecX all = VecX::Zero(18);
    for (int i = 0; i < 6; ++i) all.segment<3>(3 * i) = Vec3(0.2, -0.1, 0.4);
    CHECK(c.step_ratio(x, all) == Approx(Vec3(0.2, -0.1, 0.4).norm() / (2 * L)));
    // After the whole valve has moved 0.5 L (less than L: the candidate list is kept), a
    // node may move 2L − 0.5 L more; the pairs' gaps are those at the new state.
    VecX y = x;
    for (int i = 0; i < 6; ++i) y[3 * i] += 0.5 * L;
    c.update_couplings(y);
    CHECK(c.step_ratio(y, move_top(Vec3(0.3, 0, 0))) == Approx((0.5 * L + 0.3) / (2 * L)));
    CHECK(c.step_ratio(y, move_top(Vec3(1.5 * L, 0, 0))) == Approx(1.0));
  }
}

TEST_CASE("penalty contact step ratio of two free edges crossing edge-on", "[mechanics][penalty_contact]") {
  // Leaflet 0 hangs below its edge (-1,0,0)-(1,0,0), leaflet 1 stands above its edge
  // (0,-1,h)-(0,1,h): the edges cross h apart, every node is farther from the other face
  // (sqrt(1 + h²) and more), so the edge pair sets the ratio. Lowering leaflet 1 by s closes it
  // by s: s / (0.8 h); raising it closes nothing (the candidate-list term remains).
  const double h = 1.0, s = 0.05;
  TriMesh m;
  m.points.resize(6, 3);
  m.points << -1, 0, 0, 1, 0, 0, 0, 0, -1, 0, -1, h, 0, 1, h, 0, 0, h + 1;
  m.triangles = {Tri(0, 1, 2), Tri(3, 4, 5)};
  m.leaflet = {0, 1};
  m.fill_defaults();
  const VecX x = flatten(m.points);
  PenaltyContactTerm c(m, PenaltyContactOptions{}, std::vector<char>(18, 0));
  c.update_couplings(x);
  const double L = (c.detection_distance() - 0.25) / 4;
  VecX down = VecX::Zero(18), up = VecX::Zero(18);
  for (int i = 3; i < 6; ++i) down[3 * i + 2] = -s, up[3 * i + 2] = s;
  CHECK(c.step_ratio(x, down) == Approx(s / (0.8 * h)));
  CHECK(c.step_ratio(x, up) == Approx(s / (2 * L)));
}

TEST_CASE("penalty contact: a step within the ratio never closes a pair by more than 0.8 of its gap", "[mechanics][penalty_contact]") {
  // Random steps on two curved sheets with every pair type (faces and edges): whenever
  // step_ratio accepts a step (<= 1), each cross-sheet node-face and boundary-edge/edge
  // distance d, measured by brute force over all pairs, keeps d' >= min(0.2 d, δ) (candidates close by
  // at most 0.8 max(δ, d); non-candidates stay beyond δ) -- checked where d >= δ.
  std::mt19937 gen(5);
  std::normal_distribution<double> noise(0, 1);
  // Two wavy 3x3-node sheets 0.6 mm apart, the upper one shifted by a third of a cell.
  const TriMesh lower = grid_mesh(2.0);
  TriMesh m;
  m.points.resize(18, 3);
  for (int i = 0; i < 9; ++i) {
    m.points.row(i) = lower.points.row(i);
    m.points.row(i + 9) = lower.points.row(i) + Eigen::RowVector3d(0.33, 0.2, 0.6);
  }
  for (int i = 0; i < 18; ++i) m.points(i, 2) += 0.15 * std::sin(1.3 * m.points(i, 0) + 0.7 * m.points(i, 1));
  for (const Tri& t : lower.triangles) {
    m.triangles.push_back(t);
    m.leaflet.push_back(0);
  }
  for (const Tri& t : lower.triangles) {
    m.triangles.push_back(Tri(t[0] + 9, t[1] + 9, t[2] + 9));
    m.leaflet.push_back(1);
  }
  m.fill_defaults();
  const VecX x = flatten(m.points);
  const double delta = 0.25;
  PenaltyContactTerm c(m, PenaltyContactOptions{}, std::vector<char>(x.size(), 0));
  c.update_couplings(x);
  const auto boundary = [&] {  // each sheet's boundary edges: the 8 outer edges of its grid
    std::vector<std::pair<int, int>> edges;
    for (int sheet = 0; sheet < 2; ++sheet)
      for (const auto& [a, b] : {std::pair{0, 1}, {1, 2}, {2, 5}, {5, 8}, {8, 7}, {7, 6}, {6, 3}, {3, 0}})
        edges.emplace_back(a + 9 * sheet, b + 9 * sheet);
    return edges;
  }();
  auto cross_distances = [&](const VecX& y) {
    std::vector<double> d;
    // Boundary edge of one sheet against every edge of the other (the edge pairs' kind).
    for (const auto& [a, b] : boundary)
      for (const Tri& t : m.triangles)
        for (int k = 0; k < 3; ++k) {
          const int c0 = t[k], c1 = t[(k + 1) % 3];
          if ((c0 < 9) == (a < 9)) continue;
          d.push_back(edge_edge_distance(y, a, b, c0, c1));
        }
    for (int i = 0; i < m.points.rows(); ++i)
      for (size_t t = 0; t < m.triangles.size(); ++t) {
        const Tri& tri = m.triangles[t];
        if (m.leaflet[t] == (i < 9 ? 0 : 1)) continue;
        d.push_back(node_face_distance(y, i, tri[0], tri[1], tri[2]));
      }
    return d;
  };
  const std::vector<double> before = cross_distances(x);
  int accepted = 0;
  for (int trial = 0; trial < 400; ++trial) {
    VecX dx(x.size());
    const double scale = 0.05 + 0.5 * (trial % 10) / 10.0;
    for (int k = 0; k < dx.size(); ++k) dx[k] = scale * noise(gen);
    if (c.step_ratio(x, dx) > 1) continue;
    ++accepted;
    const std::vector<double> after = cross_distances(x + dx);
    for (size_t k = 0; k < before.size(); ++k)
      if (before[k] >= delta) CHECK(after[k] >= std::min(0.2 * before[k], delta) - 1e-12);
  }
  CHECK(accepted > 20);
}

TEST_CASE("penalty contact exclusions, step limit and option checks", "[mechanics][penalty_contact]") {
  const TriMesh m = two_sheets(0.1);
  const VecX x = flatten(m.points);
  PenaltyContactOptions self_only;
  self_only.between_leaflets = false;
  PenaltyContactTerm c_self(m, self_only, std::vector<char>(18, 0));
  c_self.update_couplings(x);
  CHECK(forces(c_self, x).norm() == 0);
  std::vector<char> all(18, 1);
  PenaltyContactTerm c_fixed(m, PenaltyContactOptions{}, all);
  c_fixed.update_couplings(x);
  CHECK(c_fixed.statistics().candidate_pairs == 0);
  // Steps of at most min((D − δ)/4, 0.4 δ); by default D = δ + 4 max(δ, mean edge / 2).
  PenaltyContactOptions given;
  given.detection = 0.75;
  CHECK(PenaltyContactTerm(m, given, std::vector<char>(18, 0)).max_step_length() == Approx(0.1));  // 0.4 δ
  const TriMesh grid = grid_mesh(2.0);  // 8 triangles: 12 edges of 1 mm, 4 diagonals of √2 mm
  const double mean_edge = (12 * 1.0 + 4 * std::sqrt(2.0)) / 16;
  PenaltyContactTerm c(grid, PenaltyContactOptions{}, std::vector<char>(27, 0));
  CHECK(c.detection_distance() == Approx(0.25 + 4 * std::max(0.25, mean_edge / 2)));
  CHECK(c.max_step_length() == Approx(0.1));  // never more than 0.4 δ
  // max_detection caps the automatic distance (2.38 mm here) and leaves a smaller one alone.
  PenaltyContactOptions capped;
  capped.max_detection = 1.5;
  CHECK(PenaltyContactTerm(grid, capped, std::vector<char>(27, 0)).detection_distance() == 1.5);
  capped.max_detection = 3.0;
  CHECK(PenaltyContactTerm(grid, capped, std::vector<char>(27, 0)).detection_distance() ==
        Approx(0.25 + 4 * std::max(0.25, mean_edge / 2)));
  capped.max_detection = 0.25;  // not beyond the separation
  CHECK_THROWS_AS(capped.validate(), InputError);
  capped.max_detection = 1.5;
  capped.detection = 2.0;  // a given distance takes no cap
  CHECK_THROWS_AS(capped.validate(), InputError);
  PenaltyContactOptions bad;
  bad.separation = 0;
  CHECK_THROWS_AS(bad.validate(), InputError);
  bad = PenaltyContactOptions{};
  bad.detection = 0.2;
  CHECK_THROWS_AS(bad.validate(), InputError);
}
