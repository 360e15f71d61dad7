#include "valve/mesh/generators.hpp"

#include <Eigen/Geometry>
#include <algorithm>
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
  MatX3 pts(n, 3), start(m.initial.rows() == n ? n : 0, 3);
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
    if (start.rows()) start.row(count) = m.initial.row(i);
    roles.push_back(m.roles[i]);
    boundary.push_back(m.boundary[i]);
    ++count;
  }
  pts.conservativeResize(count, 3);
  if (start.rows()) start.conservativeResize(count, 3);
  m.initial = start;
  for (auto& t : m.triangles)
    for (int k = 0; k < 3; ++k) t[k] = map[t[k]];
  m.points = pts;
  m.roles = roles;
  m.boundary = boundary;
}

// The flat aortic cusp of seed 4.2.1, centred on u = 0 with its nadir at v = 0: attachment
// curve v = a sin²(u / d') between the commissures, commissure sides up to v_top, straight
// free edge. Boundary order: left commissure top, down the left side, along the curve,
// up the right side, then the free edge back. `attached_count` receives the number of
// boundary nodes before the free edge (both top corners count as attached).
struct CuspShape {
  double half_width, curve_scale, curve_depth_scale, side_height;
  double curve(double u) const {
    const double s = std::sin(u / curve_depth_scale);
    return curve_scale * s * s;
  }
  double top() const { return curve(half_width) + side_height; }
};

PlanarDomain cusp_domain(const CuspShape& c, int* attached_count) {
  PlanarDomain d;
  // Area and perimeter by sampling (the mesher only needs them for the spacing).
  const int n = 2000;
  double under = 0, curve_len = 0;
  for (int k = 0; k < n; ++k) {
    const double u0 = -c.half_width + 2 * c.half_width * k / n, u1 = -c.half_width + 2 * c.half_width * (k + 1) / n;
    under += 0.5 * (c.curve(u0) + c.curve(u1)) * (u1 - u0);
    curve_len += std::hypot(u1 - u0, c.curve(u1) - c.curve(u0));
  }
  d.area = 2 * c.half_width * c.top() - under;
  d.perimeter = curve_len + 2 * c.side_height + 2 * c.half_width;
  d.boundary = [c, curve_len, attached_count](double s) {
    std::vector<Vec2> pts;
    const Vec2 tl(-c.half_width, c.top()), bl(-c.half_width, c.curve(-c.half_width));
    const Vec2 br(c.half_width, c.curve(c.half_width)), tr(c.half_width, c.top());
    auto side = subdivide(tl, bl, std::max(1, static_cast<int>(std::lround(c.side_height / s))));
    pts.insert(pts.end(), side.begin(), side.end());
    // Even arc-length spacing along the curve.
    const int m = std::max(2, static_cast<int>(std::lround(curve_len / s)));
    const int fine = 4000;
    std::vector<double> cum(fine + 1, 0.0);
    auto at = [&](int k) { const double u = -c.half_width + 2 * c.half_width * k / fine; return Vec2(u, c.curve(u)); };
    for (int k = 1; k <= fine; ++k) cum[k] = cum[k - 1] + (at(k) - at(k - 1)).norm();
    int j = 0;
    for (int k = 0; k < m; ++k) {
      const double target = cum[fine] * k / m;
      while (j < fine && cum[j + 1] < target) ++j;
      const double t = (target - cum[j]) / std::max(cum[j + 1] - cum[j], 1e-300);
      pts.push_back(at(j) + t * (at(j + 1) - at(j)));
    }
    side = subdivide(br, tr, std::max(1, static_cast<int>(std::lround(c.side_height / s))));
    pts.insert(pts.end(), side.begin(), side.end());
    *attached_count = static_cast<int>(pts.size()) + 1;  // + the top right corner
    auto edge = subdivide(tr, tl, std::max(1, static_cast<int>(std::lround(2 * c.half_width / s))));
    pts.insert(pts.end(), edge.begin(), edge.end());
    return pts;
  };
  d.signed_distance = [c](const Vec2& p) {
    return std::max({std::abs(p.x()) - c.half_width, p.y() - c.top(), c.curve(std::clamp(p.x(), -c.half_width, c.half_width)) - p.y()});
  };
  return d;
}

}  // namespace

