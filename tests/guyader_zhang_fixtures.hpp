#pragma once
// Helpers of the Guyader–Zhang tests: the satellite observer of §4, the satellite
// with a known input term (Remark 1), and a run loop recording the errors against the plant.

#include <adaptobs/core/status.hpp>
#include <adaptobs/observers/guyader_zhang.hpp>
#include <adaptobs/simulation/discrete_plant.hpp>

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

// A known input term of Remark 1 (Guyader & Zhang 2003), computed from the
// measured u_k and y_k only: f_k = [0, 1e-3 sin y¹_k, 0, 1e-4 cos(0.01k)(1 + u¹_k)].
struct Remark1KnownInput {
  template <typename S>
  Eigen::Matrix<S, 4, 1> operator()(adaptobs::Index k, const Eigen::Matrix<S, 2, 1>& u,
                                    const Eigen::Matrix<S, 2, 1>& y) const {
    return {S(0), S(1e-3) * std::sin(y(0)), S(0), S(1e-4) * std::cos(S(0.01) * S(k)) * (S(1) + u(0))};
  }
};

// The satellite of §4, noise free, driven by that term as well: x_{k+1} = A x_k + f_k + Ψ_k θ.
template <typename S = double>
auto make_plant_with_known_input() {
  auto input = [](adaptobs::Index k) { return satellite::PulseThrusts{}.template operator()<S>(k); };
  return adaptobs::DiscreteLinearPlant(satellite::model<S>(), satellite::initial_state<S>(),
                                       satellite::true_parameters<S>(), input, satellite::ThrustRegressor<S>{},
                                       adaptobs::PlantNoise<S>{}, S(satellite::sampling_period), Remark1KnownInput{});
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
