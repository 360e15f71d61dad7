// When the quasi-static solver's contact Hessians are exact rather than projected.
#include <catch2/catch.hpp>

#include "valve/solver/quasistatic_solver.hpp"

using namespace valve;

TEST_CASE("exact contact Hessians from a proximal step of 1e4 ms² on", "[solver][quasistatic]") {
  const ExactHessianSchedule schedule;
  CHECK_FALSE(schedule.exact_at(0.01));
  CHECK_FALSE(schedule.exact_at(9.99e3));
  CHECK(schedule.exact_at(1e4));
  CHECK(schedule.exact_at(kMaxProximalStep));
}

TEST_CASE("after a failed exact direction, exact Hessians wait until the proximal step has grown fourfold", "[solver][quasistatic]") {
  ExactHessianSchedule schedule;
  schedule.failed_at(1e6);
  CHECK_FALSE(schedule.exact_at(1e6));
  CHECK_FALSE(schedule.exact_at(3.99e6));
  CHECK(schedule.exact_at(4e6));
}

TEST_CASE("exact Hessians come back at the largest proximal step after failing there", "[solver][quasistatic]") {
  // δ stops growing at kMaxProximalStep: a threshold beyond it would leave Newton's last
  // iterations on projected Hessians for good.
  ExactHessianSchedule schedule;
  schedule.failed_at(kMaxProximalStep / 2);
  CHECK(schedule.exact_at(kMaxProximalStep));
  schedule.failed_at(kMaxProximalStep);
  CHECK(schedule.exact_at(kMaxProximalStep));
}
