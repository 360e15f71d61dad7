// Helpers around the integrators' linear systems.
#include <catch2/catch.hpp>

#include <random>

#include "valve/solver/constrained_system.hpp"

using namespace valve;

namespace {
// A random n x n matrix with a structurally symmetric pattern (each entry has its mirror),
// values independent on the two sides.
SparseMatrix random_structurally_symmetric(int n, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<Eigen::Triplet<double>> t;
  for (int i = 0; i < n; ++i) {
    t.emplace_back(i, i, 4 + u(rng));
    for (int k = 0; k < 3; ++k) {
      const int j = static_cast<int>(rng() % n);
      if (j == i) continue;
      t.emplace_back(i, j, u(rng));
      t.emplace_back(j, i, u(rng));
    }
  }
  SparseMatrix A(n, n);
  A.setFromTriplets(t.begin(), t.end());
  A.makeCompressed();
  return A;
}

double max_difference(const SparseMatrix& a, const SparseMatrix& b) {
  return SparseMatrix(a - b).coeffs().cwiseAbs().maxCoeff();
}
}  // namespace

TEST_CASE("SymmetricPart equals (A + A^T)/2 on kept, changed and unsymmetric patterns", "[solver]") {
  std::mt19937 rng(11);
  SymmetricPart part;
  SparseMatrix A = random_structurally_symmetric(60, rng);
  CHECK(max_difference(part.of(A), symmetric_part(A)) == 0);
  // New values on the same pattern: the cached map must pick them up.
  for (int k = 0; k < A.nonZeros(); ++k) A.valuePtr()[k] *= 1.0 + 0.1 * k;
  CHECK(max_difference(part.of(A), symmetric_part(A)) == 0);
  CHECK(max_difference(part.of(A), SparseMatrix(SparseMatrix(A.transpose()) + A) * 0.5) < 1e-15);
  // An entry without its mirror: the pattern gains the mirror's position.
  SparseMatrix lopsided = A;
  lopsided.coeffRef(0, 59) = 0.7;
  lopsided.coeffRef(59, 0) = 0.0;
  lopsided.prune(0.0);
  lopsided.makeCompressed();
  REQUIRE(lopsided.coeff(59, 0) == 0);
  const SparseMatrix& S = part.of(lopsided);
  CHECK(S.coeff(59, 0) == Approx(0.35));
  CHECK(max_difference(S, symmetric_part(lopsided)) == 0);
  // Another pattern altogether.
  const SparseMatrix B = random_structurally_symmetric(60, rng);
  CHECK(max_difference(part.of(B), symmetric_part(B)) == 0);
}

TEST_CASE("mirror_entries pairs each stored (i, j) with (j, i), or is empty", "[solver]") {
  std::mt19937 rng(12);
  const SparseMatrix A = random_structurally_symmetric(80, rng);
  const std::vector<int> mirror = mirror_entries(A);
  REQUIRE(mirror.size() == static_cast<size_t>(A.nonZeros()));
  std::vector<int> column_of(A.nonZeros());
  for (int j = 0; j < A.outerSize(); ++j)
    for (int k = A.outerIndexPtr()[j]; k < A.outerIndexPtr()[j + 1]; ++k) column_of[k] = j;
  int wrong = 0;
  for (int k = 0; k < A.nonZeros(); ++k)
    if (A.innerIndexPtr()[mirror[k]] != column_of[k] || column_of[mirror[k]] != A.innerIndexPtr()[k]) ++wrong;
  CHECK(wrong == 0);
  SparseMatrix lopsided = A;
  lopsided.coeffRef(3, 77) = 1.0;
  lopsided.coeffRef(77, 3) = 0.0;
  lopsided.prune(0.0);
  lopsided.makeCompressed();
  CHECK(mirror_entries(lopsided).empty());
}
