// How a continuous-time observer steps between samples (core/sampled_integration.hpp):
// the number of RK4 steps per interval, the learned step limit, and the bound on
// the work of one update. The test system ẋ = −λx (λ = 50) makes the steps
// visible in the result: n equal RK4 steps over an interval T give x·R(−λT/n)ⁿ
// with R(z) = 1 + z + z²/2 + z³/6 + z⁴/24.
#include <adaptobs/core/sampled_integration.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace {

using adaptobs::SampledIntegrator;
using adaptobs::SamplingOptions;
using adaptobs::UpdateStatus;
using DecayDims = adaptobs::Dimensions<double, 1, 1, 1, 1>;
using State = Eigen::Matrix<double, 1, 1>;
using Sample = adaptobs::ContinuousSample<DecayDims>;

Sample at(double t) { return Sample{t, DecayDims::Input::Zero(), DecayDims::Output::Zero()}; }

constexpr double lambda = 50;

double rk4_decay(double interval, int steps) {
  const double z = -lambda * interval / steps;
  return std::pow(1 + z + z * z / 2 + z * z * z / 6 + z * z * z * z / 24, steps);
}

struct Decay {
  int* evaluations;
  void operator()(const State& x, State& dxdt, double, const DecayDims::Input&, const DecayDims::Output&) const {
    ++*evaluations;
    dxdt = -lambda * x;
  }
};

class SampledIntegration : public ::testing::Test {
 protected:
  // Integrates to `t`; returns the status and records the RK4 steps taken.
  UpdateStatus advance_to(double t) {
    evaluations = 0;
    const State before = x;
    const UpdateStatus status = integrator.advance(at(t), x, Decay{&evaluations}, "test");
    steps = evaluations / 4;
    if (status == UpdateStatus::accepted && steps > 0) {
      const double expected = rk4_decay(t - integrator_time_before, steps);
      EXPECT_NEAR(x(0) / before(0), expected, 1e-12 * expected);
    }
    integrator_time_before = integrator.time();
    return status;
  }
  void make(SamplingOptions options) {
    integrator = SampledIntegrator<DecayDims, State>(State::Zero(), adaptobs::Sizes{1, 1, 1, 1}, options, "test");
  }

  SampledIntegrator<DecayDims, State> integrator{State::Zero(), adaptobs::Sizes{1, 1, 1, 1},
                                                 SamplingOptions{.substeps = 2}, "test"};
  State x = State::Constant(1.0);
  int evaluations = 0, steps = 0;
  double integrator_time_before = 0;
};

TEST_F(SampledIntegration, LearnsItsStepLimitFromTheFirstInterval) {
  ASSERT_EQ(advance_to(0.0), UpdateStatus::accepted);  // the time origin: nothing integrated
  EXPECT_EQ(steps, 0);
  EXPECT_EQ(integrator.max_step(), 0.0);
  ASSERT_EQ(advance_to(0.01), UpdateStatus::accepted);
  EXPECT_EQ(steps, 2);
  EXPECT_DOUBLE_EQ(integrator.max_step(), 1.25 * 0.005);
  // Jitter below 25% keeps the configured two steps.
  ASSERT_EQ(advance_to(0.0224), UpdateStatus::accepted);
  EXPECT_EQ(steps, 2);
  // A gap of 0.098 is cut into ⌈0.098 / 0.00625⌉ = 16 steps, 0.1006 into 17.
  ASSERT_EQ(advance_to(0.1204), UpdateStatus::accepted);
  EXPECT_EQ(steps, 16);
  ASSERT_EQ(advance_to(0.221), UpdateStatus::accepted);
  EXPECT_EQ(steps, 17);
}

TEST_F(SampledIntegration, AnExplicitStepLimitBoundsEveryInterval) {
  make({.substeps = 1, .max_step = 0.004});
  ASSERT_EQ(advance_to(1.0), UpdateStatus::accepted);
  ASSERT_EQ(advance_to(1.01), UpdateStatus::accepted);
  EXPECT_EQ(steps, 3);
  ASSERT_EQ(advance_to(1.012), UpdateStatus::accepted);
  EXPECT_EQ(steps, 1);
  EXPECT_EQ(integrator.max_step(), 0.004);
}

