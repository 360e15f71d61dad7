// Rigid ICP and annulus targets against known transforms.
#include <catch2/catch.hpp>

#include <Eigen/Geometry>

#include "valve/analysis/annulus_targets.hpp"
#include "valve/analysis/rigid_registration.hpp"
#include "valve/core/error.hpp"

using namespace valve;

namespace {
// A saddle-shaped D ring (like a mitral annulus), n points.
MatX3 saddle_ring(int n, double a = 15, double b = 12) {
  MatX3 p(n, 3);
  for (int i = 0; i < n; ++i) {
    const double t = 2 * M_PI * i / n;
    p.row(i) << a * std::cos(t), b * std::sin(t) * (0.9 - 0.1 * std::sin(t)), -2 * std::cos(2 * t);
  }
  return p;
}

// A ring of triangles between the saddle ring (annulus, fixed) and a smaller inner ring.
TriMesh ring_mesh(int n, double scale = 1.0) {
  TriMesh m;
  const MatX3 outer = saddle_ring(n), inner = 0.5 * saddle_ring(n);
  m.points.resize(2 * n, 3);
  m.points.topRows(n) = scale * outer;
  m.points.bottomRows(n) = scale * inner;
  for (int i = 0; i < n; ++i) {
    const int j = (i + 1) % n;
    m.triangles.emplace_back(i, j, n + j);
    m.triangles.emplace_back(i, n + j, n + i);
  }
  m.fill_defaults();
  for (int i = 0; i < n; ++i) m.roles[i] = NodeRole::fixed;
  return m;
}
}  // namespace

TEST_CASE("ICP recovers a rigid motion of a saddle ring", "[analysis]") {
  // Point-to-point ICP pairs points with target samples: with a dense target (0.02 mm
  // spacing) the sampling error is far below the tolerances.
  const MatX3 target = saddle_ring(4000), on_ring = saddle_ring(150);
  const Mat3 R = Eigen::AngleAxisd(0.12, Vec3(0.2, 0.3, 1).normalized()).toRotationMatrix();
  const Vec3 t(1.5, -0.7, 2.0);
  MatX3 source(150, 3);
  for (int i = 0; i < 150; ++i) source.row(i) = (R.transpose() * (on_ring.row(i).transpose() - t)).transpose();
  const IcpResult r = icp_point_to_point(source, target);
  CHECK(r.converged);
  CHECK(r.rms < 0.01);
  CHECK(r.transform.rotation_angle_deg() == Approx(0.12 * 180 / M_PI).margin(0.05));
  CHECK((r.transform.translation - t).norm() < 0.02);
}

TEST_CASE("annulus targets: a ring contracted by 10 % moves each node 10 % toward the centre", "[analysis]") {
  const TriMesh open = ring_mesh(60);
  const TriMesh closed = ring_mesh(90, 0.9);  // other node count and spacing
  const AnnulusTargets a = annulus_targets(open, closed, false, "open.vtp", "closed.vtp");
  REQUIRE(a.nodes.size() == 60);
  // Arc-length correspondence on similar rings is exact up to the polygon's chords.
  double worst = 0;
  for (int k = 0; k < 60; ++k) worst = std::max(worst, (a.targets.row(k) - 0.9 * open.points.row(a.nodes[k])).norm());
  CHECK(worst < 0.15);
  CHECK(a.closed_length_mm == Approx(0.9 * a.open_length_mm).epsilon(0.01));
  // The registration removes a rigid motion of the closed scan.
  TriMesh moved = closed;
  const Mat3 R = Eigen::AngleAxisd(0.2, Vec3::UnitZ()).toRotationMatrix();
  for (int i = 0; i < moved.num_nodes(); ++i) moved.points.row(i) = (R * moved.points.row(i).transpose() + Vec3(3, 1, -2)).transpose();
  const AnnulusTargets b = annulus_targets(open, moved, true, "open.vtp", "closed.vtp");
  double worst_b = 0;
  for (int k = 0; k < 60; ++k) worst_b = std::max(worst_b, (b.targets.row(k) - a.targets.row(k)).norm());
  CHECK(worst_b < 0.3);
  CHECK(b.registration.rotation_angle_deg() == Approx(0.2 * 180 / M_PI).margin(0.5));
}

