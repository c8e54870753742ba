// Theorem 2 of Guyader & Zhang (Guyader & Zhang 2003) on the satellite of §4: with
// bounded noises the errors stay bounded and stationary over 10⁵ steps, and
// with zero-mean noise they are zero-mean over 200 seeds. Part of
// test_long_runs, which the sanitizer build compiles with optimization
// (tests/CMakeLists.txt).

#include <adaptobs/simulation/discrete_plant.hpp>

#include "guyader_zhang_fixtures.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace {

using adaptobs::Index;
using adaptobs::UpdateStatus;
using namespace adaptobs::testing::guyader_zhang;

// Theorem 2: with bounded noises, the errors stay bounded over 10⁵ steps.
TEST(GuyaderZhang, Theorem2BoundedErrorsOverLongRun) {
  adaptobs::PlantNoise<double> noise;
  noise.distribution = adaptobs::PlantNoise<double>::Distribution::uniform;
  noise.output = 0.01;
  noise.state = 1e-4;
  noise.seed = 7;
  auto observer = make_satellite_observer<double>();
  auto plant = adaptobs::DiscreteLinearPlant(
      satellite::model<double>(), satellite::initial_state<double>(), satellite::true_parameters<double>(),
      [](Index k) { return satellite::PulseThrusts{}.operator()<double>(k); }, satellite::ThrustRegressor<double>{},
      noise, satellite::sampling_period);
  const ErrorHistory h = run(observer, plant, 100000);
  double early = 0, late = 0;
  for (Index k = 10000; k < 50000; ++k) early = std::max(early, h.combined[size_t(k)]);
  for (Index k = 50000; k < 100000; ++k) late = std::max(late, h.combined[size_t(k)]);
  const auto rms = [&](Index from, Index to) {
    double sum = 0;
    for (Index k = from; k < to; ++k) sum += h.combined[size_t(k)] * h.combined[size_t(k)];
    return std::sqrt(sum / double(to - from));
  };
  // Bounded and stationary: the error's RMS level is the same (±10%) over four
  // quarters of the run, and its envelope does not grow.
  const double first = rms(10000, 32500);
  for (const Index from : {32500, 55000, 77500}) EXPECT_NEAR(rms(from, from + 22500) / first, 1.0, 0.1) << from;
  EXPECT_LT(early, 1.0);
  EXPECT_LT(late, 1.25 * early) << "the error envelope grows: not bounded";
}

// Theorem 2: with zero-mean noise the errors converge to zero in the mean.
// Over 200 seeds the mean final error of each component is within three
// standard errors of zero (and the errors are small, so the test has power).
TEST(GuyaderZhang, Theorem2ErrorsAreZeroMeanOverSeeds) {
  constexpr int seeds = 200;
  constexpr Index steps = 3000;
  Eigen::Matrix<double, 6, seeds> finals;
  for (int s = 0; s < seeds; ++s) {
    adaptobs::PlantNoise<double> noise;
    noise.distribution = adaptobs::PlantNoise<double>::Distribution::uniform;
    noise.output = 0.01;
    noise.seed = 1000 + std::uint64_t(s);
    auto observer = make_satellite_observer<double>();
    auto plant = adaptobs::DiscreteLinearPlant(
        satellite::model<double>(), satellite::initial_state<double>(), satellite::true_parameters<double>(),
        [](Index k) { return satellite::PulseThrusts{}.operator()<double>(k); }, satellite::ThrustRegressor<double>{},
        noise, satellite::sampling_period);
    for (Index k = 0; k < steps; ++k) {
      ASSERT_EQ(observer.update(plant.sample()), UpdateStatus::accepted);
      plant.advance();
    }
    finals.col(s) << observer.state() - plant.state(), observer.parameters() - plant.parameters();
  }
  const Eigen::Matrix<double, 6, 1> mean = finals.rowwise().mean();
  const Eigen::Matrix<double, 6, 1> sd =
      ((finals.colwise() - mean).array().square().rowwise().sum() / (seeds - 1)).sqrt();
  const Eigen::Matrix<double, 6, 1> standard_error = sd / std::sqrt(double(seeds));
  for (int i = 0; i < 6; ++i) {
    EXPECT_LE(std::abs(mean(i)), 3 * standard_error(i))
        << "component " << i << ": mean " << mean(i) << ", SE " << standard_error(i);
    EXPECT_LT(sd(i), 0.1) << "component " << i;
  }
}

}  // namespace
