// The continuous-time observers over long runs and across gaps (Zhang 2005):
// the Kalman–Bucy filter's 1/t convergence without parameter noise, a gap of 2
// and 20 s crossed with the learned step limit, and irregular sample times
// against the regular grid. Part of test_long_runs, which the sanitizer build
// compiles with optimization (tests/CMakeLists.txt).

#include <adaptobs/baselines/kalman_bucy.hpp>
#include <adaptobs/core/validation.hpp>
#include <adaptobs/observers/bastin_gevers.hpp>
#include <adaptobs/observers/zhang_continuous.hpp>
#include <adaptobs/simulation/continuous_plant.hpp>

#include "models/siso_third_order.hpp"
#include "unified_fixtures.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <utility>

namespace {

using adaptobs::UpdateStatus;
using namespace adaptobs::testing::unified;

// With Q = 0 the gain dies out and θ̃ decays like 1/t only: t‖θ̃‖ stays put.
TEST(KalmanBucy, WithoutParameterNoiseConvergesOnlyLikeOneOverT) {
  auto filter = kalman_bucy_filter<double>(0.0);
  auto plant = siso::make_plant<double>();
  const Trace trace = run(filter, plant, 200.0);
  const double at100 = 100.0 * trace.theta_rel[10000], at200 = 200.0 * trace.theta_rel[20000];
  EXPECT_NEAR(at100 / at200, 1.0, 0.1) << at100 << " " << at200;
  EXPECT_GT(trace.theta_rel.back(), 1e-4);
}

// ---------------------------------------------------------------------------
// A gap between samples: 20 s of 10-ms samples, then one sample `gap` seconds
// later, held and interpolated across. The observer with the learned step limit
// (SamplingOptions::max_step = 0) must agree with one stepped eight times finer
// on every sample; one RK4 step over the gap leaves the stability region of the
// filter dynamics (errors of 1e3 after 2 s, a Kalman–Bucy P with an eigenvalue
// of −5e11 after 20 s).

template <class Make>
void expect_gap_integrated_like_a_fine_step(Make make, double gap, double tolerance) {
  auto observer = make(adaptobs::SamplingOptions{});
  auto fine = make(adaptobs::SamplingOptions{.max_step = 0.01 / 8});
  auto plant = siso::make_plant<double>();
  for (int k = 0; k < 2000; ++k) {
    ASSERT_EQ(observer.update(plant.sample()), UpdateStatus::accepted);
    ASSERT_EQ(fine.update(plant.sample()), UpdateStatus::accepted);
    plant.advance();
  }
  for (int k = 0; k < int(std::lround(gap / 0.01)); ++k) plant.advance();
  auto sample = plant.sample();
  sample.midpoint.reset();
  ASSERT_EQ(observer.update(sample), UpdateStatus::accepted);
  ASSERT_EQ(fine.update(sample), UpdateStatus::accepted);
  EXPECT_LT((observer.state() - fine.state()).norm(), tolerance * fine.state().norm());
  EXPECT_LT((observer.parameters() - fine.parameters()).norm(), tolerance * fine.parameters().norm());
}

// The gaps of 2 s and 20 s, each checked on its own.
template <class Make>
void expect_gaps_integrated_like_a_fine_step(Make make, double tolerance) {
  for (const double gap : {2.0, 20.0}) {
    SCOPED_TRACE(gap);
    expect_gap_integrated_like_a_fine_step(make, gap, tolerance);
  }
}

TEST(SampledIntegration, BastinGeversCrossesAGapWithTheLearnedStep) {
  expect_gaps_integrated_like_a_fine_step(
      [](adaptobs::SamplingOptions sampling) { return bastin_gevers_observer<double>({.sampling = sampling}); }, 1e-6);
}

TEST(SampledIntegration, ZhangCrossesAGapWithTheLearnedStep) {
  expect_gaps_integrated_like_a_fine_step(
      [](adaptobs::SamplingOptions sampling) { return siso_zhang_observer<double>({.sampling = sampling}); }, 1e-6);
}

TEST(SampledIntegration, KalmanBucyCrossesAGapWithItsCovariancePositiveDefinite) {
  expect_gaps_integrated_like_a_fine_step(
      [](adaptobs::SamplingOptions sampling) { return kalman_bucy_filter<double>(1e-4, sampling); }, 1e-6);
  // The covariance itself, after the longer gap.
  auto filter = kalman_bucy_filter<double>(1e-4, adaptobs::SamplingOptions{});
  auto plant = siso::make_plant<double>();
  for (int k = 0; k < 2000; ++k, plant.advance()) ASSERT_EQ(filter.update(plant.sample()), UpdateStatus::accepted);
  for (int k = 0; k < 2000; ++k) plant.advance();
  auto sample = plant.sample();
  sample.midpoint.reset();
  ASSERT_EQ(filter.update(sample), UpdateStatus::accepted);
  const Eigen::MatrixXd P = filter.covariance();
  EXPECT_EQ(P, P.transpose());
  EXPECT_TRUE(adaptobs::detail::cholesky_succeeds(P));
}

// A first interval that is itself a gap: the filter crosses it in steps of its
// stable step 1/‖A_e − LC_e‖_F (about 0.046 s here, baselines/kalman_bucy.hpp) and
// learns its limit from the 10-ms intervals after it. One RK4 step across the
// gap left P indefinite, and every later interval, longer still, was rejected
// until resynchronize(). Against the filter stepped at 1.25 ms throughout: after
// the gap 2.4e-4 (2 s) and 4.5e-5 (20 s) relative in θ̂, 1.2e-5 ten seconds later.
TEST(SampledIntegration, KalmanBucyWhoseFirstIntervalIsAGapAcceptsItAndEverySampleAfter) {
  for (const double gap : {2.0, 20.0}) {
    SCOPED_TRACE(gap);
    auto filter = kalman_bucy_filter<double>(1e-4, adaptobs::SamplingOptions{});
    auto fine = kalman_bucy_filter<double>(1e-4, adaptobs::SamplingOptions{.max_step = 0.01 / 8});
    auto plant = siso::make_plant<double>();
    const auto next_sample = [&] {
      auto sample = plant.sample();
      sample.midpoint.reset();
      return sample;
    };
    ASSERT_EQ(filter.update(next_sample()), UpdateStatus::accepted);
    ASSERT_EQ(fine.update(next_sample()), UpdateStatus::accepted);
    for (int k = 0; k < int(std::lround(gap / 0.01)); ++k) plant.advance();
    const auto relative_error = [&](const auto& a, const auto& b) { return (a - b).norm() / b.norm(); };
    for (int k = 0; k <= 1000; ++k, plant.advance()) {
      const auto sample = next_sample();
      ASSERT_EQ(filter.update(sample), UpdateStatus::accepted) << "k = " << k;
      ASSERT_EQ(fine.update(sample), UpdateStatus::accepted) << "k = " << k;
      if (k == 0) {
        EXPECT_LT(relative_error(filter.parameters(), fine.parameters()), 1e-3);
        EXPECT_LT(relative_error(filter.state(), fine.state()), 1e-3);
      }
    }
    EXPECT_LT(relative_error(filter.parameters(), fine.parameters()), 1e-4);
    EXPECT_LT(relative_error(filter.state(), fine.state()), 1e-4);
    const Eigen::MatrixXd P = filter.covariance();
    EXPECT_TRUE(adaptobs::detail::cholesky_succeeds(P));
  }
}

// Irregular sample times: intervals drawn from {1, 2, 3, 4} plant steps of
// 10 ms, i.e. [0.5, 2] times a nominal 20 ms, against the regular 20-ms grid.
// Both reconstruct u and y linearly between samples (no midpoint), which sets
// the floor both reach.
template <class Make>
void expect_irregular_times_converge_as_the_regular_grid(Make make, const char* name, double theta_limit) {
  const auto final_errors = [&](bool irregular) {
    auto observer = make();
    auto plant = siso::make_plant<double>();
    std::mt19937_64 generator(30);
    std::uniform_int_distribution<int> steps(1, 4);
    EXPECT_EQ(observer.update(plant.sample()), UpdateStatus::accepted);
    while (plant.time() < 100.0) {
      for (int k = irregular ? steps(generator) : 2; k > 0; --k) plant.advance();
      auto sample = plant.sample();
      sample.midpoint.reset();
      EXPECT_EQ(observer.update(sample), UpdateStatus::accepted) << name << " at t = " << plant.time();
    }
    return std::pair{(observer.parameters() - plant.parameters()).norm() / plant.parameters().norm(),
                     (observer.state() - plant.state()).norm() / plant.state().norm()};
  };
  const auto [theta_regular, state_regular] = final_errors(false);
  const auto [theta_irregular, state_irregular] = final_errors(true);
  EXPECT_LT(theta_regular, theta_limit) << name;
  EXPECT_LT(theta_irregular, theta_limit) << name;
  EXPECT_LT(theta_irregular, 10 * theta_regular) << name;
  EXPECT_LT(state_irregular, 10 * state_regular + 1e-6) << name;
  ::testing::Test::RecordProperty(std::string(name) + "_theta_regular", std::to_string(theta_regular));
  ::testing::Test::RecordProperty(std::string(name) + "_theta_irregular", std::to_string(theta_irregular));
}

TEST(SampledIntegration, IrregularSampleTimesConvergeAsTheRegularGrid) {
  const adaptobs::SamplingOptions linear{.input = adaptobs::SignalReconstruction::linear,
                                         .output = adaptobs::SignalReconstruction::linear};
  expect_irregular_times_converge_as_the_regular_grid(
      [&] { return bastin_gevers_observer<double>({.sampling = linear}); }, "bastin_gevers", 1e-3);
  // The Kalman–Bucy filter with this parameter noise is still at 3 % after 100 s, on either grid.
  expect_irregular_times_converge_as_the_regular_grid([&] { return kalman_bucy_filter<double>(1e-4, linear); },
                                                      "kalman_bucy", 0.05);
}

}  // namespace
