#include "valve/solver/constrained_system.hpp"

#include <algorithm>
#include <cmath>

#include "valve/core/error.hpp"

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

const SparseMatrix& SymmetricPart::of(const SparseMatrix& A) {
  if (!same_pattern(A)) map_pattern(A);
  if (mirror_.empty()) {
    S_ = symmetric_part(A);
    return S_;
  }
  const double* a = A.valuePtr();
  double* s = S_.valuePtr();
  for (size_t k = 0; k < mirror_.size(); ++k) s[k] = 0.5 * (a[k] + a[mirror_[k]]);
  return S_;
}

bool SymmetricPart::same_pattern(const SparseMatrix& A) const {
  return !mirror_.empty() && A.isCompressed() && A.rows() == S_.rows() && A.cols() == S_.cols() &&
         A.nonZeros() == S_.nonZeros() &&
         std::equal(A.outerIndexPtr(), A.outerIndexPtr() + A.outerSize() + 1, S_.outerIndexPtr()) &&
         std::equal(A.innerIndexPtr(), A.innerIndexPtr() + A.nonZeros(), S_.innerIndexPtr());
}

void SymmetricPart::map_pattern(const SparseMatrix& A) {
  mirror_ = mirror_entries(A);
  if (!mirror_.empty()) S_ = A;
}

std::vector<int> mirror_entries(const SparseMatrix& A) {
  if (!A.isCompressed() || A.rows() != A.cols()) return {};
  const int* outer = A.outerIndexPtr();
  const int* inner = A.innerIndexPtr();
  std::vector<int> next(outer, outer + A.outerSize());  // per column, its first unmatched entry
  std::vector<int> mirror(A.nonZeros());
  for (int j = 0; j < A.outerSize(); ++j)
    for (int k = outer[j]; k < outer[j + 1]; ++k) {
      const int i = inner[k];
      const int m = next[i]++;
      if (m >= outer[i + 1] || inner[m] != j) return {};  // (j, i) missing: not structurally symmetric
      mirror[k] = m;
    }
  return mirror;
}

namespace {

// Index of the entry (row, col) in a compressed column-major matrix, or -1.
int entry_index(const SparseMatrix& A, int row, int col) {
  const int* inner = A.innerIndexPtr();
  const int begin = A.outerIndexPtr()[col], end = A.outerIndexPtr()[col + 1];
  const int* it = std::lower_bound(inner + begin, inner + end, row);
  return it != inner + end && *it == row ? static_cast<int>(it - inner) : -1;
}

}  // namespace

void SystemMatrix::build_maps(const BlockJacobian& dfdx, const BlockJacobian* dfdv) {
  A_ = dfdx.matrix();
  const int n = static_cast<int>(A_.cols());
  const int nnz = static_cast<int>(A_.nonZeros());
  transpose_ = mirror_entries(A_);
  rows_.assign(A_.innerIndexPtr(), A_.innerIndexPtr() + nnz);
  diagonal_.assign(n, -1);
  for (int j = 0; j < n; ++j)
    for (int k = A_.outerIndexPtr()[j]; k < A_.outerIndexPtr()[j + 1]; ++k)
      if (rows_[k] == j) diagonal_[j] = k;
  // BlockJacobian patterns are structurally symmetric with every diagonal block present.
  if (transpose_.size() != static_cast<size_t>(nnz) || std::find(diagonal_.begin(), diagonal_.end(), -1) != diagonal_.end())
    throw Error("SystemMatrix: the Jacobian pattern is not structurally symmetric with a full diagonal");
  dfdv_slot_.clear();
  if (dfdv) {
    const SparseMatrix& V = dfdv->matrix();
    for (int j = 0; j < n; ++j)
      for (int k = V.outerIndexPtr()[j]; k < V.outerIndexPtr()[j + 1]; ++k) {
        const int slot = entry_index(A_, V.innerIndexPtr()[k], j);
        if (slot < 0) throw Error("SystemMatrix: the velocity Jacobian has entries outside the position Jacobian's pattern");
        dfdv_slot_.push_back(slot);
      }
  }
  dfdx_revision_ = dfdx.pattern_revision();
  dfdv_revision_ = dfdv ? dfdv->pattern_revision() : -1;
}

double free_norm(const VecX& f, const std::vector<char>& constrained) {
  double s = 0;
  for (int i = 0; i < f.size(); ++i)
    if (!constrained[i]) s += f[i] * f[i];
  return std::sqrt(s);
}

const SparseMatrix& SystemMatrix::assemble(const BlockJacobian& dfdx, double c_x, const BlockJacobian* dfdv,
                                           double c_v, const VecX& mass, const std::vector<char>& constrained,
                                           bool symmetric, VecX& b) {
  if (dfdx.pattern_revision() != dfdx_revision_ || (dfdv ? dfdv->pattern_revision() : -1) != dfdv_revision_)
    build_maps(dfdx, dfdv);
  const int n = static_cast<int>(A_.cols());
  const int nnz = static_cast<int>(A_.nonZeros());
  double* a = A_.valuePtr();
  const double* x = dfdx.matrix().valuePtr();
  for (int k = 0; k < nnz; ++k) a[k] = c_x * x[k];
  if (dfdv) {
    const double* v = dfdv->matrix().valuePtr();
    for (size_t k = 0; k < dfdv_slot_.size(); ++k) a[dfdv_slot_[k]] += c_v * v[k];
  }
  for (int j = 0; j < n; ++j) a[diagonal_[j]] += mass[j];
  if (symmetric)
    for (int k = 0; k < nnz; ++k)
      if (transpose_[k] > k) a[k] = a[transpose_[k]] = 0.5 * (a[k] + a[transpose_[k]]);
  double diag_sum = 0;
  int diag_count = 0;
  for (int j = 0; j < n; ++j)
    if (!constrained[j]) diag_sum += std::abs(a[diagonal_[j]]), ++diag_count;
  const double pivot = diag_count > 0 && diag_sum > 0 ? diag_sum / diag_count : 1.0;
  for (int j = 0; j < n; ++j)
    for (int k = A_.outerIndexPtr()[j]; k < A_.outerIndexPtr()[j + 1]; ++k)
      if (constrained[j] || constrained[rows_[k]]) a[k] = rows_[k] == j ? pivot : 0.0;
  for (int j = 0; j < n; ++j)
    if (constrained[j]) b[j] = 0;
  return A_;
}

}  // namespace valve
