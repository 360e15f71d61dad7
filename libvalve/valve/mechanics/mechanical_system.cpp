#include "valve/mechanics/mechanical_system.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "valve/core/error.hpp"

namespace valve {

MechanicalSystem::MechanicalSystem(const TriMesh& mesh, double density, double thickness)
    : n_(mesh.num_nodes()), node_mass_(n_, 0.0), dof_mass_(3 * n_), constrained_(3 * n_, 0) {
  for (const auto& t : mesh.triangles) {
    const double m = density * thickness * triangle_area(mesh.points, t) / 3.0;
    for (int k = 0; k < 3; ++k) node_mass_[t[k]] += m;
  }
  for (int i = 0; i < n_; ++i) {
    // A node in no triangle would have no mass; give it a tiny one and fix it below.
    dof_mass_.segment<3>(3 * i).setConstant(node_mass_[i] > 0 ? node_mass_[i] : 1.0);
    if (node_mass_[i] <= 0 || (!mesh.roles.empty() && mesh.roles[i] != NodeRole::free)) fix_node(i);
  }
}

void MechanicalSystem::add_node_mass(int i, double mass) {
  node_mass_[i] += mass;
  dof_mass_.segment<3>(3 * i).setConstant(node_mass_[i] > 0 ? node_mass_[i] : 1.0);
}

void MechanicalSystem::add_term(std::unique_ptr<ForceTerm> term) {
  if (term->depends_on_velocity()) has_velocity_terms_ = true;
  if (auto* d = dynamic_cast<DampingTerm*>(term.get())) damping_ = d;
  timings_.push_back({term->name(), 0.0, 0});
  terms_.push_back(std::move(term));
}

void MechanicalSystem::finalize() {
  std::vector<std::pair<int, int>> pairs;
  for (const auto& t : terms_) t->couplings(pairs);
  dfdx_ = BlockJacobian(n_, pairs);
  dfdv_ = BlockJacobian(n_, {});
}

bool MechanicalSystem::evaluate(const State& s, VecX& f, bool want_dfdx, bool want_dfdv, bool load_stiffness) {
  if (want_dfdx) {
    bool grown = false;
    for (auto& t : terms_) grown |= t->update_couplings(s.x);
    if (grown) finalize();
  }
  f.setZero(3 * n_);
  if (want_dfdx) dfdx_.set_zero();
  if (want_dfdv) dfdv_.set_zero();
  for (size_t k = 0; k < terms_.size(); ++k) {
    const auto t0 = std::chrono::steady_clock::now();
    const bool jacobian = want_dfdx && (load_stiffness || !terms_[k]->is_external_load());
    terms_[k]->add(s, f, jacobian ? &dfdx_ : nullptr, want_dfdv ? &dfdv_ : nullptr);
    timings_[k].seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    ++timings_[k].calls;
  }
  return f.allFinite();
}

void MechanicalSystem::update_critical_damping(const State& s, VecX& f) {
  if (!damping_ || damping_->mode() != DampingTerm::Mode::critical) return;
  VecX fd = VecX::Zero(f.size());
  damping_->add(s, fd, nullptr, nullptr);
  f -= fd;
  damping_->update_from_stiffness(dfdx_);
  fd.setZero();
  dfdv_.set_zero();
  for (const auto& t : terms_)
    if (t->depends_on_velocity()) t->add(s, fd, nullptr, &dfdv_);
  f += fd;
}

VecX MechanicalSystem::external_force(const State& s) const {
  VecX f = VecX::Zero(3 * n_);
  for (const auto& t : terms_)
    if (t->is_external_load()) t->add(s, f, nullptr, nullptr);
  return f;
}

bool MechanicalSystem::energy(const State& s, double& e) const {
  e = 0;
  for (const auto& t : terms_) {
    if (t->depends_on_velocity()) continue;
    if (!t->energy(s, e)) return false;
  }
  return true;
}

bool MechanicalSystem::internal_energy(const State& s, double& e, std::string* missing) const {
  e = 0;
  for (const auto& t : terms_) {
    if (t->depends_on_velocity() || t->is_external_load()) continue;
    if (!t->energy(s, e)) {
      if (missing) *missing = t->name();
      return false;
    }
  }
  return true;
}

void MechanicalSystem::start_at(const VecX& x) {
  for (auto& t : terms_) t->start_at(x);
}

void MechanicalSystem::set_jacobian_mode(JacobianMode mode) {
  for (auto& t : terms_) t->set_jacobian_mode(mode);
}

double MechanicalSystem::step_ratio(const VecX& x, const VecX& dx) const {
  double r = 0;
  for (const auto& t : terms_) r = std::max(r, t->step_ratio(x, dx));
  return r;
}

double MechanicalSystem::max_step_length() const {
  double m = std::numeric_limits<double>::infinity();
  for (const auto& t : terms_) m = std::min(m, t->max_step_length());
  return m;
}

double MechanicalSystem::max_free_force(const VecX& f) const {
  double m = 0;
  for (int i = 0; i < 3 * n_; ++i)
    if (!constrained_[i]) m = std::max(m, std::abs(f[i]));
  return m;
}

}  // namespace valve
