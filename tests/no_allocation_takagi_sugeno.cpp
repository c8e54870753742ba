// No heap allocation inside fixed-size updates of the Takagi–Sugeno observer
// for time-varying parameters (21), with the leakage K_θ; the observer contract
// checks constant parameters (65).

#include <adaptobs/observers/takagi_sugeno.hpp>
#include <adaptobs/simulation/plant.hpp>

#include "models/wwtp.hpp"
#include "support/allocation_counter.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace {

using adaptobs::testing::allocations_during;
namespace wwtp = adaptobs::examples::wwtp;

TEST(NoAllocation, TakagiSugenoWithLeakageFixedSizeUpdates) {
  const auto samples = adaptobs::record_samples(wwtp::make_plant<double>(0.1), 5000);
  auto gains = wwtp::paper_gains<double>();
  gains.K_theta = wwtp::Vector1<double>(1e-3);
  adaptobs::TakagiSugenoObserver observer(wwtp::model<double>(), gains, wwtp::initial_state_estimate<double>(),
                                          wwtp::initial_parameter_estimate<double>());
  int rejected = 0;
  EXPECT_EQ(allocations_during([&] {
              for (const auto& s : samples) rejected += observer.update(s) != adaptobs::UpdateStatus::accepted;
            }),
            0);
  EXPECT_EQ(rejected, 0);
}

}  // namespace