TriMesh generate_aortic_valve(const AorticValveOptions& opt) {
  if (!(opt.diameter > 0) || !(opt.gamma_deg > 0 && opt.gamma_deg < 90) || !(opt.width_ratio > 0) ||
      !(opt.commissure_height > 0))
    throw InputError("aortic valve generator: expected diameter > 0, 0 < gamma < 90 deg, width ratio > 0, commissure height > 0");
  const double d = opt.diameter, R = d / 2;
  auto is_graft = [&](int k) { return opt.width_scale[k] != 1 || opt.height_scale[k] != 1; };
  const bool has_graft = is_graft(0) || is_graft(1) || is_graft(2);
  if (has_graft && !(opt.graft_commissure_gap >= 0 && opt.graft_commissure_gap < 0.5 * opt.width_ratio * R))
    throw_input_error("aortic valve generator", "graft_commissure_gap",
                      "[0, " + format_number(0.5 * opt.width_ratio * R) + ") mm (under a quarter of a leaflet's width)",
                      format_number(opt.graft_commissure_gap) + " mm");
  const double native_top = d * std::pow(std::sin(opt.width_ratio / 2), 2) / std::tan(opt.gamma_deg * kPi / 180) +
                            opt.commissure_height;
  TriMesh mesh;
  mesh.points.resize(0, 3);
  mesh.fiber.resize(0, 3);
  MatX3 initial(0, 3);
  for (int k = 0; k < 3; ++k) {
    const double ws = opt.width_scale[k], hs = opt.height_scale[k];
    if (!(ws >= 1 && ws < 2 && hs > 0.5 && hs < 2))
      throw InputError("aortic valve generator: leaflet " + std::to_string(k) +
                       ": expected width scale in [1, 2) and height scale in (0.5, 2)");
    const CuspShape shape{ws * opt.width_ratio * d / 2, hs * d / std::tan(opt.gamma_deg * kPi / 180), ws * d,
                          hs * opt.commissure_height};
    int attached = 0;
    PlanarMeshOptions mo = opt.mesh;
    mo.seed = opt.mesh.seed + 7919 * k;
    const PlanarMesh pm = mesh_planar_domain(cusp_domain(shape, &attached), mo);
    // Rest: wrapped on radius ws R (isometric); start: on the root radius at the same angles,
    // for a graft scaled so that each side moves in by the gap (its half-angle at rest is width_ratio).
    const double Rk = ws * R, phi0 = 2 * kPi * k / 3;
    const double start_angle_scale = is_graft(k) ? 1 - opt.graft_commissure_gap / (R * opt.width_ratio) : 1.0;
    const int base = mesh.num_nodes();
    mesh.points.conservativeResize(base + static_cast<int>(pm.points.size()), 3);
    initial.conservativeResize(base + static_cast<int>(pm.points.size()), 3);
    for (size_t i = 0; i < pm.points.size(); ++i) {
      const double phi = phi0 + pm.points[i].x() / Rk, z = pm.points[i].y() - native_top;
      const double phi_start = phi0 + start_angle_scale * pm.points[i].x() / Rk;
      mesh.points.row(base + i) << Rk * std::cos(phi), Rk * std::sin(phi), z;
      initial.row(base + i) << R * std::cos(phi_start), R * std::sin(phi_start), z;
      const bool boundary = static_cast<int>(i) < pm.num_boundary, on_attachment = static_cast<int>(i) < attached;
      mesh.roles.push_back(boundary && on_attachment ? NodeRole::fixed : NodeRole::free);
      mesh.boundary.push_back(!boundary ? BoundaryType::interior
                                        : (on_attachment ? BoundaryType::attached : BoundaryType::free_edge));
    }
    const int tbase = mesh.num_triangles();
    mesh.fiber.conservativeResize(tbase + static_cast<int>(pm.triangles.size()), 3);
    const double angle = opt.fiber_angle_deg * kPi / 180;
    for (size_t t = 0; t < pm.triangles.size(); ++t) {
      const Tri& tri = pm.triangles[t];
      mesh.triangles.emplace_back(base + tri[0], base + tri[2], base + tri[1]);  // normals toward the axis
      const double uc = (pm.points[tri[0]].x() + pm.points[tri[1]].x() + pm.points[tri[2]].x()) / 3;
      const double phi = phi0 + uc / Rk;
      const Vec3 e_u(-std::sin(phi), std::cos(phi), 0), e_v(0, 0, 1);
      // Left half descends toward the midline, right half rises from it (mirror images).
      const double a = uc < 0 ? -angle : angle;
      mesh.fiber.row(tbase + t) = std::cos(a) * e_u + std::sin(a) * e_v;
      mesh.leaflet.push_back(k);
    }
  }
  if (has_graft) mesh.initial = initial;
  weld(mesh, 1e-6 * d);
  return mesh;
}

