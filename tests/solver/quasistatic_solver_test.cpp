// The quasi-static solver's schedules: when contact Hessians are exact rather than projected,
// how accurately each Newton direction is solved, and how many directions an increment may take.
#include <catch2/catch.hpp>

#include <cmath>

#include "valve/solver/quasistatic_solver.hpp"

using namespace valve;

TEST_CASE("exact contact Hessians from a proximal step of 1e4 ms² on", "[solver][quasistatic]") {
  ExactHessianSchedule schedule;
  schedule.record_residual(1e-3);
  CHECK_FALSE(schedule.exact_at(0.01));
  CHECK_FALSE(schedule.exact_at(9.99e3));
  CHECK(schedule.exact_at(1e4));
  CHECK(schedule.exact_at(kMaxProximalStep));
}

TEST_CASE("exact contact Hessians once an increment's residual has come within a tenth of the load", "[solver][quasistatic]") {
  ExactHessianSchedule schedule;
  schedule.record_residual(0.44);  // settling into contact: projected whatever the proximal step
  CHECK_FALSE(schedule.exact_at(kMaxProximalStep));
  schedule.record_residual(0.1);
  CHECK(schedule.exact_at(1e4));
  schedule.record_residual(0.3);  // across a kink the residual may rise again: exact ones stay
  CHECK(schedule.exact_at(1e4));
  schedule.start_increment();  // the next load increment starts far from its equilibrium
  CHECK_FALSE(schedule.exact_at(1e4));
}

TEST_CASE("after a failed exact direction, exact Hessians wait until the proximal step has grown fourfold", "[solver][quasistatic]") {
  ExactHessianSchedule schedule;
  schedule.record_residual(1e-3);
  schedule.failed_at(1e6);
  CHECK_FALSE(schedule.exact_at(1e6));
  CHECK_FALSE(schedule.exact_at(3.99e6));
  CHECK(schedule.exact_at(4e6));
}

TEST_CASE("exact Hessians come back at the largest proximal step after failing there", "[solver][quasistatic]") {
  // δ stops growing at kMaxProximalStep: a threshold beyond it would leave Newton's last
  // iterations on projected Hessians for good.
  ExactHessianSchedule schedule;
  schedule.record_residual(1e-3);
  schedule.failed_at(kMaxProximalStep / 2);
  CHECK(schedule.exact_at(kMaxProximalStep));
  schedule.failed_at(kMaxProximalStep);
  CHECK(schedule.exact_at(kMaxProximalStep));
}

TEST_CASE("the adaptive forcing term: loose far from equilibrium, tightening with the residual's fall", "[solver][quasistatic]") {
  ForcingTerm forcing(1e-10, 1e-12);
  CHECK(forcing.next(1.0) == Approx(0.01));  // the first direction of an increment: the ceiling
  CHECK(forcing.next(0.1) == Approx(9e-3));   // r falls tenfold: 0.9 · 0.1²
  CHECK(forcing.next(1e-3) == Approx(9e-5));  // a hundredfold: 0.9 · 1e-4
}

TEST_CASE("the adaptive forcing term solves no tighter than the residual target needs", "[solver][quasistatic]") {
  ForcingTerm forcing(1e-10, 1e-6);
  forcing.next(0.1);
  // 0.9 · 0.01² = 9e-5, but 0.5 τ / r = 0.5 · 1e-6 / 1e-3 = 5e-4 is enough for the target.
  CHECK(forcing.next(1e-3) == Approx(5e-4));
  // At r = 2e-6: 0.5 τ / r = 0.25, held at the ceiling.
  CHECK(forcing.next(2e-6) == Approx(0.01));
}

TEST_CASE("the adaptive forcing term stays within its ceiling and its floor", "[solver][quasistatic]") {
  ForcingTerm forcing(1e-3, 1e-12);
  CHECK(forcing.next(1.0) == Approx(0.01));
  // r halves: 0.9 · 0.25 = 0.225, capped at 0.01.
  CHECK(forcing.next(0.5) == Approx(0.01));
  // r falls 1e4-fold: 0.9e-8, raised to the floor 1e-3.
  CHECK(forcing.next(5e-5) == Approx(1e-3));
}

