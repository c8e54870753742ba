// Choosing μ for the Guyader–Zhang observer (design/guyader_zhang_tuning.hpp)
// and what its health() reports, on the DC motor of the tutorial
// (examples/models/dc_motor.hpp).

#include <adaptobs/core/snapshot.hpp>
#include <adaptobs/design/dare.hpp>
#include <adaptobs/design/guyader_zhang_tuning.hpp>
#include <adaptobs/observers/guyader_zhang.hpp>

#include "models/dc_motor.hpp"
#include "support/eigen_testing.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <sstream>
#include <string>
#include <vector>

namespace {

namespace motor = adaptobs::examples::dc_motor;
using adaptobs::Health;
using adaptobs::Index;
using adaptobs::UpdateStatus;

struct MotorCase {
  motor::SampledMotor plant{motor::Motor{}};
  adaptobs::DiscreteLtiModel<motor::Dims> model = plant.model();
  Eigen::Matrix2d K =
      adaptobs::steady_state_kalman_gain(plant.A, Eigen::Matrix2d::Identity(), Eigen::Matrix2d::Identity() * 1e-4,
                                         Eigen::Matrix2d(Eigen::Vector2d(1e-4, 0.25).asDiagonal()))
          .K;

  [[nodiscard]] adaptobs::GuyaderZhangObserver<adaptobs::DiscreteLtiModel<motor::Dims>> observer(double mu) const {
    return {model, K, mu, Eigen::Vector2d::Zero(), Eigen::Vector2d::Zero()};
  }
};

// The tutorial's reckless step size: θ̂ overshoots from the fourth step on and
// overflows about 150 steps later; health() names both, in order, with the remedy.
TEST(GuyaderZhangHealth, DcMotorAtMuOneThousandthReportsTheBrokenAssumptionThenTheDivergence) {
  const MotorCase c;
  const motor::Run run = motor::Scenario{}.simulate(c.plant, 1.0, 1);
  auto observer = c.observer(1e-3);
  Index refused = 0;
  for (const auto& s : run.samples) refused += observer.update(s) == UpdateStatus::nonfinite_result;
  const adaptobs::HealthReport health = observer.health();
  EXPECT_EQ(health.state, Health::diverged) << health.message;
  EXPECT_GT(refused, 800);                  // every update after the overflow
  EXPECT_EQ(health.step, observer.step());  // accepted steps stop where the divergence began
  EXPECT_EQ(health.message.rfind("diverged: assumption 2", 0), 0u) << health.message;
  EXPECT_NE(health.message.find("divide mu"), std::string::npos) << health.message;
  EXPECT_NE(health.message.find("ran away"), std::string::npos) << health.message;
  EXPECT_NE(health.message.find("from step " + std::to_string(observer.step())), std::string::npos) << health.message;
  // The worst measure it reports is that of μ = 1e-3 over the regressors of the accepted steps.
  std::vector<Eigen::Matrix2d> accepted = motor::regressors_of(run);
  accepted.resize(static_cast<std::size_t>(observer.step()));
  std::ostringstream worst;
  worst.precision(3);
  worst << "(up to " << std::sqrt(1e-3 / adaptobs::guyader_zhang_mu_bound(c.model, c.K, accepted)) << " > 1";
  EXPECT_NE(health.message.find(worst.str()), std::string::npos) << worst.str() << " in " << health.message;
  EXPECT_NE(health.message.find("failed at step 4 "), std::string::npos) << health.message;

  // The record survives a snapshot, and a reset clears it.
  auto copy = c.observer(1e-3);
  adaptobs::restore(copy, adaptobs::snapshot(observer));
  EXPECT_EQ(copy.health().message, health.message);
  copy.reset(Eigen::Vector2d::Zero(), Eigen::Vector2d::Zero());
  EXPECT_EQ(copy.health().state, Health::healthy);
  EXPECT_EQ(copy.health().message, "healthy");
}

// The bound is exact: Υ does not depend on μ, so at 0.99 of it assumption 2
// holds at every step of the same regressors, and at 1.01 it fails (without
// divergence: θ̃ expands only past √2).
TEST(GuyaderZhangTuning, TheMuBoundIsWhereAssumptionTwoStartsToFail) {
  const MotorCase c;
  const motor::Run run = motor::Scenario{}.simulate(c.plant, 2.0, 2);
  const double bound = adaptobs::guyader_zhang_mu_bound(c.model, c.K, motor::regressors_of(run));
  EXPECT_NEAR(bound, 4.3e-6, 0.1e-6);
  for (const double factor : {0.99, 1.01}) {
    auto observer = c.observer(factor * bound);
    double largest = 0;
    for (const auto& s : run.samples) {
      ASSERT_EQ(observer.update(s), UpdateStatus::accepted);
      largest = std::max(largest, observer.assumption2_norm());
    }
    EXPECT_NEAR(largest * largest, factor, 1e-9 * factor);
    EXPECT_EQ(observer.health().state, factor < 1 ? Health::healthy : Health::assumption_violated)
        << observer.health().message;
  }
}

// The predicted rate is that of the observer itself: without noise, θ̃ shrinks
// by ρ per step once η has decayed, at the fastest μ (where averaging is still
// about right) and at half the bound (where averaging predicts a time constant
// some 500 times too short).
TEST(GuyaderZhangTuning, ThePredictedRateIsTheObserversOwn) {
  const MotorCase c;
  motor::Scenario noise_free;
  noise_free.current_noise = noise_free.speed_noise = 0;
  const motor::Run run = noise_free.simulate(c.plant, 6.0, 3);
  const std::vector<Eigen::Matrix2d> regressors = motor::regressors_of(run);
  const auto fastest = adaptobs::guyader_zhang_fastest_mu(c.model, c.K, regressors);
  const auto slow = adaptobs::guyader_zhang_convergence(
      c.model, c.K, regressors, 0.5 * adaptobs::guyader_zhang_mu_bound(c.model, c.K, regressors));
  EXPECT_NEAR(fastest.time_constant, 239, 10);  // steps
  EXPECT_FALSE(slow.averaging_holds);
  EXPECT_GT(slow.time_constant, 400 * slow.averaged_time_constant);
  for (const auto& prediction : {fastest, slow}) {
    auto observer = c.observer(prediction.mu);
    std::vector<double> error;
    for (std::size_t k = 0; k < run.samples.size(); ++k) {
      ASSERT_EQ(observer.update(run.samples[k]), UpdateStatus::accepted);
      error.push_back((observer.parameters() - run.parameters[k]).norm());
    }
    // Over whole periods of the square wave (500 steps), from 1 s on.
    const std::size_t from = 1000, to = prediction.time_constant < 1000 ? 3000 : 6000;
    const double measured_decay = std::log(error[to - 1] / error[from - 1]) / double(to - from);
    EXPECT_NEAR(measured_decay, std::log(prediction.rate), 0.15 * std::abs(std::log(prediction.rate)))
        << "mu = " << prediction.mu;
  }
}

TEST(GuyaderZhangTuning, RefusalsNameTheArgument) {
  const MotorCase c;
  const std::vector<Eigen::Matrix2d> none;
  const std::vector<Eigen::Matrix2d> zero(10, Eigen::Matrix2d::Zero());
  EXPECT_EQ(adaptobs::testing::configuration_error_of([&] {
              (void)adaptobs::guyader_zhang_mu_bound(c.model, c.K, none);
            }).rfind("guyader_zhang_mu_bound: argument 'regressors'", 0),
            0u);
  EXPECT_NE(adaptobs::testing::configuration_error_of([&] {
              (void)adaptobs::guyader_zhang_mu_bound(c.model, c.K, zero);
            }).find("never reach the output"),
            std::string::npos);
  EXPECT_EQ(adaptobs::testing::configuration_error_of([&] {
              (void)adaptobs::guyader_zhang_convergence(c.model, c.K, zero, -1.0);
            }).rfind("guyader_zhang_convergence: argument 'mu'", 0),
            0u);
}

}  // namespace