TEST_F(SampledIntegration, AnIntervalBeyondTheStepBudgetIsRejectedUntilResynchronized) {
  make({.substeps = 1, .max_substeps = 50});
  ASSERT_EQ(advance_to(0.0), UpdateStatus::accepted);
  ASSERT_EQ(advance_to(0.01), UpdateStatus::accepted);  // learns 0.0125
  ASSERT_EQ(advance_to(0.6), UpdateStatus::accepted);   // ⌈0.59 / 0.0125⌉ = 48 steps: within budget
  EXPECT_EQ(steps, 48);
  const State before = x;
  EXPECT_EQ(advance_to(1.3), UpdateStatus::interval_too_long);  // 56 steps
  EXPECT_EQ(evaluations, 0);
  EXPECT_EQ(x, before);
  EXPECT_EQ(integrator.time(), 0.6);
  // Resynchronized, the next sample is a new time origin, and the interval
  // after it sets the step limit anew.
  integrator.resynchronize();
  EXPECT_EQ(integrator.max_step(), 0.0);
  ASSERT_EQ(advance_to(1.3), UpdateStatus::accepted);
  EXPECT_EQ(steps, 0);
  EXPECT_EQ(x, before);
  ASSERT_EQ(advance_to(1.31), UpdateStatus::accepted);
  EXPECT_EQ(steps, 1);
  EXPECT_NEAR(integrator.max_step(), 1.25 * 0.01, 1e-15);
  ASSERT_EQ(advance_to(1.35), UpdateStatus::accepted);  // ⌈0.04 / 0.0125⌉
  EXPECT_EQ(steps, 4);
  // restart() forgets the limit as well: the next first interval sets it anew.
  integrator.restart();
  EXPECT_EQ(integrator.max_step(), 0.0);
}

// A repeated time stamp made the first interval 1e-9: every later 10-ms
// interval needed 8e6 steps and was rejected, and resynchronizing kept the
// limit, so the observer never moved again.
TEST_F(SampledIntegration, ALimitLearnedFromATinyFirstIntervalIsLearnedAgainAfterResynchronizing) {
  make({.substeps = 1});
  ASSERT_EQ(advance_to(0.0), UpdateStatus::accepted);
  ASSERT_EQ(advance_to(1e-9), UpdateStatus::accepted);
  EXPECT_EQ(advance_to(0.01), UpdateStatus::interval_too_long);
  integrator.resynchronize();
  ASSERT_EQ(advance_to(0.01), UpdateStatus::accepted);  // the new origin
  for (int k = 2; k <= 5; ++k) {
    ASSERT_EQ(advance_to(0.01 * k), UpdateStatus::accepted) << k;
    EXPECT_EQ(steps, 1);
  }
  EXPECT_NEAR(integrator.max_step(), 1.25 * 0.01, 1e-15);
}

// An observer that bounds its own step (the Kalman–Bucy filter): while no limit
// is known, a first interval whose `substeps` steps would be longer than the
// bound is crossed in steps of the bound and teaches nothing; the limit is
// learned from the first interval that fits. Here the bound is 0.02 (λh = 1).
TEST_F(SampledIntegration, AFirstIntervalLongerThanTheStableStepIsCutAndTeachesNothing) {
  make({.substeps = 2});
  int bound_calls = 0;
  const auto stable_step = [&](const State&, double, const DecayDims::Input&, const DecayDims::Output&) {
    ++bound_calls;
    return 0.02;
  };
  const auto advance_with_bound = [&](double t) {
    const State before = x;
    const double t0 = integrator.time();
    evaluations = 0;
    const UpdateStatus status = integrator.advance(
        at(t), x, Decay{&evaluations}, "test", [](State&) { return UpdateStatus::accepted; }, stable_step);
    steps = evaluations / 4;
    if (steps > 0) {
      EXPECT_NEAR(x(0) / before(0), rk4_decay(t - t0, steps), 1e-12 * rk4_decay(t - t0, steps));
    }
    return status;
  };
  ASSERT_EQ(advance_with_bound(0.0), UpdateStatus::accepted);
  EXPECT_EQ(bound_calls, 0);  // the time origin: nothing integrated
  // A 3-s gap first: ⌈3 / 0.02⌉ = 150 steps, where two would multiply x by R(−75)² ≈ 1.6e12.
  ASSERT_EQ(advance_with_bound(3.0), UpdateStatus::accepted);
  EXPECT_EQ(steps, 150);
  EXPECT_EQ(integrator.max_step(), 0.0);
  EXPECT_LT(x(0), 1e-60);
  x(0) = 1;
  // The 10-ms interval after it is the first to fit: two steps, and the limit 1.25 × 0.005.
  ASSERT_EQ(advance_with_bound(3.01), UpdateStatus::accepted);
  EXPECT_EQ(steps, 2);
  EXPECT_NEAR(integrator.max_step(), 1.25 * 0.005, 1e-15);
  EXPECT_EQ(bound_calls, 2);
  // From then on the learned limit bounds the steps, and the bound is not asked again.
  ASSERT_EQ(advance_with_bound(3.1), UpdateStatus::accepted);  // ⌈0.09 / 0.00625⌉ steps
  EXPECT_EQ(steps, 15);
  EXPECT_EQ(bound_calls, 2);
}

