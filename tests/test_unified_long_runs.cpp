// The continuous-time observers over long runs and across gaps (Zhang 2005):
// the Kalman–Bucy filter's 1/t convergence without parameter noise, a gap of 2
// and 20 s crossed with the learned step limit, and irregular sample times
// against the regular grid. Part of test_long_runs, which the sanitizer build
// compiles with optimization (tests/CMakeLists.txt).

#include <adaptobs/baselines/kalman_bucy.hpp>
#include <adaptobs/core/matrix_exponential.hpp>
#include <adaptobs/core/validation.hpp>
#include <adaptobs/observers/bastin_gevers.hpp>
#include <adaptobs/observers/zhang_continuous.hpp>
#include <adaptobs/simulation/continuous_plant.hpp>

#include "models/periodic_mimo.hpp"
#include "models/siso_third_order.hpp"
#include "unified_fixtures.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
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

// ---------------------------------------------------------------------------
// A 6-s outage of the output (docs/readings/continuous_gaps.md): the 10-ms
// samples keep coming with u, y is absent. Over the outage the observer runs
// its time update, θ̂ stays where it was, and the errors after it are within a
// small factor of those before. Integrated instead across one interval with y
// on the straight line between the samples at its ends, Zhang's θ̂ error goes
// from 1.7e-4 to 1.33.
struct OutageErrors {
  double theta_before, theta_after, theta_ten_later, state_before, state_after;
};

template <class Observer>
OutageErrors errors_across_an_outage(Observer& observer, bool mask_the_outage) {
  auto plant = siso::make_plant<double>();
  const auto theta_error = [&] {
    return (observer.parameters() - plant.parameters()).norm() / plant.parameters().norm();
  };
  const auto state_error = [&] { return (observer.state() - plant.state()).norm() / plant.state().norm(); };
  for (; plant.time() < 100.0; plant.advance()) EXPECT_EQ(observer.update(plant.sample()), UpdateStatus::accepted);
  EXPECT_EQ(observer.update(plant.sample()), UpdateStatus::accepted);  // the observer at the plant's time
  OutageErrors e{};
  e.theta_before = theta_error();
  e.state_before = state_error();
  const Eigen::VectorXd theta_at_outage = observer.parameters();
  const adaptobs::OutputMask<typename Observer::Dims> absent =
      adaptobs::OutputMask<typename Observer::Dims>::Constant(1, false);
  for (int k = 0; k < 600; ++k) {
    plant.advance();
    if (!mask_the_outage) continue;
    auto sample = plant.sample();
    sample.y.setConstant(std::numeric_limits<double>::quiet_NaN());  // never read
    sample.midpoint.reset();
    EXPECT_EQ(observer.update(sample, absent), UpdateStatus::accepted);
  }
  if (mask_the_outage) {
    EXPECT_EQ(observer.parameters(), theta_at_outage);  // θ̂' = 0 over the outage
  }
  plant.advance();
  EXPECT_EQ(observer.update(plant.sample()), UpdateStatus::accepted);
  e.theta_after = theta_error();
  e.state_after = state_error();
  for (int k = 0; k < 10; ++k) {
    plant.advance();
    EXPECT_EQ(observer.update(plant.sample()), UpdateStatus::accepted);
  }
  e.theta_ten_later = theta_error();
  return e;
}