TEST_CASE("annulus targets by node: each annulus node goes where the same node of the closed mesh is", "[analysis]") {
  const TriMesh open = ring_mesh(60);
  TriMesh closed = open;
  // A non-rigid motion: every node moves by its own amount, which no ring mapping would find.
  for (int i = 0; i < closed.num_nodes(); ++i) closed.points.row(i) += Vec3(0.01 * i, -0.02 * (i % 7), 0.5).transpose();
  const AnnulusTargets a = annulus_targets_by_node(open, closed, false, "open.vtp", "closed.vtp");
  REQUIRE(a.nodes.size() == 60);  // the fixed ring; the inner ring is free
  double worst = 0;
  for (std::size_t k = 0; k < a.nodes.size(); ++k) worst = std::max(worst, (a.targets.row(k) - closed.points.row(a.nodes[k])).norm());
  CHECK(worst == 0.0);
  CHECK(a.max_motion_mm > 0.5);
  CHECK(a.open_length_mm > 0);
  // With registration, a purely rigid motion of the closed mesh leaves the annulus in place.
  TriMesh moved = open;
  const Mat3 R = Eigen::AngleAxisd(0.3, Vec3(1, 1, 0).normalized()).toRotationMatrix();
  for (int i = 0; i < moved.num_nodes(); ++i) moved.points.row(i) = (R * open.points.row(i).transpose() + Vec3(3, 1, -2)).transpose();
  const AnnulusTargets b = annulus_targets_by_node(open, moved, true, "open.vtp", "closed.vtp");
  CHECK(b.max_motion_mm < 1e-9);
  CHECK(b.registration.rotation_angle_deg() == Approx(0.3 * 180 / M_PI).epsilon(1e-9));
  // Another mesh is an error naming the closed file.
  CHECK_THROWS_WITH(annulus_targets_by_node(open, ring_mesh(50), false, "open.vtp", "closed.vtp"),
                    Catch::Contains("closed.vtp") && Catch::Contains("nodes"));
}

TEST_CASE("a closed mesh without an annulus is an error naming the file", "[analysis]") {
  const TriMesh open = ring_mesh(40);
  TriMesh closed = ring_mesh(40);
  closed.roles.assign(closed.num_nodes(), NodeRole::free);
  CHECK_THROWS_WITH(annulus_targets(open, closed, true, "open.vtp", "closed.vtp"),
                    Catch::Contains("closed.vtp") && Catch::Contains("annulus"));
}

TEST_CASE("The atrial direction is the annulus plane's normal, pointing away from the leaflets", "[annulus]") {
  // A funnel: an annulus circle of radius 10 in z = 0 (fixed) and the leaflets' inner circle of
  // radius 5 hanging 5 mm below: the atrial direction is +z, and turns with the mesh.
  const int n = 24;
  TriMesh m;
  m.points.resize(2 * n, 3);
  for (int i = 0; i < n; ++i) {
    const double t = 2 * M_PI * i / n;
    m.points.row(i) << 10 * std::cos(t), 10 * std::sin(t), 0;
    m.points.row(n + i) << 5 * std::cos(t), 5 * std::sin(t), -5;
  }
  for (int i = 0; i < n; ++i) {
    const int j = (i + 1) % n;
    m.triangles.emplace_back(i, j, n + j);
    m.triangles.emplace_back(i, n + j, n + i);
  }
  m.fill_defaults();
  CHECK(annulus_atrial_direction(m).isApprox(Vec3::UnitZ()));  // no annulus marked: +z by default
  m.points.col(2) *= -1;  // hanging up now: still +z without an annulus
  CHECK(annulus_atrial_direction(m).isApprox(Vec3::UnitZ()));
  for (int i = 0; i < n; ++i) m.roles[i] = NodeRole::fixed;
  CHECK(annulus_atrial_direction(m).isApprox(-Vec3::UnitZ(), 1e-12));  // away from the leaflets above
  m.points.col(2) *= -1;
  const Mat3 R = Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()).toRotationMatrix();
  m.points = (m.points * R.transpose()).eval();
  CHECK(annulus_atrial_direction(m).isApprox(R * Vec3::UnitZ(), 1e-12));
}