TEST_F(SampledIntegration, AValidatorCanRejectTheStepAndNothingIsCommitted) {
  ASSERT_EQ(advance_to(0.0), UpdateStatus::accepted);
  const State before = x;
  int evaluations_seen = 0;
  const UpdateStatus status = integrator.advance(at(0.01), x, Decay{&evaluations_seen}, "test", [](State& candidate) {
    candidate.setZero();
    return UpdateStatus::indefinite_covariance;
  });
  EXPECT_EQ(status, UpdateStatus::indefinite_covariance);
  EXPECT_EQ(evaluations_seen, 8);
  EXPECT_EQ(x, before);
  EXPECT_EQ(integrator.time(), 0.0);
  EXPECT_EQ(integrator.max_step(), 0.0);  // a rejected first interval teaches nothing
}

// In float, max_substeps = INT_MAX rounds up to 2^31: an interval that needs
// 2^31 steps passed the bound, and int(2^31) is undefined (on x86 INT_MIN: no
// step at all, and the sample was accepted with the state where it was).
TEST(SampledIntegrationInFloat, AStepCountBeyondIntIsRejectedAsTooLong) {
  using Dims = adaptobs::Dimensions<float, 1, 1, 1, 1>;
  using FloatState = Eigen::Matrix<float, 1, 1>;
  const auto at_time = [](float t) {
    return adaptobs::ContinuousSample<Dims>{t, Dims::Input::Zero(), Dims::Output::Zero()};
  };
  SampledIntegrator<Dims, FloatState> integrator(FloatState::Zero(), adaptobs::Sizes{1, 1, 1, 1},
                                                 {.max_step = 1e-3, .max_substeps = std::numeric_limits<int>::max()},
                                                 "test");
  FloatState x = FloatState::Constant(1.0f);
  int evaluations = 0;
  const auto decay = [&](const FloatState& s, FloatState& ds, float, const Dims::Input&, const Dims::Output&) {
    ++evaluations;
    ds = -2.0f * s;
  };
  ASSERT_EQ(integrator.advance(at_time(0.0f), x, decay, "test"), UpdateStatus::accepted);
  // ⌈2147483.648 / 0.001⌉ in float is 2^31 = INT_MAX + 1.
  ASSERT_EQ(std::ceil(2147483.648f / float(1e-3)), 2147483648.0f);
  EXPECT_EQ(integrator.advance(at_time(2147483.648f), x, decay, "test"), UpdateStatus::interval_too_long);
  EXPECT_EQ(evaluations, 0);
  EXPECT_EQ(x(0), 1.0f);
  EXPECT_EQ(integrator.time(), 0.0f);
  // An interval within the budget is integrated: ⌈0.01 / 0.001⌉ = 10 steps of RK4.
  ASSERT_EQ(integrator.advance(at_time(0.01f), x, decay, "test"), UpdateStatus::accepted);
  EXPECT_EQ(evaluations, 40);
  EXPECT_NEAR(x(0), std::exp(-0.02f), 1e-6f);
}

TEST_F(SampledIntegration, BadStepOptionsNameTheArgument) {
  const auto message = [](SamplingOptions options) -> std::string {
    try {
      SampledIntegrator<DecayDims, State>(State::Zero(), adaptobs::Sizes{1, 1, 1, 1}, options, "test");
    } catch (const adaptobs::ConfigurationError& e) {
      return e.what();
    }
    return "<no exception>";
  };
  EXPECT_NE(message({.max_step = -1.0}).find("'options.max_step'"), std::string::npos);
  EXPECT_NE(message({.max_step = std::nan("")}).find("'options.max_step'"), std::string::npos);
  EXPECT_NE(message({.substeps = 4, .max_substeps = 3}).find("'options.max_substeps'"), std::string::npos);
}

}  // namespace
