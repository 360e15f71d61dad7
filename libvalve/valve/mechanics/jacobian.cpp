#include "valve/mechanics/jacobian.hpp"

#include <algorithm>
#include <atomic>
#include <cassert>

#include "valve/core/error.hpp"

namespace valve {

BlockJacobian::BlockJacobian(int num_nodes, const std::vector<std::pair<int, int>>& couplings)
    : n_(num_nodes), m_(3 * num_nodes, 3 * num_nodes), column_nodes_(num_nodes) {
  static std::atomic<long> patterns{0};
  revision_ = ++patterns;
  for (int i = 0; i < n_; ++i) column_nodes_[i].push_back(i);
  for (const auto& [a, b] : couplings) {
    if (a == b) continue;
    column_nodes_[b].push_back(a);
    column_nodes_[a].push_back(b);
  }
  size_t nnz = 0;
  for (auto& c : column_nodes_) {
    std::sort(c.begin(), c.end());
    c.erase(std::unique(c.begin(), c.end()), c.end());
    nnz += 9 * c.size();
  }
  // Build the compressed pattern directly: column 3j+c holds rows 3i+r for i in column j's list.
  m_.resizeNonZeros(static_cast<Eigen::Index>(nnz));
  int* outer = m_.outerIndexPtr();
  int* inner = m_.innerIndexPtr();
  int k = 0;
  for (int j = 0; j < n_; ++j)
    for (int c = 0; c < 3; ++c) {
      outer[3 * j + c] = k;
      for (int i : column_nodes_[j])
        for (int r = 0; r < 3; ++r) inner[k++] = 3 * i + r;
    }
  outer[3 * n_] = k;
  set_zero();
}

std::vector<std::pair<int, int>> BlockJacobian::node_pairs() const {
  std::vector<std::pair<int, int>> pairs;
  for (int a = 0; a < n_; ++a)
    for (int b : column_nodes_[a])
      if (b > a) pairs.emplace_back(a, b);
  return pairs;
}

void BlockJacobian::set_zero() { std::fill_n(m_.valuePtr(), m_.nonZeros(), 0.0); }

int BlockJacobian::position(int i, int j) const {
  const auto& c = column_nodes_[j];
  auto it = std::lower_bound(c.begin(), c.end(), i);
  if (it == c.end() || *it != i) throw Error("BlockJacobian: node pair not in the pattern");
  return static_cast<int>(it - c.begin());
}

void BlockJacobian::add(int i, int j, const Mat3& B) {
  const int p = position(i, j);
  double* v = m_.valuePtr();
  const int* outer = m_.outerIndexPtr();
  for (int c = 0; c < 3; ++c) {
    double* col = v + outer[3 * j + c] + 3 * p;
    col[0] += B(0, c);
    col[1] += B(1, c);
    col[2] += B(2, c);
  }
}

BlockSlot BlockJacobian::slot(int i, int j) const {
  const int* outer = m_.outerIndexPtr();
  return {outer[3 * j] + 3 * position(i, j), outer[3 * j + 1] - outer[3 * j]};
}

void BlockJacobian::add_diagonal(int i, double s) {
  const int p = position(i, i);
  double* v = m_.valuePtr();
  const int* outer = m_.outerIndexPtr();
  for (int c = 0; c < 3; ++c) v[outer[3 * i + c] + 3 * p + c] += s;
}

Mat3 BlockJacobian::diagonal_block(int i) const {
  const int p = position(i, i);
  const double* v = m_.valuePtr();
  const int* outer = m_.outerIndexPtr();
  Mat3 B;
  for (int c = 0; c < 3; ++c)
    for (int r = 0; r < 3; ++r) B(r, c) = v[outer[3 * i + c] + 3 * p + r];
  return B;
}

}  // namespace valve
