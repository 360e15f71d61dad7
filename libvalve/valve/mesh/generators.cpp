#include "valve/mesh/generators.hpp"

#include <Eigen/Geometry>
#include <cmath>

#include "valve/core/error.hpp"

namespace valve {
namespace {

constexpr double kPi = 3.14159265358979323846;

std::vector<Vec2> subdivide(const Vec2& a, const Vec2& b, int n) {
  std::vector<Vec2> p;
  for (int k = 0; k < n; ++k) p.push_back(a + (b - a) * (static_cast<double>(k) / n));
  return p;
}

PlanarDomain square_domain(double side) {
  const double h = side / 2;
  PlanarDomain d;
  d.area = side * side;
  d.perimeter = 4 * side;
  d.boundary = [h, side](double s) {
    const int n = std::max(1, static_cast<int>(std::lround(side / s)));
    std::vector<Vec2> pts;
    const Vec2 c[4] = {{-h, -h}, {h, -h}, {h, h}, {-h, h}};
    for (int k = 0; k < 4; ++k) {
      auto seg = subdivide(c[k], c[(k + 1) % 4], n);
      pts.insert(pts.end(), seg.begin(), seg.end());
    }
    return pts;
  };
  d.signed_distance = [h](const Vec2& p) { return std::max(std::abs(p.x()), std::abs(p.y())) - h; };
  return d;
}

// Semicircle of radius r below the u axis: {v <= 0, u² + v² <= r²}. Boundary order: the
// arc from (-r, 0) through (0, -r) to (r, 0), then the free edge back to (-r, 0).
PlanarDomain semicircle_domain(double r, int* arc_nodes) {
  PlanarDomain d;
  d.area = 0.5 * kPi * r * r;
  d.perimeter = kPi * r + 2 * r;
  d.boundary = [r, arc_nodes](double s) {
    const int n_arc = std::max(2, static_cast<int>(std::lround(kPi * r / s)));
    const int n_edge = std::max(1, static_cast<int>(std::lround(2 * r / s)));
    std::vector<Vec2> pts;
    for (int k = 0; k < n_arc; ++k) {
      const double a = kPi + kPi * k / n_arc;
      pts.emplace_back(r * std::cos(a), r * std::sin(a));
    }
    *arc_nodes = n_arc + 1;  // the arc includes both corners
    auto edge = subdivide(Vec2(r, 0), Vec2(-r, 0), n_edge);
    pts.insert(pts.end(), edge.begin(), edge.end());
    return pts;
  };
  d.signed_distance = [r](const Vec2& p) { return std::max(p.norm() - r, p.y()); };
  return d;
}

// Wraps planar (u, v) onto the cylinder of radius R: u is arc length around the axis,
// v the axial coordinate. Flips the winding so normals point toward the axis.
void wrap_onto_cylinder(const std::vector<Vec2>& uv, const std::vector<Tri>& tris, double R,
                        double u_offset, double fiber_angle, TriMesh& out, int leaflet) {
  const int base = out.num_nodes();
  out.points.conservativeResize(base + static_cast<int>(uv.size()), 3);
  for (size_t i = 0; i < uv.size(); ++i) {
    const double phi = (uv[i].x() + u_offset) / R;
    out.points.row(base + i) << R * std::cos(phi), R * std::sin(phi), uv[i].y();
  }
  const int tbase = out.num_triangles();
  out.fiber.conservativeResize(tbase + static_cast<int>(tris.size()), 3);
  for (size_t k = 0; k < tris.size(); ++k) {
    const Tri& t = tris[k];
    out.triangles.emplace_back(base + t[0], base + t[2], base + t[1]);
    const double uc = (uv[t[0]].x() + uv[t[1]].x() + uv[t[2]].x()) / 3.0 + u_offset;
    const double phi = uc / R;
    const Vec3 e_u(-std::sin(phi), std::cos(phi), 0), e_v(0, 0, 1);
    out.fiber.row(tbase + k) = std::cos(fiber_angle) * e_u + std::sin(fiber_angle) * e_v;
    out.leaflet.push_back(leaflet);
  }
}

TriMesh leaflet_row(const LeafletOptions& opt, int count, double circumference) {
  if (opt.diameter <= 0 || circumference <= 0)
    throw InputError("leaflet generator: expected a positive diameter and circumference");
  const double r = opt.diameter / 2;
  if (count * opt.diameter > circumference + 1e-9)
    throw InputError("leaflet generator: the leaflets do not fit around the cylinder");
  int arc_nodes = 0;
  const PlanarMesh pm = mesh_planar_domain(semicircle_domain(r, &arc_nodes), opt.mesh);
  const double R = circumference / (2 * kPi);
  TriMesh mesh;
  mesh.points.resize(0, 3);
  mesh.fiber.resize(0, 3);
  for (int k = 0; k < count; ++k) {
    wrap_onto_cylinder(pm.points, pm.triangles, R, k * opt.diameter, opt.fiber_angle_deg * kPi / 180, mesh, k);
    for (int i = 0; i < static_cast<int>(pm.points.size()); ++i) {
      const bool on_arc = i < arc_nodes;  // the arc and both corners
      const bool boundary = i < pm.num_boundary;
      mesh.roles.push_back(boundary && on_arc ? NodeRole::fixed : NodeRole::free);
      mesh.boundary.push_back(!boundary ? BoundaryType::interior
                                        : (on_arc ? BoundaryType::attached : BoundaryType::free_edge));
    }
  }
  return mesh;
}

// Merges boundary nodes closer than tol (commissure corners shared by neighbouring
// leaflets). Only boundary nodes can coincide, so the quadratic search stays small.
void weld(TriMesh& m, double tol) {
  const int n = m.num_nodes();
  std::vector<int> map(n), kept_boundary;
  MatX3 pts(n, 3);
  std::vector<NodeRole> roles;
  std::vector<BoundaryType> boundary;
  int count = 0;
  for (int i = 0; i < n; ++i) {
    const Vec3 p = m.points.row(i);
    int match = -1;
    if (m.boundary[i] != BoundaryType::interior)
      for (int j : kept_boundary)
        if ((pts.row(j).transpose() - p).norm() < tol) match = j;
    if (match >= 0) {
      map[i] = match;
      continue;
    }
    if (m.boundary[i] != BoundaryType::interior) kept_boundary.push_back(count);
    map[i] = count;
    pts.row(count) = p;
    roles.push_back(m.roles[i]);
    boundary.push_back(m.boundary[i]);
    ++count;
  }
  pts.conservativeResize(count, 3);
  for (auto& t : m.triangles)
    for (int k = 0; k < 3; ++k) t[k] = map[t[k]];
  m.points = pts;
  m.roles = roles;
  m.boundary = boundary;
}

}  // namespace

TriMesh generate_square_patch(const SquarePatchOptions& opt) {
  if (opt.side <= 0) throw InputError("square patch: side: expected > 0");
  const PlanarMesh pm = mesh_planar_domain(square_domain(opt.side), opt.mesh);
  TriMesh m;
  m.points.resize(pm.points.size(), 3);
  for (size_t i = 0; i < pm.points.size(); ++i) m.points.row(i) << pm.points[i].x(), pm.points[i].y(), 0;
  m.triangles = pm.triangles;
  const double a = opt.fiber_angle_deg * kPi / 180;
  m.fiber.resize(m.num_triangles(), 3);
  for (int t = 0; t < m.num_triangles(); ++t) m.fiber.row(t) << std::cos(a), std::sin(a), 0;
  m.roles.assign(m.num_nodes(), NodeRole::free);
  m.boundary.assign(m.num_nodes(), BoundaryType::interior);
  for (int i = 0; i < pm.num_boundary; ++i) m.boundary[i] = BoundaryType::free_edge;
  m.leaflet.assign(m.num_triangles(), 0);
  return m;
}

TriMesh generate_aortic_leaflet(const LeafletOptions& opt) {
  return leaflet_row(opt, 1, opt.cylinder_circumference);
}

TriMesh generate_three_leaflet_valve(const LeafletOptions& opt) {
  TriMesh m = leaflet_row(opt, 3, 3 * opt.diameter);
  weld(m, 1e-6 * opt.diameter);
  return m;
}

}  // namespace valve
