// The block Jacobian's pattern bookkeeping.
#include <catch2/catch.hpp>

#include "valve/mechanics/jacobian.hpp"

using namespace valve;

TEST_CASE("BlockJacobian node_pairs lists each coupling once, as (a < b), sorted", "[mechanics]") {
  // Repeats, both orders and a self-coupling, as terms hand them over.
  const BlockJacobian J(5, {{3, 1}, {0, 4}, {1, 3}, {2, 2}, {4, 0}, {1, 0}});
  const std::vector<std::pair<int, int>> expected{{0, 1}, {0, 4}, {1, 3}};
  CHECK(J.node_pairs() == expected);
  // Every listed pair has its blocks in the pattern both ways; others do not.
  for (const auto& [a, b] : expected) {
    CHECK_NOTHROW(J.slot(a, b));
    CHECK_NOTHROW(J.slot(b, a));
  }
  CHECK_THROWS(J.slot(2, 3));
  CHECK(BlockJacobian(3, {}).node_pairs().empty());
}
