// No heap allocation inside fixed-size updates: the global allocation
// functions are replaced by counting ones for this executable.

#include <adaptobs/baselines/augmented_kalman.hpp>
#include <adaptobs/observers/guyader_zhang.hpp>

#include "models/satellite.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <new>
#include <vector>

namespace {
std::atomic<long> allocations{0};
}  // namespace

void* operator new(std::size_t size) {
  ++allocations;
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}
void* operator new[](std::size_t size) { return ::operator new(size); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }

namespace {

using adaptobs::Index;
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
  const long before = allocations.load();
  int rejected = 0;
  for (const auto& s : samples) rejected += observer.update(s) != adaptobs::UpdateStatus::accepted;
  const long after = allocations.load();
  EXPECT_EQ(rejected, 0);
  return after - before;
}

TEST(NoAllocation, CounterSeesAllocations) {
  const long before = allocations.load();
  auto* p = new std::vector<double>(10);
  delete p;
  EXPECT_GE(allocations.load() - before, 2);
}

TEST(NoAllocation, GuyaderZhangFixedSizeUpdates) {
  const auto samples = satellite_samples(10000);
  adaptobs::GuyaderZhangObserver observer(satellite::model<double>(), satellite::paper_gain<double>(), satellite::mu,
                                          satellite::initial_state_estimate<double>(),
                                          satellite::initial_parameter_estimate<double>(),
                                          {.excitation_window = 100});  // the monitor allocated its ring here
  EXPECT_EQ(allocations_during_updates(observer, samples), 0);
  (void)observer.assumption2_norm();
  const long before = allocations.load();
  (void)observer.assumption2_norm();
  (void)observer.excitation_level();
  EXPECT_EQ(allocations.load() - before, 0) << "diagnostics allocate";
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
