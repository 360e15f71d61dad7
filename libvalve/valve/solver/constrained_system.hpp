#pragma once
// Helpers shared by the integrators: impose constrained degrees of freedom on a linear
// system, and take the symmetric part for solvers that need one.
#include <vector>

#include "valve/mechanics/jacobian.hpp"

namespace valve {

/// For each constrained dof c with prescribed increment d_c: moves column c to the right-
/// hand side (b -= A(:,c) d_c), clears row and column c, puts the mean free diagonal on
/// A(c,c) and sets b_c accordingly. Keeps a symmetric A symmetric. This is equivalent to
/// the seed's infinite nodal mass (zero inverse-mass rows), written so that Cholesky
/// applies.
void apply_constraints(SparseMatrix& A, VecX& b, const std::vector<char>& constrained,
                       const VecX* prescribed = nullptr);

/// (A + Aᵀ)/2.
SparseMatrix symmetric_part(const SparseMatrix& A);

/// Euclidean norm of f over the unconstrained dofs.
double free_norm(const VecX& f, const std::vector<char>& constrained);

/// For a compressed matrix whose pattern is structurally symmetric (each stored (i, j) has a
/// stored (j, i)), the index of each stored entry's mirror; empty for any other pattern.
/// O(nnz): columns are visited in order, so the mirrors in each column come in row order.
std::vector<int> mirror_entries(const SparseMatrix& A);

/// (A + Aᵀ)/2 for a sequence of matrices that mostly share one pattern, as symmetric_part()
/// computes it. A structurally symmetric pattern (the integrators' system matrices are)
/// keeps A's pattern, and each entry pairs with its mirror through an index map built once
/// per pattern; any other pattern goes through symmetric_part(). Why: the transpose and sum
/// allocated two sparse matrices per step, 5 % of the sample mitral closure's wall time.
class SymmetricPart {
 public:
  /// Valid until the next call.
  const SparseMatrix& of(const SparseMatrix& A);

 private:
  bool same_pattern(const SparseMatrix& A) const;
  void map_pattern(const SparseMatrix& A);
  SparseMatrix S_;
  std::vector<int> mirror_;  // per stored entry of A, the index of its mirror entry
};

/// The implicit integrators' system matrix
///     A = diag(mass) + c_x ∂f/∂x + c_v ∂f/∂v,
/// optionally replaced by its symmetric part, with the constrained dofs imposed exactly as
/// apply_constraints() does (without prescribed increments; their b entries become 0).
/// Same result as composing those with Eigen expressions, but assembled in place over
/// ∂f/∂x's pattern with index maps kept until the pattern changes: the expression route
/// allocated three sparse matrices and a transpose per step, measured at a third of the
/// wall time of the sample mitral closure.
class SystemMatrix {
 public:
  /// `dfdv` may be null; its pattern must lie within dfdx's (diagonal blocks do).
  const SparseMatrix& assemble(const BlockJacobian& dfdx, double c_x, const BlockJacobian* dfdv, double c_v,
                               const VecX& mass, const std::vector<char>& constrained, bool symmetric, VecX& b);

 private:
  void build_maps(const BlockJacobian& dfdx, const BlockJacobian* dfdv);
  SparseMatrix A_;
  long dfdx_revision_ = -1, dfdv_revision_ = -1;
  std::vector<int> transpose_;  // per stored entry, the index of its mirror entry
  std::vector<int> diagonal_;   // per column, the index of its diagonal entry
  std::vector<int> rows_;       // per stored entry, its row (cols: column loop)
  std::vector<int> dfdv_slot_;  // per stored entry of dfdv, its index in A
};

}  // namespace valve
