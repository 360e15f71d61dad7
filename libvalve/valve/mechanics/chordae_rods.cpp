#include "valve/mechanics/chordae_rods.hpp"

#include "valve/mechanics/axial_pair.hpp"

namespace valve {

void ChordaeTerm::couplings(std::vector<std::pair<int, int>>& pairs) const {
  for (const Rod& r : rods_) pairs.emplace_back(r.a, r.b);
}

std::vector<double> ChordaeTerm::tensions(const VecX& x) const {
  std::vector<double> t;
  t.reserve(rods_.size());
  for (const Rod& r : rods_) {
    const double L = (node3(x, r.b) - node3(x, r.a)).norm();
    t.push_back(L > r.rest_length ? r.axial_stiffness * (L - r.rest_length) / r.rest_length : 0.0);
  }
  return t;
}

void ChordaeTerm::add(const State& s, VecX& f, BlockJacobian* dfdx, BlockJacobian*) const {
  for (const Rod& r : rods_) {
    const Vec3 e = node3(s.x, r.b) - node3(s.x, r.a);
    const double L = e.norm();
    if (L <= r.rest_length) continue;
    const double k = r.axial_stiffness / r.rest_length;
    add_axial_pair(r.a, r.b, e / L, L, k * (L - r.rest_length), k, f, dfdx);
  }
}

bool ChordaeTerm::energy(const State& s, double& e) const {
  for (const Rod& r : rods_) {
    const double L = (node3(s.x, r.b) - node3(s.x, r.a)).norm();
    if (L > r.rest_length) e += 0.5 * r.axial_stiffness / r.rest_length * (L - r.rest_length) * (L - r.rest_length);
  }
  return true;
}

}  // namespace valve
