#include "valve/mechanics/chordae_rods.hpp"

#include <stdexcept>

#include "valve/mechanics/axial_pair.hpp"

namespace valve {

ChordaeTerm::ChordaeTerm(std::vector<Rod> rods) : rods_(std::move(rods)) {
  for (const Rod& r : rods_)
    if (!r.law || !(r.area > 0) || !(r.rest_length > 0))
      throw std::invalid_argument("ChordaeTerm: every rod needs a law, a positive section area and rest length");
}

void ChordaeTerm::couplings(std::vector<std::pair<int, int>>& pairs) const {
  for (const Rod& r : rods_) pairs.emplace_back(r.a, r.b);
}

std::vector<double> ChordaeTerm::tensions(const VecX& x) const {
  std::vector<double> t;
  t.reserve(rods_.size());
  for (const Rod& r : rods_) {
    const double L = (node3(x, r.b) - node3(x, r.a)).norm();
    t.push_back(r.area * r.law->response(L / r.rest_length).nominal_stress);
  }
  return t;
}

void ChordaeTerm::add(const State& s, VecX& f, BlockJacobian* dfdx, BlockJacobian*) const {
  for (const Rod& r : rods_) {
    const Vec3 e = node3(s.x, r.b) - node3(s.x, r.a);
    const double L = e.norm();
    if (L <= r.rest_length) continue;
    const RodResponse p = r.law->response(L / r.rest_length);
    add_axial_pair(r.a, r.b, e / L, L, r.area * p.nominal_stress, r.area * p.stiffness / r.rest_length, f, dfdx);
  }
}

bool ChordaeTerm::energy(const State& s, double& e) const {
  for (const Rod& r : rods_) {
    const double L = (node3(s.x, r.b) - node3(s.x, r.a)).norm();
    if (L > r.rest_length) e += r.area * r.rest_length * r.law->response(L / r.rest_length).energy;
  }
  return true;
}

}  // namespace valve
