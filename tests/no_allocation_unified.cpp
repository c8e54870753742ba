// No heap allocation in the right-hand sides of the continuous-time observers
// (the four algorithms of the unified formulation and the Kalman–Bucy
// baseline), nor in their steps over 2000 samples with the excitation monitor and
// fixed substeps, which the observer contract's factories do not configure.

#include <adaptobs/simulation/plant.hpp>

#include "support/allocation_counter.hpp"
#include "unified_fixtures.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace {

using adaptobs::testing::allocations_during;
using namespace adaptobs::testing::unified;

// The options the contract's factories leave at their defaults, and the
// right-hand side f(t, ξ) that an external integrator calls.
template <class Observer, class Samples>
void expect_allocation_free(Observer& observer, const Samples& samples) {
  int rejected = 0;
  const long count = allocations_during([&] {
    for (const auto& s : samples) rejected += observer.update(s) != adaptobs::UpdateStatus::accepted;
  });
  EXPECT_EQ(rejected, 0);
  EXPECT_EQ(count, 0);
  typename Observer::InternalState ds = observer.internal_state();
  const auto& s = samples.back();
  EXPECT_EQ(allocations_during([&] { observer.derivative(observer.internal_state(), ds, s.t, s.u, s.y); }), 0)
      << "right-hand side allocates";
}

TEST(NoAllocation, UnifiedObserversWithOtherOptionsAndRightHandSides) {
  const auto siso_samples = adaptobs::record_samples(siso::make_plant<double>(), 2000);
  const auto mimo_samples = adaptobs::record_samples(periodic::make_plant<double>(), 2000);
  auto bg = bastin_gevers_observer<double>();
  expect_allocation_free(bg, siso_samples);
  auto mt = marino_tomei_observer<double>();
  expect_allocation_free(mt, siso_samples);
  auto bes = besancon_observer<double>({.sampling = quadratic(), .excitation_window = 100});
  expect_allocation_free(bes, mimo_samples);
  auto zh = zhang_observer<double>(50.0, {.sampling = {.substeps = 3}});
  expect_allocation_free(zh, mimo_samples);
  auto kb = kalman_bucy_filter<double>(1.0);
  expect_allocation_free(kb, siso_samples);
}

}  // namespace
