#include "valve/remesh/membrane_extraction.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <algorithm>
#include <map>
#include <limits>
#include <numeric>

#include "valve/core/error.hpp"
#include "valve/mesh/closest_point.hpp"
#include "valve/mesh/topology.hpp"

namespace valve {

Vec3 estimate_atrial_direction(const MatX3& points) {
  const Vec3 c = points.colwise().mean().transpose();
  const MatX3 d = points.rowwise() - c.transpose();
  const Eigen::SelfAdjointEigenSolver<Mat3> eig(d.transpose() * d);
  Vec3 axis = eig.eigenvectors().col(0);  // smallest eigenvalue first
  // Sign: correlate height along the axis with distance from it.
  double corr = 0, mean_r = 0;
  std::vector<double> r(points.rows()), h(points.rows());
  for (Eigen::Index i = 0; i < points.rows(); ++i) {
    const Vec3 p = d.row(i).transpose();
    h[i] = p.dot(axis);
    r[i] = (p - h[i] * axis).norm();
    mean_r += r[i] / points.rows();
  }
  for (Eigen::Index i = 0; i < points.rows(); ++i) corr += (r[i] - mean_r) * h[i];
  return corr >= 0 ? axis : -axis;
}

TriMesh extract_atrial_membrane(const TriMesh& surface, const MembraneOptions& o, MembraneSummary* summary) {
  MembraneSummary s;
  const int nf = surface.num_triangles();
  s.faces_in = nf;
  if (nf == 0) throw_input_error("membrane extraction", "surface", "a triangulated surface", "no triangles");
  if (o.atrial_direction && !(o.atrial_direction->norm() > 0))
    throw_input_error("membrane extraction", "atrial_direction", "a non-zero vector", "zero");
  s.direction_estimated = !o.atrial_direction;
  s.atrial_direction = o.atrial_direction ? o.atrial_direction->normalized() : estimate_atrial_direction(surface.points);
  if (!s.atrial_direction.allFinite()) throw_input_error("membrane extraction", "atrial_direction", "a non-zero vector", "zero");

  const Vec3 lo = surface.points.colwise().minCoeff().transpose(), hi = surface.points.colwise().maxCoeff().transpose();
  const Vec3 centroid = surface.points.colwise().mean().transpose();
  const Vec3 eye = centroid + o.viewpoint_height * (hi - lo).norm() * s.atrial_direction;

  std::vector<char> atrial(nf, 0);
  for (int f = 0; f < nf; ++f) {
    const Tri& t = surface.triangles[f];
    const Vec3 c = (surface.points.row(t[0]) + surface.points.row(t[1]) + surface.points.row(t[2])).transpose() / 3;
    atrial[f] = triangle_normal(surface.points, t).dot(eye - c) > 0;
  }
  // Face neighbours across edges.
  const Topology topo = build_topology(surface.triangles, surface.num_nodes());
  std::vector<std::vector<int>> neighbours(nf);
  for (const Edge& e : topo.edges)
    if (e.tris[1] >= 0) {
      neighbours[e.tris[0]].push_back(e.tris[1]);
      neighbours[e.tris[1]].push_back(e.tris[0]);
    }
  for (int pass = 0; pass < o.smoothing_passes; ++pass) {
    std::vector<char> next = atrial;
    for (int f = 0; f < nf; ++f) {
      int votes = atrial[f] ? 1 : -1;
      for (int g : neighbours[f]) votes += atrial[g] ? 1 : -1;
      next[f] = votes > 0;
    }
    atrial.swap(next);
  }
  // Morphological closing on the face graph (grow by n rings, shrink by n): fills the slits
  // and notches the rim leaves in the atrial face, whose narrow necks no remesher can
  // triangulate well.
  auto grow = [&](bool value) {
    std::vector<char> next = atrial;
    for (int f = 0; f < nf; ++f)
      for (int g : neighbours[f])
        if (bool(atrial[g]) == value) next[f] = value;
    atrial.swap(next);
  };
  for (int ring = 0; ring < o.closing_rings; ++ring) grow(true);
  for (int ring = 0; ring < o.closing_rings; ++ring) grow(false);
  // Connected pieces of the atrial faces.
  std::vector<int> piece(nf, -1);
  std::vector<double> piece_area;
  for (int f = 0; f < nf; ++f) {
    if (!atrial[f] || piece[f] >= 0) continue;
    const int id = static_cast<int>(piece_area.size());
    piece_area.push_back(0);
    std::vector<int> stack{f};
    piece[f] = id;
    while (!stack.empty()) {
      const int g = stack.back();
      stack.pop_back();
      piece_area[id] += triangle_area(surface.points, surface.triangles[g]);
      for (int h : neighbours[g])
        if (atrial[h] && piece[h] < 0) piece[h] = id, stack.push_back(h);
    }
  }
  if (piece_area.empty()) throw_input_error("membrane extraction", "atrial_direction", "faces looking toward the atrium", "none");
  const double largest = *std::max_element(piece_area.begin(), piece_area.end());
  std::vector<char> keep_piece(piece_area.size());
  for (std::size_t p = 0; p < piece_area.size(); ++p) {
    keep_piece[p] = piece_area[p] >= o.min_piece_fraction * largest;
    (keep_piece[p] ? s.pieces_kept : s.pieces_dropped)++;
  }

  TriMesh out;
  std::vector<int> new_index(surface.num_nodes(), -1);
  int count = 0;
  for (int f = 0; f < nf; ++f) {
    if (piece[f] < 0 || !keep_piece[piece[f]]) continue;
    Tri t = surface.triangles[f];
    for (int k = 0; k < 3; ++k) {
      if (new_index[t[k]] < 0) new_index[t[k]] = count++;
      t[k] = new_index[t[k]];
    }
    out.triangles.push_back(t);
  }
  out.points.resize(count, 3);
  for (int i = 0; i < surface.num_nodes(); ++i)
    if (new_index[i] >= 0) out.points.row(new_index[i]) = surface.points.row(i);
  out.fill_defaults();
  s.faces_kept = out.num_triangles();
  for (const Tri& t : out.triangles) s.area_mm2 += triangle_area(out.points, t);
  if (summary) *summary = s;
  return out;
}

namespace {

// Boundary-loop nodes flagged in `annulus` become annulus (attached, fixed), the other loop
// nodes free edge; fibers run circumferential about the valve axis (parallel to the annulus).
void mark_boundary(TriMesh& mesh, const Topology& topo, const std::vector<char>& annulus, const Vec3& a) {
  mesh.roles.assign(mesh.num_nodes(), NodeRole::free);
  mesh.boundary.assign(mesh.num_nodes(), BoundaryType::interior);
  for (const auto& loop : topo.loops)
    for (int n : loop) {
      mesh.boundary[n] = annulus[n] ? BoundaryType::attached : BoundaryType::free_edge;
      if (annulus[n]) mesh.roles[n] = NodeRole::fixed;
    }
  const Vec3 centre = mesh.points.colwise().mean().transpose();
  mesh.fiber.resize(mesh.num_triangles(), 3);
  for (int t = 0; t < mesh.num_triangles(); ++t) {
    const Tri& tri = mesh.triangles[t];
    const Vec3 c = (mesh.points.row(tri[0]) + mesh.points.row(tri[1]) + mesh.points.row(tri[2])).transpose() / 3;
    const Vec3 n = triangle_normal(mesh.points, tri);
    Vec3 f = a.cross(c - centre);
    f -= f.dot(n) * n;
    if (f.norm() < 1e-12) f = (mesh.points.row(tri[1]) - mesh.points.row(tri[0])).transpose();
    mesh.fiber.row(t) = f.normalized().transpose();
  }
}

}  // namespace

int mark_annulus_and_free_edge(TriMesh& mesh, const Vec3& atrial_direction) {
  const Vec3 a = atrial_direction.normalized();
  const Topology topo = build_topology(mesh.triangles, mesh.num_nodes());
  const std::vector<int>* highest = nullptr;
  double best = -1e300;
  for (const auto& loop : topo.loops) {
    double h = 0;
    for (int n : loop) h += mesh.points.row(n).dot(a) / loop.size();
    if (h > best) best = h, highest = &loop;
  }
  std::vector<char> annulus(mesh.num_nodes(), 0);
  if (highest)
    for (int n : *highest) annulus[n] = 1;
  mark_boundary(mesh, topo, annulus, a);
  return static_cast<int>(topo.loops.size());
}

std::vector<std::pair<Vec3, Vec3>> annulus_segments(const TriMesh& reference, const std::string& file) {
  std::vector<std::pair<Vec3, Vec3>> segments;
  if (reference.boundary.size() == static_cast<std::size_t>(reference.num_nodes())) {
    auto attached = [&](int v) { return reference.boundary[v] == BoundaryType::attached; };
    const Topology topo = build_topology(reference.triangles, reference.num_nodes());
    for (const Edge& e : topo.edges)
      if (e.tris[1] < 0 && attached(e.a) && attached(e.b))
        segments.emplace_back(reference.points.row(e.a).transpose(), reference.points.row(e.b).transpose());
  }
  if (segments.empty())
    throw_input_error(file, "BoundaryType", "a mesh whose annulus is marked (boundary edges with both nodes attached = 1)",
                      "no such edge");
  return segments;
}

int mark_annulus_near(TriMesh& mesh, const std::vector<std::pair<Vec3, Vec3>>& annulus, double tolerance,
                      const Vec3& atrial_direction, const std::string& landmark_file) {
  const Topology topo = build_topology(mesh.triangles, mesh.num_nodes());
  std::vector<char> near(mesh.num_nodes(), 0);
  int marked = 0;
  double nearest = std::numeric_limits<double>::infinity();
  for (const auto& loop : topo.loops)
    for (int n : loop) {
      const Vec3 p = mesh.points.row(n).transpose();
      double d = std::numeric_limits<double>::infinity();
      for (const auto& [a, b] : annulus) d = std::min(d, point_segment_distance(p, a, b));
      nearest = std::min(nearest, d);
      if (d <= tolerance) near[n] = 1, ++marked;
    }
  if (marked == 0)
    throw_input_error(landmark_file, "annulus_tolerance", "a boundary node within " + std::to_string(tolerance) + " mm of the annulus",
                      "the nearest at " + std::to_string(nearest) + " mm");
  mark_boundary(mesh, topo, near, atrial_direction.normalized());
  return static_cast<int>(topo.loops.size());
}

MembraneSummary describe_given_membrane(const TriMesh& surface, const std::optional<Vec3>& atrial_direction) {
  MembraneSummary summary;
  summary.direction_estimated = !atrial_direction;
  summary.atrial_direction = atrial_direction ? atrial_direction->normalized() : estimate_atrial_direction(surface.points);
  summary.faces_in = summary.faces_kept = surface.num_triangles();
  return summary;
}

}  // namespace valve
