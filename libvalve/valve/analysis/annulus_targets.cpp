#include "valve/analysis/annulus_targets.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "valve/core/error.hpp"
#include "valve/mesh/topology.hpp"

namespace valve {

Vec3 annulus_atrial_direction(const TriMesh& mesh) {
  std::vector<int> ring_nodes;
  for (int i = 0; i < mesh.num_nodes(); ++i)
    if (mesh.boundary[i] == BoundaryType::attached || mesh.roles[i] == NodeRole::fixed) ring_nodes.push_back(i);
  if (ring_nodes.size() < 3) return Vec3::UnitZ();
  MatX3 ring(ring_nodes.size(), 3);
  for (size_t k = 0; k < ring_nodes.size(); ++k) ring.row(k) = mesh.points.row(ring_nodes[k]);
  const Vec3 centre = ring.colwise().mean().transpose();
  const MatX3 d = ring.rowwise() - centre.transpose();
  Vec3 atrial = Eigen::SelfAdjointEigenSolver<Mat3>(d.transpose() * d).eigenvectors().col(0);
  if ((mesh.points.colwise().mean().transpose() - centre).dot(atrial) > 0) atrial = -atrial;
  return atrial;
}

namespace {

bool marked(const TriMesh& m, int i) {
  return (i < static_cast<int>(m.roles.size()) && m.roles[i] == NodeRole::fixed) ||
         (i < static_cast<int>(m.boundary.size()) && m.boundary[i] == BoundaryType::attached);
}

// A closed polyline parametrised by arc length fraction s in [0, 1).
struct Ring {
  MatX3 p;
  std::vector<double> s;  // cumulative fraction at each vertex
  double length = 0;

