#include "valve/phantom/mitral_phantom.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <random>

#include "valve/core/error.hpp"

namespace valve {
namespace {

constexpr double pi = 3.14159265358979323846;

struct SkirtShape {
  const MitralPhantomOptions& o;
  double theta_a0, theta_a1;  // anterior leaflet span (commissures), radians

  Vec3 annulus(double t) const {
    const double a = o.commissural_diameter / 2, b = o.septal_lateral_diameter / 2;
    return {a * std::cos(t), b * std::sin(t) * (0.9 - 0.1 * std::sin(t)), 0.5 * o.saddle_height * -std::cos(2 * t)};
  }
  // Fraction u ∈ [0, 1] across the leaflet that holds angle t, and whether it is anterior.
  bool anterior(double t, double* u) const {
    t = std::fmod(std::fmod(t, 2 * pi) + 2 * pi, 2 * pi);
    if (t >= theta_a0 && t <= theta_a1) {
      *u = (t - theta_a0) / (theta_a1 - theta_a0);
      return true;
    }
    double tp = t < theta_a0 ? t + 2 * pi : t;
    *u = (tp - theta_a1) / (theta_a0 + 2 * pi - theta_a1);
    return false;
  }
  double length(double t) const {
    double u = 0;
    const bool ant = anterior(t, &u);
    const double envelope = std::pow(std::sin(pi * u), 0.6);
    if (ant) return o.commissure_length + (o.anterior_length - o.commissure_length) * envelope;
    // Clefts between P1|P2 and P2|P3; P2 the widest scallop.
    const double w = 0.045;
    const double cleft = std::exp(-std::pow((u - 0.3) / w, 2)) + std::exp(-std::pow((u - 0.7) / w, 2));
    return o.commissure_length + (o.posterior_length * (1 - o.cleft_depth * cleft) - o.commissure_length) * envelope;
  }
  Vec3 point(double t, double s) const {
    const double alpha = o.opening_angle_deg * pi / 180;
    const Vec3 a = annulus(t);
    const Vec3 r = Vec3(a.x(), a.y(), 0).normalized();
    const Vec3 d = -std::sin(alpha) * r - std::cos(alpha) * Vec3::UnitZ();
    const Vec3 e = std::cos(alpha) * r - std::sin(alpha) * Vec3::UnitZ();
    return a + s * length(t) * d + o.belly_bulge * std::sin(pi * s) * e;
  }
};

}  // namespace

MitralPhantom make_mitral_phantom(const MitralPhantomOptions& given) {
  if (!(given.commissural_diameter > 0 && given.septal_lateral_diameter > 0 && given.anterior_length > 0 &&
        given.posterior_length > 0 && given.commissure_length > 0 && given.thickness > 0 && given.chord_diameter > 0 &&
        given.edge_length > 0 && given.variation >= 0 && given.variation < 0.5))
    throw InputError("mitral phantom: expected positive sizes and variation in [0, 0.5)");
  MitralPhantom ph;
  MitralPhantomOptions& o = ph.options;
  o = given;
  std::mt19937_64 rng(given.seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  auto vary = [&](double& x) { x *= 1 + o.variation * unit(rng); };
  for (double* x : {&o.commissural_diameter, &o.septal_lateral_diameter, &o.saddle_height, &o.anterior_length,
                    &o.posterior_length, &o.commissure_length, &o.cleft_depth, &o.opening_angle_deg, &o.belly_bulge,
                    &o.anterior_span_deg, &o.papillary_depth})
    vary(*x);

  const double span = o.anterior_span_deg * pi / 180;
  const SkirtShape shape{o, pi / 2 - span / 2, pi / 2 + span / 2};

  // Structured (θ, s) grid: periodic in θ, rows of constant s.
  double perimeter = 0;
  for (int k = 0; k < 720; ++k) perimeter += (shape.annulus(2 * pi * (k + 1) / 720) - shape.annulus(2 * pi * k / 720)).norm();
  const int nt = std::max(24, static_cast<int>(std::lround(perimeter / o.edge_length)));
  const int ns = std::max(4, static_cast<int>(std::lround(o.anterior_length / o.edge_length)));
  TriMesh& m = ph.leaflets;
  m.points.resize(nt * (ns + 1), 3);
  auto node = [&](int i, int j) { return (i % nt) + nt * j; };
  for (int j = 0; j <= ns; ++j)
    for (int i = 0; i < nt; ++i) m.points.row(node(i, j)) = shape.point(2 * pi * i / nt, double(j) / ns).transpose();
  for (int j = 0; j < ns; ++j)
    for (int i = 0; i < nt; ++i) {
      const int a = node(i, j), b = node(i + 1, j), c = node(i, j + 1), d = node(i + 1, j + 1);
      double u = 0;
      const int leaflet = shape.anterior(2 * pi * (i + 0.5) / nt, &u) ? 0 : 1;
      if ((i + j) % 2 == 0) {
        m.triangles.emplace_back(a, b, c);
        m.triangles.emplace_back(b, d, c);
      } else {
        m.triangles.emplace_back(a, d, c);
        m.triangles.emplace_back(a, b, d);
      }
      m.leaflet.push_back(leaflet);
      m.leaflet.push_back(leaflet);
    }
  m.roles.assign(m.num_nodes(), NodeRole::free);
  m.boundary.assign(m.num_nodes(), BoundaryType::interior);
  for (int i = 0; i < nt; ++i) {
    m.roles[node(i, 0)] = NodeRole::fixed;
    m.boundary[node(i, 0)] = BoundaryType::attached;
    m.boundary[node(i, ns)] = BoundaryType::free_edge;
  }
  // Fibers run circumferentially, parallel to the annulus (the collagen of the mitral leaflets).
  m.fiber.resize(m.num_triangles(), 3);
  for (int t = 0; t < m.num_triangles(); ++t) {
    const Tri& tri = m.triangles[t];
    const Vec3 c = (m.points.row(tri[0]) + m.points.row(tri[1]) + m.points.row(tri[2])).transpose() / 3;
    const Vec3 n = triangle_normal(m.points, tri);
    Vec3 f = Vec3::UnitZ().cross(Vec3(c.x(), c.y(), 0));
    f -= f.dot(n) * n;
    m.fiber.row(t) = f.normalized().transpose();
  }

  // Papillary muscles below the commissures, at 75 % of the annulus radius.
  for (int k = 0; k < 2; ++k) {
    const double t = k == 0 ? shape.theta_a0 : shape.theta_a1;
    const Vec3 a = shape.annulus(t);
    PapillaryMuscle& pm = ph.papillary[k];
    pm.tip = Vec3(0.75 * a.x(), 0.75 * a.y() - 1.0, -o.papillary_depth);
    pm.semi_axes = Vec3(o.papillary_radius, o.papillary_radius, 1.7 * o.papillary_radius);
    pm.centre = pm.tip - Vec3(0, 0, pm.semi_axes.z());
  }

  // Chordae.
  ChordaeNetwork& ch = ph.chordae;
  ch.diameter = o.chord_diameter;
  auto add_point = [&](ChordPointKind kind, const Vec3& p, int mesh_node, const std::string& name) {
    ch.points.push_back({kind, p, mesh_node, name});
    return static_cast<int>(ch.points.size()) - 1;
  };
  int tips[2];
  for (int k = 0; k < 2; ++k)
    tips[k] = add_point(ChordPointKind::papillary_tip, ph.papillary[k].tip, -1, k == 0 ? "anterolateral" : "posteromedial");
  auto serving = [&](const Vec3& p) { return p.x() >= 0 ? 0 : 1; };
  auto insertion = [&](double t, double s, const std::string& name) {
    const int i = static_cast<int>(std::lround(t / (2 * pi) * nt)) % nt;
    const int j = static_cast<int>(std::lround(s * ns));
    const int n = node((i + nt) % nt, j);
    return add_point(ChordPointKind::insertion, m.points.row(n).transpose(), n, name);
  };
  // Primary fans: groups of three free-edge insertions 12° apart, skipping the commissure tips.
  const double step = 12 * pi / 180;
  std::vector<double> free_edge_angles;
  for (double t = shape.theta_a0 + step / 2; t < shape.theta_a0 + 2 * pi - step / 4; t += step) {
    const double tt = std::fmod(t, 2 * pi);
    if (std::abs(std::remainder(tt - shape.theta_a1, 2 * pi)) < step / 2) continue;
    free_edge_angles.push_back(tt);
  }
  for (std::size_t g = 0; g + 2 < free_edge_angles.size(); g += 3) {
    int ids[3];
    Vec3 mean = Vec3::Zero();
    for (int q = 0; q < 3; ++q) {
      ids[q] = insertion(free_edge_angles[g + q], 1.0, "primary");
      mean += ch.points[ids[q]].position / 3;
    }
    const int tip = tips[serving(mean)];
    const int branch = add_point(ChordPointKind::branch, ch.points[tip].position + 0.6 * (mean - ch.points[tip].position), -1, "");
    ch.segments.push_back({tip, branch, ChordType::primary});
    for (int q = 0; q < 3; ++q) ch.segments.push_back({branch, ids[q], ChordType::primary});
  }
  // Secondary chords to the belly, every 30°, away from the commissures.
  for (double t = shape.theta_a0 + pi / 9; t < shape.theta_a0 + 2 * pi - pi / 18; t += pi / 6) {
    const double tt = std::fmod(t, 2 * pi);
    if (std::abs(std::remainder(tt - shape.theta_a1, 2 * pi)) < pi / 9) continue;
    const int id = insertion(tt, 0.55, "secondary");
    ch.segments.push_back({tips[serving(ch.points[id].position)], id, ChordType::secondary});
  }
  // Two struts to the anterior leaflet.
  for (double dt : {-0.4, 0.4}) {
    const int id = insertion(pi / 2 + dt, 0.45, "strut");
    ch.segments.push_back({tips[dt > 0 ? 1 : 0], id, ChordType::strut});
  }
  return ph;
}

}  // namespace valve
