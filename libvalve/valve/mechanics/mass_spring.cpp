#include "valve/mechanics/mass_spring.hpp"

#include "valve/mechanics/axial_pair.hpp"

#include <Eigen/Geometry>
#include <cmath>

#include "valve/mesh/topology.hpp"

namespace valve {

MassSpringTerm::MassSpringTerm(const TriMesh& mesh, const BilinearParameters& p, double thickness) {
  const Topology topo = build_topology(mesh.triangles, mesh.num_nodes());
  springs_.reserve(topo.edges.size());
  for (const auto& e : topo.edges) {
    const Vec3 d = mesh.points.row(e.b) - mesh.points.row(e.a);
    const double l0 = d.norm();
    double area = 0, cos2 = 0;
    for (int t : e.tris) {
      if (t < 0) continue;
      const double a = triangle_area(mesh.points, mesh.triangles[t]);
      const double c = d.dot(mesh.fiber.row(t).transpose()) / (l0 * mesh.fiber.row(t).norm());
      area += a;
      cos2 += a * c * c;
    }
    cos2 /= area;
    const double sin2 = 1 - cos2;
    auto blend = [&](double fiber, double cross) {
      return std::sqrt(fiber * fiber * cos2 + cross * cross * sin2);
    };
    const double m1 = blend(p.fiber.m1, p.cross.m1), m2 = blend(p.fiber.m2, p.cross.m2);
    const double ls = blend(p.fiber.lambda_star, p.cross.lambda_star);
    const double scale = thickness * area / (l0 * l0);
    springs_.push_back({e.a, e.b, l0, m1 * scale, m2 * scale, ls});
  }
  std::vector<std::pair<int, int>> pairs;
  for (const auto& sp : springs_)
    for (const auto& ij : {std::make_pair(sp.a, sp.a), {sp.b, sp.b}, {sp.a, sp.b}, {sp.b, sp.a}}) pairs.push_back(ij);
  slots_ = BlockSlotCache(std::move(pairs));
}

void MassSpringTerm::force(const Spring& sp, double l, double& F, double& dF) {
  if (l <= sp.lambda_star * sp.rest_length) {
    F = sp.k1 * (l - sp.rest_length);
    dF = sp.k1;
  } else {
    F = sp.k1 * sp.rest_length * (sp.lambda_star - 1) + sp.k2 * (l - sp.lambda_star * sp.rest_length);
    dF = sp.k2;
  }
}

void MassSpringTerm::couplings(std::vector<std::pair<int, int>>& pairs) const {
  for (const auto& s : springs_) pairs.emplace_back(s.a, s.b);
}

void MassSpringTerm::add(const State& s, VecX& f, BlockJacobian* dfdx, BlockJacobian*) const {
  const std::vector<BlockSlot>* slots = dfdx ? &slots_.slots(*dfdx) : nullptr;
  for (std::size_t k = 0; k < springs_.size(); ++k) {
    const Spring& sp = springs_[k];
    const Vec3 d = node3(s.x, sp.b) - node3(s.x, sp.a);
    const double l = d.norm();
    if (l <= 0) continue;  // coincident nodes: no direction, no force
    const Vec3 n = d / l;
    double F, dF;
    force(sp, l, F, dF);
    add_axial_pair(sp.a, sp.b, n, l, F, dF, f, dfdx, slots ? &(*slots)[4 * k] : nullptr);
  }
}

bool MassSpringTerm::energy(const State& s, double& e) const {
  double sum = 0;
  for (const auto& sp : springs_) {
    const double l = (node3(s.x, sp.b) - node3(s.x, sp.a)).norm();
    const double l0 = sp.rest_length, ls = sp.lambda_star * l0;
    if (l <= ls) {
      sum += 0.5 * sp.k1 * (l - l0) * (l - l0);
    } else {
      sum += 0.5 * sp.k1 * (ls - l0) * (ls - l0) + sp.k1 * (ls - l0) * (l - ls) +
             0.5 * sp.k2 * (l - ls) * (l - ls);
    }
  }
  e += sum;
  return true;
}

}  // namespace valve