template <class Make>
void expect_an_outage_costs_little(Make make, const char* name) {
  auto observer = make();
  const OutageErrors masked = errors_across_an_outage(observer, true);
  EXPECT_LT(masked.theta_after, 1.1 * masked.theta_before) << name;
  EXPECT_LT(masked.theta_ten_later, 5 * masked.theta_before) << name;
  // The state is predicted open loop for 6 s: θ̃ and the model drive its error,
  // 1.5e-3 to 5e-2 of the state after the outage, against 0.35 to 1.1 across the line.
  EXPECT_LT(masked.state_after, 0.1) << name;
  ::testing::Test::RecordProperty(std::string(name) + "_theta_before", std::to_string(masked.theta_before));
  ::testing::Test::RecordProperty(std::string(name) + "_theta_after", std::to_string(masked.theta_after));
  ::testing::Test::RecordProperty(std::string(name) + "_theta_ten_later", std::to_string(masked.theta_ten_later));
  ::testing::Test::RecordProperty(std::string(name) + "_state_before", std::to_string(masked.state_before));
  ::testing::Test::RecordProperty(std::string(name) + "_state_after", std::to_string(masked.state_after));
  auto interpolating = make();
  const OutageErrors line = errors_across_an_outage(interpolating, false);
  ::testing::Test::RecordProperty(std::string(name) + "_theta_after_interpolated", std::to_string(line.theta_after));
  ::testing::Test::RecordProperty(std::string(name) + "_state_after_interpolated", std::to_string(line.state_after));
}

TEST(ContinuousOutage, ZhangRunsItsTimeUpdateAcrossSixSecondsWithoutOutput) {
  expect_an_outage_costs_little([] { return siso_zhang_observer<double>({}); }, "zhang");
  // The same 6 s as one interval on the line between its ends.
  auto interpolating = siso_zhang_observer<double>({});
  const OutageErrors line = errors_across_an_outage(interpolating, false);
  EXPECT_GT(line.theta_after, 100 * line.theta_before);
}

// Over an outage Algorithm 4 loses its output injection in the filter as well
// (Ω' = TAT⁻¹Ω + Ψ), so that η = x̃ − Ωθ̃ obeys η' = TAT⁻¹η: after 2 s without
// y, early in the run where θ̃ is large, η is e^{TAT⁻¹·2}η of its start. A filter
// left on A_o = T(A − KC)T⁻¹ would add ∫e^{TAT⁻¹(τ−s)}KC_oΩθ̃ ds. The quadratic
// reconstruction of u (the plant's input is smooth) keeps the observer's own
// integration error far below that.
TEST(ContinuousOutage, ZhangErrorCoordinateFollowsTheOpenLoopPlantAcrossAnOutage) {
  auto observer = siso_zhang_observer<double>();
  auto plant = siso::make_plant<double>();
  const auto& st = observer.algorithm().static_transform;
  const auto eta = [&] {
    const Eigen::VectorXd x_error = observer.transformed_state() - st.T() * plant.state();
    return Eigen::VectorXd(x_error - observer.omega() * (observer.parameters() - plant.parameters()));
  };
  for (; plant.time() < 5.0; plant.advance()) ASSERT_EQ(observer.update(plant.sample()), UpdateStatus::accepted);
  ASSERT_EQ(observer.update(plant.sample()), UpdateStatus::accepted);  // the observer at the plant's time
  const Eigen::VectorXd before = eta();
  const double t0 = observer.time();
  const adaptobs::OutputMask<decltype(observer)::Dims> absent(false);
  for (int k = 0; k < 200; ++k) {
    plant.advance();
    ASSERT_EQ(observer.update(plant.sample(), absent), UpdateStatus::accepted);
  }
  const Eigen::Matrix3d a = st.T() * observer.model().at(0.0).A * st.T_inverse();
  const Eigen::VectorXd expected = adaptobs::matrix_exponential(Eigen::Matrix3d(a * (observer.time() - t0))) * before;
  EXPECT_GT(before.norm(), 1e-4);
  EXPECT_LT((eta() - expected).norm(), 1e-4 * before.norm()) << (eta() - expected).norm() << " of " << before.norm();
}

TEST(ContinuousOutage, BastinGeversRunsItsTimeUpdateAcrossSixSecondsWithoutOutput) {
  expect_an_outage_costs_little([] { return bastin_gevers_observer<double>({}); }, "bastin_gevers");
}

