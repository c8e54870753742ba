#pragma once
// Helpers of the Guyader–Zhang tests: the satellite observer of §4 and a run
// loop recording the errors against the plant.

#include <adaptobs/core/status.hpp>
#include <adaptobs/observers/guyader_zhang.hpp>

#include "models/satellite.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace adaptobs::testing::guyader_zhang {

namespace satellite = adaptobs::examples::satellite;

template <typename S>
auto make_satellite_observer(adaptobs::GuyaderZhangOptions options = {}) {
  return adaptobs::GuyaderZhangObserver(satellite::model<S>(), satellite::paper_gain<S>(), S(satellite::mu),
                                        satellite::initial_state_estimate<S>(),
                                        satellite::initial_parameter_estimate<S>(), options);
}

struct ErrorHistory {
  std::vector<double> state;      // ‖x̂_k − x_k‖
  std::vector<double> parameter;  // ‖θ̂_k − θ‖
  std::vector<double> combined;   // ‖[x̃_k; θ̃_k]‖
};

// Runs observer and plant side by side for `steps` samples.
template <class Observer, class Plant>
ErrorHistory run(Observer& observer, Plant& plant, adaptobs::Index steps) {
  ErrorHistory h;
  for (adaptobs::Index k = 0; k < steps; ++k) {
    const double ex = static_cast<double>((observer.state() - plant.state()).norm());
    const double et = static_cast<double>((observer.parameters() - plant.parameters()).norm());
    h.state.push_back(ex);
    h.parameter.push_back(et);
    h.combined.push_back(std::hypot(ex, et));
    EXPECT_EQ(observer.update(plant.sample()), adaptobs::UpdateStatus::accepted) << "step " << k;
    plant.advance();
  }
  return h;
}

}  // namespace adaptobs::testing::guyader_zhang