namespace {

// A planar mesh laid in the z = 0 plane (normals +z) as one free, interior leaflet with a
// uniform fiber direction at `fiber_angle_deg` from +x; callers mark its boundary.
TriMesh flat_sheet(const PlanarMesh& pm, double fiber_angle_deg) {
  TriMesh m;
  m.points.resize(pm.points.size(), 3);
  for (size_t i = 0; i < pm.points.size(); ++i) m.points.row(i) << pm.points[i].x(), pm.points[i].y(), 0;
  m.triangles = pm.triangles;
  const double a = fiber_angle_deg * kPi / 180;
  m.fiber.resize(m.num_triangles(), 3);
  for (int t = 0; t < m.num_triangles(); ++t) m.fiber.row(t) << std::cos(a), std::sin(a), 0;
  m.roles.assign(m.num_nodes(), NodeRole::free);
  m.boundary.assign(m.num_nodes(), BoundaryType::interior);
  m.leaflet.assign(m.num_triangles(), 0);
  return m;
}

}  // namespace

TriMesh generate_square_patch(const SquarePatchOptions& opt) {
  if (opt.side <= 0) throw InputError("square patch: side: expected > 0");
  const PlanarMesh pm = mesh_planar_domain(square_domain(opt.side), opt.mesh);
  TriMesh m = flat_sheet(pm, opt.fiber_angle_deg);
  for (int i = 0; i < pm.num_boundary; ++i) m.boundary[i] = BoundaryType::free_edge;
  return m;
}

TriMesh generate_clamped_disk(const DiskOptions& opt) {
  if (opt.diameter <= 0) throw InputError("disk: diameter: expected > 0");
  const double r = opt.diameter / 2;
  PlanarDomain d;
  d.area = kPi * r * r;
  d.perimeter = 2 * kPi * r;
  d.boundary = [r](double s) {
    const int n = std::max(6, static_cast<int>(std::lround(2 * kPi * r / s)));
    std::vector<Vec2> pts;
    for (int k = 0; k < n; ++k) pts.emplace_back(r * std::cos(2 * kPi * k / n), r * std::sin(2 * kPi * k / n));
    return pts;
  };
  d.signed_distance = [r](const Vec2& p) { return p.norm() - r; };
  const PlanarMesh pm = mesh_planar_domain(d, opt.mesh);
  TriMesh m = flat_sheet(pm, opt.fiber_angle_deg);
  for (int i = 0; i < pm.num_boundary; ++i) m.boundary[i] = BoundaryType::attached, m.roles[i] = NodeRole::fixed;
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