TEST(ContinuousOutage, KalmanBucyPredictsItsCovarianceAcrossSixSecondsWithoutOutput) {
  expect_an_outage_costs_little([] { return kalman_bucy_filter<double>(1e-4, adaptobs::SamplingOptions{}); },
                                "kalman_bucy");
}

// The second output of the periodic MIMO plant lost for good, on the
// Kalman–Bucy filter: with the mask it must be the filter of the plant that has
// the first output only, C its first row and R its (0, 0) entry — the gain's
// column of the lost channel 0 and P corrected by the first alone (C̄ = DC,
// R̄ = DRD + (I − D)), although R couples the two channels.
TEST(ContinuousOutage, KalmanBucyWithAChannelLostIsTheFilterOfTheOtherChannel) {
  namespace periodic = adaptobs::examples::periodic;
  using Cov = adaptobs::AugmentedKalmanCovariances<periodic::Dims<double>>;
  Eigen::Matrix2d R;
  R << 0.5, 0.2, 0.2, 2.0;
  const Cov covariances{Cov::AugmentedMatrix::Identity(), 0.1 * Cov::AugmentedMatrix::Identity(), R};
  adaptobs::AugmentedKalmanBucyFilter both(periodic::model<double>(), Eigen::Vector4d::Zero().eval(),
                                           Eigen::Vector2d::Zero().eval(), covariances);
  using FirstOutput = adaptobs::Dimensions<double, 4, 1, 1, 2>;
  auto first_output_model = adaptobs::make_continuous_ltv_model<FirstOutput>(
      [](double t) {
        const auto s = periodic::system<double>(t);
        return adaptobs::ContinuousSystem<FirstOutput>{s.A, s.B, s.C.topRows<1>()};
      },
      [](double t) { return periodic::Regressor{}.operator()<double>(t); });
  using FirstCov = adaptobs::AugmentedKalmanCovariances<FirstOutput>;
  const FirstCov first_covariances{covariances.P0, covariances.Q, R.topLeftCorner<1, 1>()};
  adaptobs::AugmentedKalmanBucyFilter first(first_output_model, Eigen::Vector4d::Zero().eval(),
                                            Eigen::Vector2d::Zero().eval(), first_covariances);
  auto plant = periodic::make_plant<double>();
  const adaptobs::OutputMask<periodic::Dims<double>> lost_second(true, false);
  for (int k = 0; k < 500; ++k, plant.advance()) {
    auto sample = plant.sample();
    sample.midpoint.reset();
    adaptobs::ContinuousSample<FirstOutput> reduced{sample.t, sample.u, sample.y.head<1>(), {}};
    sample.y(1) = std::numeric_limits<double>::quiet_NaN();  // never read
    ASSERT_EQ(both.update(sample, lost_second), UpdateStatus::accepted) << k;
    ASSERT_EQ(first.update(reduced), UpdateStatus::accepted) << k;
  }
  EXPECT_LT((both.state() - first.state()).norm(), 1e-10 * first.state().norm());
  EXPECT_LT((both.parameters() - first.parameters()).norm(), 1e-10 * first.parameters().norm());
  EXPECT_LT((both.covariance() - first.covariance()).norm(), 1e-10 * first.covariance().norm());
  EXPECT_EQ(both.output_error()(1), 0);
  // Not a test that cannot fail: the filter of both channels ends elsewhere.
  adaptobs::AugmentedKalmanBucyFilter measured(periodic::model<double>(), Eigen::Vector4d::Zero().eval(),
                                               Eigen::Vector2d::Zero().eval(), covariances);
  auto again = periodic::make_plant<double>();
  for (int k = 0; k < 500; ++k, again.advance()) {
    auto sample = again.sample();
    sample.midpoint.reset();
    ASSERT_EQ(measured.update(sample), UpdateStatus::accepted) << k;
  }
  EXPECT_GT((measured.covariance() - first.covariance()).norm(), 1e-3 * first.covariance().norm());
}

}  // namespace
