// No heap allocation inside updates of the Dey–Bhasin observer and of the
// adaptation laws on their own, beyond what the observer contract runs: the
// covariance resets of a long run, and dynamic sizes, which allocate at
// construction only.

#include <adaptobs/adaptation/covariance_resetting.hpp>
#include <adaptobs/adaptation/exponential_forgetting.hpp>
#include <adaptobs/adaptation/normalized_gradient.hpp>
#include <adaptobs/adaptation/recursive_least_squares.hpp>
#include <adaptobs/observers/dey_bhasin.hpp>

#include "models/dey_bhasin.hpp"
#include "support/allocation_counter.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace {

using adaptobs::Index;
using adaptobs::testing::allocations_during;
namespace db = adaptobs::examples::dey_bhasin;

template <class Observer, class Sample>
long allocations_during_updates(Observer& observer, const std::vector<Sample>& samples) {
  int rejected = 0;
  const long count = allocations_during([&] {
    for (const auto& s : samples) rejected += observer.update(s) != adaptobs::UpdateStatus::accepted;
  });
  EXPECT_EQ(rejected, 0);
  return count;
}

std::vector<db::mimo::Observer<double>::Sample> mimo_samples(Index n) {
  auto plant = db::mimo::make_plant(db::mimo::RichInput{});
  std::vector<db::mimo::Observer<double>::Sample> samples;
  for (Index k = 0; k < n; ++k) {
    samples.push_back({plant.sample().u, plant.sample().y});
    plant.advance();
  }
  return samples;
}

TEST(NoAllocation, DeyBhasinFixedSizeUpdates) {
  const auto samples = mimo_samples(5000);
  auto observer = db::mimo::make_observer();
  EXPECT_EQ(allocations_during_updates(observer, samples), 0);
  EXPECT_GT(observer.law().reset_count(), 0);  // the reset path ran too
}

TEST(NoAllocation, DeyBhasinDynamicSizeUpdates) {
  using Dynamic = adaptobs::DeyBhasinObserver<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::Dynamic>;
  std::vector<Dynamic::Sample> samples;
  for (const auto& s : mimo_samples(2000)) samples.push_back({s.u, s.y});
  Dynamic observer(Eigen::VectorXd(db::mimo::f()), Eigen::VectorXd(db::mimo::x_hat0()),
                   Eigen::VectorXd(db::mimo::a_hat0()), Eigen::MatrixXd(db::mimo::B_hat0()),
                   {.k0 = db::mimo::k0, .kmin = db::mimo::kmin, .R = Eigen::MatrixXd::Identity(2, 2)});
  EXPECT_EQ(allocations_during_updates(observer, samples), 0);
}

// The excitation diagnostics (information and window), with masked samples too.
template <class Observer, class Sample>
long allocations_during_masked_updates(Observer& observer, const std::vector<Sample>& samples) {
  using Mask = adaptobs::OutputMask<typename Observer::Dims>;
  Mask partial = Mask::Constant(observer.sizes().ny, true);  // built before counting
  partial(1) = false;
  int rejected = 0;
  const long count = allocations_during([&] {
    for (std::size_t k = 0; k < samples.size(); ++k)
      rejected += (k % 3 == 0 ? observer.update(samples[k], partial) : observer.update(samples[k])) !=
                  adaptobs::UpdateStatus::accepted;
  });
  EXPECT_EQ(rejected, 0);
  return count;
}

TEST(NoAllocation, DeyBhasinUpdatesWithTheExcitationDiagnostics) {
  const auto samples = mimo_samples(1000);
  auto observer = db::mimo::Observer<double>(db::mimo::f(), db::mimo::x_hat0(), db::mimo::a_hat0(), db::mimo::B_hat0(),
                                             db::mimo::law_options(), {.information = true, .excitation_window = 50});
  EXPECT_EQ(allocations_during_masked_updates(observer, samples), 0);
  EXPECT_TRUE(observer.excitation_level().has_value());

  using Dynamic = adaptobs::DeyBhasinObserver<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::Dynamic>;
  std::vector<Dynamic::Sample> dynamic_samples;
  for (const auto& s : samples) dynamic_samples.push_back({s.u, s.y});
  Dynamic dynamic(Eigen::VectorXd(db::mimo::f()), Eigen::VectorXd(db::mimo::x_hat0()),
                  Eigen::VectorXd(db::mimo::a_hat0()), Eigen::MatrixXd(db::mimo::B_hat0()),
                  {.k0 = db::mimo::k0, .kmin = db::mimo::kmin, .R = Eigen::MatrixXd::Identity(2, 2)},
                  {.information = true, .excitation_window = 50});
  EXPECT_EQ(allocations_during_masked_updates(dynamic, dynamic_samples), 0);
  EXPECT_TRUE(dynamic.information_level().has_value());
}

template <class Law>
long allocations_of_law(Law& law, Index steps) {
  typename Law::Regressor phi = Law::Regressor::Zero(law.parameter_count(), law.measurement_count());
  typename Law::Measurement z = Law::Measurement::Zero(law.measurement_count());
  int failed = 0;
  const long count = allocations_during([&] {
    for (Index t = 0; t < steps; ++t) {
      phi(t % phi.rows(), t % phi.cols()) = std::sin(0.7 * double(t));
      z(t % z.size()) = std::cos(0.3 * double(t));
      failed += !law.propose(phi, z);
      law.commit();
    }
  });
  EXPECT_EQ(failed, 0);
  return count;
}

TEST(NoAllocation, AdaptationLawUpdates) {
  using Matrix = Eigen::Matrix<double, 16, 16>;
  using Weight = Eigen::Matrix2d;
  const Eigen::Matrix<double, 16, 1> p0 = Eigen::Matrix<double, 16, 1>::Zero();
  adaptobs::RecursiveLeastSquares<double, 16, 2> rls(p0, {Matrix::Identity(), Weight::Identity()});
  EXPECT_EQ(allocations_of_law(rls, 2000), 0);
  adaptobs::CovarianceResettingRls<double, 16, 2> resetting(p0, {.k0 = 10, .kmin = 1e-3, .R = Weight::Identity()});
  EXPECT_EQ(allocations_of_law(resetting, 2000), 0);
  adaptobs::ExponentialForgettingRls<double, 16, 2> forgetting(p0, {Matrix::Identity(), Weight::Identity(), 0.999});
  EXPECT_EQ(allocations_of_law(forgetting, 2000), 0);
  adaptobs::NormalizedGradient<double, 16, 2> gradient(p0, {});
  EXPECT_EQ(allocations_of_law(gradient, 2000), 0);
  adaptobs::CovarianceResettingRls<double, Eigen::Dynamic, Eigen::Dynamic> dynamic(
      Eigen::VectorXd::Zero(16), {.k0 = 10, .kmin = 1e-3, .R = Eigen::MatrixXd::Identity(2, 2)});
  EXPECT_EQ(allocations_of_law(dynamic, 2000), 0);
}

}  // namespace
