#include "valve/mechanics/damping.hpp"

#include <algorithm>
#include <cmath>

namespace valve {

DampingTerm::DampingTerm(std::vector<double> masses, Mode mode, double factor)
    : masses_(std::move(masses)), b_(masses_.size(), 0.0), mode_(mode), factor_(factor) {
  if (mode_ == Mode::mass_proportional)
    for (size_t i = 0; i < masses_.size(); ++i) b_[i] = factor_ * masses_[i];
}

void DampingTerm::update_from_stiffness(const BlockJacobian& dfdx) {
  if (mode_ != Mode::critical) return;
  for (size_t i = 0; i < masses_.size(); ++i) {
    const Mat3 K = -dfdx.diagonal_block(static_cast<int>(i));
    const double k = std::max({K(0, 0), K(1, 1), K(2, 2), 0.0});
    b_[i] = factor_ * 2.0 * std::sqrt(masses_[i] * k);
  }
}

void DampingTerm::add(const State& s, VecX& f, BlockJacobian*, BlockJacobian* dfdv) const {
  for (size_t i = 0; i < b_.size(); ++i) {
    if (b_[i] == 0) continue;
    node3(f, static_cast<int>(i)) -= b_[i] * node3(s.v, static_cast<int>(i));
    if (dfdv) dfdv->add_diagonal(static_cast<int>(i), -b_[i]);
  }
}

}  // namespace valve
