// No heap allocation inside fixed-size updates of the Guyader–Zhang observer
// and of the augmented Kalman filter.

#include <adaptobs/baselines/augmented_kalman.hpp>
#include <adaptobs/observers/guyader_zhang.hpp>

#include "models/satellite.hpp"
#include "support/allocation_counter.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace {

using adaptobs::Index;
using adaptobs::testing::allocations_during;
namespace satellite = adaptobs::examples::satellite;

// Samples are recorded beforehand so that only the updates run in the counted region.
std::vector<adaptobs::DiscreteSample<satellite::Dims<double>>> satellite_samples(Index n) {
  auto plant = satellite::make_plant<double>();
  std::vector<adaptobs::DiscreteSample<satellite::Dims<double>>> samples;
  samples.reserve(std::size_t(n));
  for (Index k = 0; k < n; ++k) {
    samples.push_back(plant.sample());
    plant.advance();
  }
  return samples;
}

template <class Observer, class Samples>
long allocations_during_updates(Observer& observer, const Samples& samples) {
  int rejected = 0;
  const long count = allocations_during([&] {
    for (const auto& s : samples) rejected += observer.update(s) != adaptobs::UpdateStatus::accepted;
  });
  EXPECT_EQ(rejected, 0);
  return count;
}

// Stores through a volatile pointer, so the compiler cannot elide the allocations.
std::vector<double>* volatile sink = nullptr;

TEST(NoAllocation, CounterSeesAllocations) {
  EXPECT_EQ(allocations_during([] {
              sink = new std::vector<double>(10);  // the vector object and its buffer
              delete sink;
            }),
            2);
}

// Eigen allocates with std::malloc, which a replaced operator new never sees.
volatile double eigen_sink = 0;

TEST(NoAllocation, CounterSeesEigensMalloc) {
  EXPECT_EQ(allocations_during([] {
              const Eigen::MatrixXd m = Eigen::MatrixXd::Constant(7, 9, 0.5);
              eigen_sink = m.sum();
            }),
            1);
}

TEST(NoAllocation, GuyaderZhangFixedSizeUpdates) {
  const auto samples = satellite_samples(10000);
  adaptobs::GuyaderZhangObserver observer(satellite::model<double>(), satellite::paper_gain<double>(), satellite::mu,
                                          satellite::initial_state_estimate<double>(),
                                          satellite::initial_parameter_estimate<double>(),
                                          {.excitation_window = 100});  // the monitor allocated its ring here
  EXPECT_EQ(allocations_during_updates(observer, samples), 0);
  EXPECT_EQ(allocations_during([&] {
              (void)observer.assumption2_norm();
              (void)observer.excitation_level();
            }),
            0)
      << "diagnostics allocate";
}

TEST(NoAllocation, AugmentedKalmanFixedSizeUpdates) {
  const auto samples = satellite_samples(10000);
  using Matrix6 = Eigen::Matrix<double, 6, 6>;
  adaptobs::AugmentedKalmanFilter filter(satellite::model<double>(), satellite::initial_state_estimate<double>(),
                                         satellite::initial_parameter_estimate<double>(),
                                         {Matrix6::Identity(), Matrix6::Identity() * 1e-10, Eigen::Matrix2d::Identity()});
  EXPECT_EQ(allocations_during_updates(filter, samples), 0);
}

}  // namespace