  explicit Ring(const MatX3& points) : p(points) {
    const int n = static_cast<int>(p.rows());
    s.assign(n, 0.0);
    for (int i = 1; i < n; ++i) s[i] = s[i - 1] + (p.row(i) - p.row(i - 1)).norm();
    length = s[n - 1] + (p.row(0) - p.row(n - 1)).norm();
    for (double& v : s) v /= length;
  }
  Vec3 at(double t) const {
    t -= std::floor(t);
    const int n = static_cast<int>(p.rows());
    const int i = static_cast<int>(std::upper_bound(s.begin(), s.end(), t) - s.begin()) - 1;
    const int j = (i + 1) % n;
    const double s1 = j == 0 ? 1.0 : s[j];
    const double w = s1 > s[i] ? (t - s[i]) / (s1 - s[i]) : 0.0;
    return ((1 - w) * p.row(i) + w * p.row(j)).transpose();
  }
};

MatX3 ring_points(const TriMesh& m, const std::vector<int>& ring) {
  MatX3 p(static_cast<int>(ring.size()), 3);
  for (std::size_t k = 0; k < ring.size(); ++k) p.row(k) = m.points.row(ring[k]);
  return p;
}

// Mean and largest distance from each open annulus node to its target.
void measure_motion(AnnulusTargets& out, const MatX3& open_points) {
  const auto n = open_points.rows();
  for (Eigen::Index i = 0; i < n; ++i) {
    const double d = (out.targets.row(i) - open_points.row(i)).norm();
    out.mean_motion_mm += d / n;
    out.max_motion_mm = std::max(out.max_motion_mm, d);
  }
}

MatX3 resample(const Ring& r, int count) {
  MatX3 out(count, 3);
  for (int k = 0; k < count; ++k) out.row(k) = r.at(static_cast<double>(k) / count).transpose();
  return out;
}

}  // namespace

MatX3 resample_ring(const MatX3& ring, int count) { return resample(Ring(ring), count); }

std::vector<int> annulus_ring(const TriMesh& mesh) {
  const Topology topo = build_topology(mesh.triangles, mesh.num_nodes());
  const std::vector<int>* best = nullptr;
  long best_count = 0;
  for (const auto& loop : topo.loops) {
    const long c = std::count_if(loop.begin(), loop.end(), [&](int i) { return marked(mesh, i); });
    if (c > best_count) best_count = c, best = &loop;
  }
  std::vector<int> ring;
  if (best)
    for (int i : *best)
      if (marked(mesh, i)) ring.push_back(i);
  return ring;
}

AnnulusTargets annulus_targets(const TriMesh& open, const TriMesh& closed, bool register_rigidly,
                               const std::string& open_file, const std::string& closed_file) {
  const std::vector<int> open_ring = annulus_ring(open), closed_ring = annulus_ring(closed);
  if (open_ring.size() < 3)
    throw_input_error(open_file, "NodeRole", "an annulus: a boundary loop with fixed or attached nodes",
                      std::to_string(open_ring.size()) + " such nodes");
  if (closed_ring.size() < 3)
    throw_input_error(closed_file, "NodeRole", "an annulus: a boundary loop with fixed or attached nodes",
                      std::to_string(closed_ring.size()) + " such nodes");
  AnnulusTargets out;
  out.nodes = open_ring;
  const Ring open_curve(ring_points(open, open_ring));
  MatX3 closed_points = ring_points(closed, closed_ring);
  if (register_rigidly) {
    // Dense samples of both rings so the registration does not depend on node spacing.
    const IcpResult icp = icp_point_to_point(resample(Ring(closed_points), 720), resample(open_curve, 720));
    out.registration = icp.transform;
    out.ring_rms_mm = icp.rms;
    closed_points = icp.transform.apply(closed_points);
  }
  const Ring closed_curve(closed_points);
  out.open_length_mm = open_curve.length;
  out.closed_length_mm = closed_curve.length;
  // Start and sense of the closed ring: the best of 720 offsets in each sense.
  const int n = static_cast<int>(open_ring.size());
  double best = 1e300, best_offset = 0;
  int best_sense = 1;
  for (int sense : {1, -1})
    for (int k = 0; k < 720; ++k) {
      const double offset = k / 720.0;
      double sum = 0;
      for (int i = 0; i < n && sum < best; ++i)
        sum += (closed_curve.at(offset + sense * open_curve.s[i]) - open_curve.p.row(i).transpose()).squaredNorm();
      if (sum < best) best = sum, best_offset = offset, best_sense = sense;
    }
  out.targets.resize(n, 3);
  for (int i = 0; i < n; ++i) out.targets.row(i) = closed_curve.at(best_offset + best_sense * open_curve.s[i]).transpose();
  measure_motion(out, open_curve.p);
  return out;
}

AnnulusTargets annulus_targets_by_node(const TriMesh& open, const TriMesh& closed, bool register_rigidly,
                                       const std::string& open_file, const std::string& closed_file) {
  if (closed.num_nodes() != open.num_nodes())
    throw_input_error(closed_file, "points", "the open mesh's " + std::to_string(open.num_nodes()) + " nodes (correspondence: nodes)",
                      std::to_string(closed.num_nodes()) + " nodes");
  AnnulusTargets out;
  for (int i = 0; i < open.num_nodes(); ++i)
    if (marked(open, i)) out.nodes.push_back(i);
  if (out.nodes.size() < 3)
    throw_input_error(open_file, "NodeRole", "an annulus: fixed or attached nodes", std::to_string(out.nodes.size()) + " such nodes");
  const MatX3 open_points = ring_points(open, out.nodes);
  out.targets = ring_points(closed, out.nodes);
  if (register_rigidly) {
    const Eigen::Matrix4d T = Eigen::umeyama(out.targets.transpose(), open_points.transpose(), false);
    out.registration.rotation = T.topLeftCorner<3, 3>();
    out.registration.translation = T.topRightCorner<3, 1>();
    out.targets = out.registration.apply(out.targets);
    out.ring_rms_mm = std::sqrt((out.targets - open_points).rowwise().squaredNorm().mean());
  }
  measure_motion(out, open_points);
  // Lengths along the annulus loop, where the marked nodes form one.
  if (const std::vector<int> ring = annulus_ring(open); ring.size() >= 3) {
    std::vector<int> row_of(open.num_nodes(), -1);
    for (std::size_t k = 0; k < out.nodes.size(); ++k) row_of[out.nodes[k]] = static_cast<int>(k);
    MatX3 closed_ring(static_cast<int>(ring.size()), 3);
    for (std::size_t k = 0; k < ring.size(); ++k) closed_ring.row(k) = out.targets.row(row_of[ring[k]]);
    out.open_length_mm = Ring(ring_points(open, ring)).length;
    out.closed_length_mm = Ring(closed_ring).length;
  }
  return out;
}

}  // namespace valve
