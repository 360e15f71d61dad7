#include "valve/solver/constrained_system.hpp"

#include <cmath>

namespace valve {

void apply_constraints(SparseMatrix& A, VecX& b, const std::vector<char>& constrained, const VecX* prescribed) {
  const int n = static_cast<int>(A.cols());
  double diag_sum = 0;
  int diag_count = 0;
  for (int j = 0; j < n; ++j) {
    if (constrained[j]) continue;
    diag_sum += std::abs(A.coeff(j, j));
    ++diag_count;
  }
  const double pivot = diag_count > 0 && diag_sum > 0 ? diag_sum / diag_count : 1.0;
  for (int j = 0; j < n; ++j) {
    for (SparseMatrix::InnerIterator it(A, j); it; ++it) {
      const int i = static_cast<int>(it.row());
      if (constrained[j] && !constrained[i] && prescribed) b[i] -= it.value() * (*prescribed)[j];
      if (constrained[i] || constrained[j]) it.valueRef() = (i == j) ? pivot : 0.0;
    }
  }
  for (int j = 0; j < n; ++j)
    if (constrained[j]) b[j] = prescribed ? pivot * (*prescribed)[j] : 0.0;
}

SparseMatrix symmetric_part(const SparseMatrix& A) {
  SparseMatrix At = A.transpose();
  SparseMatrix S = 0.5 * (A + At);
  return S;
}

}  // namespace valve
