#include "valve/mechanics/membrane_fe.hpp"

#include <Eigen/Geometry>
#include <Eigen/LU>

#include "valve/core/error.hpp"
#include "valve/mechanics/kinematics.hpp"

namespace valve {


MembraneFETerm::MembraneFETerm(const TriMesh& mesh, std::shared_ptr<const MaterialLaw> law,
                               double thickness)
    : law_(std::move(law)) {
  elements_.reserve(mesh.triangles.size());
  for (int t = 0; t < mesh.num_triangles(); ++t) {
    double area = 0;
    const Mat2 Dm_inv = material_frame_inverse(mesh, t, &area);
    elements_.push_back({mesh.triangles[t], Dm_inv, area * thickness});
  }
  std::vector<std::pair<int, int>> pairs;
  for (const auto& e : elements_)
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) pairs.emplace_back(e.nodes[a], e.nodes[b]);
  slots_ = BlockSlotCache(std::move(pairs));
}

void MembraneFETerm::couplings(std::vector<std::pair<int, int>>& pairs) const {
  for (const auto& e : elements_)
    for (int a = 0; a < 3; ++a) pairs.emplace_back(e.nodes[a], e.nodes[(a + 1) % 3]);
}

Voigt MembraneFETerm::green_strain(const VecX& x, int t) const {
  const auto& e = elements_[t];
  return valve::green_strain(deformation_gradient(x, e.nodes, e.Dm_inv));
}

void MembraneFETerm::add(const State& s, VecX& f, BlockJacobian* dfdx, BlockJacobian*) const {
  const std::vector<BlockSlot>* slots = dfdx ? &slots_.slots(*dfdx) : nullptr;
  for (std::size_t k = 0; k < elements_.size(); ++k) {
    const Element& e = elements_[k];
    const Mat32 F = deformation_gradient(s.x, e.nodes, e.Dm_inv);
    const Voigt E = valve::green_strain(F);
    Voigt S;
    Mat3 D;
    if (dfdx)
      law_->stress_and_tangent(E, S, D);
    else
      S = law_->stress(E);
    // Shape-function gradients in the rest frame.
    Eigen::Matrix<double, 2, 3> gradN;
    gradN.col(1) = e.Dm_inv.row(0).transpose();
    gradN.col(2) = e.Dm_inv.row(1).transpose();
    gradN.col(0) = -gradN.col(1) - gradN.col(2);
    Mat3 B[3];
    for (int a = 0; a < 3; ++a) {
      const double g1 = gradN(0, a), g2 = gradN(1, a);
      B[a].row(0) = g1 * F.col(0).transpose();
      B[a].row(1) = g2 * F.col(1).transpose();
      B[a].row(2) = g2 * F.col(0).transpose() + g1 * F.col(1).transpose();
      node3(f, e.nodes[a]) -= e.volume * B[a].transpose() * S;
    }
    if (!dfdx) continue;
    Mat2 S2;
    S2 << S[0], S[2], S[2], S[1];
    for (int a = 0; a < 3; ++a) {
      const Eigen::Matrix<double, 3, 3> BtD = B[a].transpose() * D;
      for (int b = 0; b < 3; ++b) {
        const double geo = gradN.col(a).dot(S2 * gradN.col(b));
        Mat3 K = BtD * B[b];
        K.diagonal().array() += geo;
        dfdx->add((*slots)[9 * k + 3 * a + b], -e.volume * K);
      }
    }
  }
}

bool MembraneFETerm::energy(const State& s, double& e) const {
  double sum = 0;
  for (const auto& el : elements_) sum += el.volume * law_->energy(valve::green_strain(deformation_gradient(s.x, el.nodes, el.Dm_inv)));
  e += sum;
  return true;
}

}  // namespace valve
