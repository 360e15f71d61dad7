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

}  // namespace valve