TEST_CASE("the adaptive forcing term solves the direction after a step without progress as fixed does", "[solver][quasistatic]") {
  // Choice 2 alone would give 0.9 · 1² (the ceiling, 0.01) to a residual that stays put, and
  // 0.5 τ / r would allow 5e-4 here; the floor is what `fixed` solves to.
  ForcingTerm forcing(1e-6, 1e-6);
  forcing.next(0.1);
  CHECK(forcing.next(1e-3) == Approx(5e-4));
  CHECK(forcing.next(1e-3) == Approx(1e-6));  // no progress
  CHECK(forcing.next(2e-3) == Approx(1e-6));  // the residual rose
  // Progress again: back to choice 2 (r halves: 0.9 · 0.25, capped at the ceiling).
  CHECK(forcing.next(1e-3) == Approx(0.01));
}

TEST_CASE("the adaptive forcing term is never tighter than a fixed tolerance above its ceiling", "[solver][quasistatic]") {
  // iterative_tolerance 0.05 (above the 0.01 ceiling): adaptive then solves to 0.05, as fixed would.
  ForcingTerm forcing(0.05, 1e-6);
  CHECK(forcing.next(1.0) == Approx(0.05));
  CHECK(forcing.next(1e-3) == Approx(0.05));
}

TEST_CASE("an increment still closing at its iteration limit goes on; one that only wanders stops there", "[solver][quasistatic]") {
  // At the limit of 4 the last quarter's best (1) is not below half the best before it (1).
  IncrementBudget levelled(4);
  const double level[] = {5, 2, 1, 1};
  for (int it = 0; it < 4; ++it) {
    REQUIRE(levelled.allows(it));
    levelled.record(level[it]);
  }
  CHECK(!levelled.allows(4));
  IncrementBudget still_falling(4);
  const double halving[] = {8, 4, 2, 0.9, 0.4, 0.2, 0.1, 0.04};
  int it = 0;
  for (; still_falling.allows(it) && it < 8; ++it) still_falling.record(halving[it]);
  CHECK(it == 8);  // extended at 4 (0.9 below half of 2) and runs its second round
  // A residual wandering between 1 and 3 never halves its best: no extension.
  IncrementBudget wandering(40);
  for (it = 0; wandering.allows(it); ++it) wandering.record(1 + 2 * std::abs(std::sin(0.7 * it)));
  CHECK(it == 40);
  // Falling fourfold each round of 10 for three rounds, then level: extended at 10, 20 and 30,
  // stopped at 40.
  IncrementBudget levels_off(10);
  double r = 1;
  for (it = 0; levels_off.allows(it); ++it) {
    if (it < 30 && it % 10 == 9) r *= 0.25;
    levels_off.record(r);
  }
  CHECK(it == 40);
}

TEST_CASE("a line search may not step back to any of the last eight iterates", "[solver][quasistatic]") {
  // Iterates 1 to 9 along x; the first has left the window when the ninth is recorded.
  RecentIterates recent;
  auto at = [](double position) {
    VecX y = VecX::Zero(6);
    y[0] = position;
    return y;
  };
  CHECK_FALSE(recent.returns_to(at(1), 1e-3));  // nothing recorded yet
  for (int k = 1; k <= 9; ++k) recent.push(at(k));
  for (int k = 2; k <= 9; ++k) CHECK(recent.returns_to(at(k + 5e-4), 1e-3));
  CHECK_FALSE(recent.returns_to(at(1), 1e-3));          // the ninth iterate back
  CHECK_FALSE(recent.returns_to(at(5.5), 1e-3));        // between iterates, farther than the tolerance
  CHECK_FALSE(recent.returns_to(VecX::Zero(3), 1e-3));  // another size: another system
}
