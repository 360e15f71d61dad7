#pragma once
// A 3N x 3N sparse matrix of 3x3 node blocks whose pattern is built once from the node
// pairs the force terms couple; force terms add blocks into it without allocating.
#include <Eigen/SparseCore>
#include <utility>
#include <vector>

#include "valve/core/types.hpp"

namespace valve {

using SparseMatrix = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;

/// Where a block lives in BlockJacobian::matrix(): column c of the block starts at
/// first + c * stride. Valid until the pattern changes (pattern_revision()).
struct BlockSlot {
  int first = 0, stride = 0;
};

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
  /// The slot of block (i, j) (the pair must be in the pattern), and adds through it
  /// without the search add(i, j, B) does.
  BlockSlot slot(int i, int j) const;
  void add(const BlockSlot& slot, const Mat3& B) {
    double* v = m_.valuePtr() + slot.first;
    for (int c = 0; c < 3; ++c, v += slot.stride) {
      v[0] += B(0, c);
      v[1] += B(1, c);
      v[2] += B(2, c);
    }
  }
  /// Adds a * I through a slot.
  void add_identity(const BlockSlot& slot, double a) {
    double* v = m_.valuePtr() + slot.first;
    for (int c = 0; c < 3; ++c, v += slot.stride) v[c] += a;
  }

  const SparseMatrix& matrix() const { return m_; }
  SparseMatrix& matrix() { return m_; }
  int num_nodes() const { return n_; }
  /// The 3x3 diagonal block of node i.
  Mat3 diagonal_block(int i) const;
  /// Identifies the sparsity pattern: a new value for every constructed pattern, so a
  /// consumer that caches index maps over matrix() can tell when to rebuild them.
  long pattern_revision() const { return revision_; }
  /// The coupled node pairs (a < b) of the pattern, sorted.
  std::vector<std::pair<int, int>> node_pairs() const;

 private:
  int position(int i, int j) const;  // index of node i within node column j's list
  int n_ = 0;
  long revision_ = 0;
  SparseMatrix m_;
  std::vector<std::vector<int>> column_nodes_;  // sorted node rows per node column
};

/// The slots of a fixed list of node pairs, looked up again only when the Jacobian's pattern
/// changes (contact grows it). Force terms with a fixed stencil keep one: the binary search
/// of add(i, j, B) was 12 % of the sample mitral closure's run time.
class BlockSlotCache {
 public:
  explicit BlockSlotCache(std::vector<std::pair<int, int>> pairs = {}) : pairs_(std::move(pairs)) {}
  /// Slots of the pairs, in their order, for J's current pattern.
  const std::vector<BlockSlot>& slots(const BlockJacobian& J) {
    if (J.pattern_revision() != revision_) {
      slots_.clear();
      for (const auto& [i, j] : pairs_) slots_.push_back(J.slot(i, j));
      revision_ = J.pattern_revision();
    }
    return slots_;
  }

 private:
  std::vector<std::pair<int, int>> pairs_;
  std::vector<BlockSlot> slots_;
  long revision_ = -1;
};

}  // namespace valve
