#include "valve/mechanics/pressure.hpp"

#include <Eigen/Geometry>

namespace valve {
PressureTerm::PressureTerm(const TriMesh& mesh, double pressure, bool along_normal, std::vector<char> active)
    : signed_pressure_(along_normal ? pressure : -pressure) {
  for (int t = 0; t < mesh.num_triangles(); ++t)
    if (active.empty() || active[t]) triangles_.push_back(mesh.triangles[t]);
  std::vector<std::pair<int, int>> pairs;
  for (const auto& t : triangles_)
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) pairs.emplace_back(t[a], t[b]);
  slots_ = BlockSlotCache(std::move(pairs));
}

void PressureTerm::couplings(std::vector<std::pair<int, int>>& pairs) const {
  for (const auto& t : triangles_)
    for (int a = 0; a < 3; ++a) pairs.emplace_back(t[a], t[(a + 1) % 3]);
}

void PressureTerm::add(const State& s, VecX& f, BlockJacobian* dfdx, BlockJacobian*) const {
  const double c = signed_pressure_ * s.load / 3.0;
  const std::vector<BlockSlot>* slots = dfdx ? &slots_.slots(*dfdx) : nullptr;
  for (std::size_t k = 0; k < triangles_.size(); ++k) {
    const Tri& t = triangles_[k];
    const Vec3 x1 = node3(s.x, t[0]), e1 = node3(s.x, t[1]) - x1, e2 = node3(s.x, t[2]) - x1;
    const Vec3 force = c * 0.5 * e1.cross(e2);
    for (int a = 0; a < 3; ++a) node3(f, t[a]) += force;
    if (!dfdx) continue;
    const Mat3 d2 = -0.5 * c * cross_matrix(e2), d3 = 0.5 * c * cross_matrix(e1);
    const Mat3 d1 = -d2 - d3;
    for (int a = 0; a < 3; ++a) {
      dfdx->add((*slots)[9 * k + 3 * a], d1);
      dfdx->add((*slots)[9 * k + 3 * a + 1], d2);
      dfdx->add((*slots)[9 * k + 3 * a + 2], d3);
    }
  }
}

}  // namespace valve
