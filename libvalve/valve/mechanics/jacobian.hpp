#pragma once
// A 3N x 3N sparse matrix of 3x3 node blocks whose pattern is built once from the node
// pairs the force terms couple; force terms add blocks into it without allocating.
#include <Eigen/SparseCore>
#include <utility>
#include <vector>

#include "valve/core/types.hpp"

namespace valve {

using SparseMatrix = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;

class BlockJacobian {
 public:
  BlockJacobian() = default;
  /// Pattern: every diagonal block plus both (i,j) and (j,i) for each coupled pair.
  BlockJacobian(int num_nodes, const std::vector<std::pair<int, int>>& couplings);

  void set_zero();
  /// Adds block B at rows of node i, columns of node j. The pair must be in the pattern.
  void add(int i, int j, const Mat3& B);
  /// Adds s * I at node i's diagonal block.
  void add_diagonal(int i, double s);

  const SparseMatrix& matrix() const { return m_; }
  SparseMatrix& matrix() { return m_; }
  int num_nodes() const { return n_; }
  /// The 3x3 diagonal block of node i.
  Mat3 diagonal_block(int i) const;
  /// Identifies the sparsity pattern: a new value for every constructed pattern, so a
  /// consumer that caches index maps over matrix() can tell when to rebuild them.
  long pattern_revision() const { return revision_; }

 private:
  int position(int i, int j) const;  // index of node i within node column j's list
  int n_ = 0;
  long revision_ = 0;
  SparseMatrix m_;
  std::vector<std::vector<int>> column_nodes_;  // sorted node rows per node column
};

}  // namespace valve
