#pragma once
/// \file
/// A fault of the waste water treatment plant of Srinivasarengan et al. (2018) §6: the growth
/// parameter θ steps from 0 to 0.15 at sample 400 (or ramps there), watched by a
/// `FaultMonitor` on the Takagi–Sugeno observer with the printed gains; shared
/// by the `wwtp_fault` example and the tests.
///
/// The paper's simulation is noise-free; here the measured biomass carries
/// Gaussian noise of standard deviation 0.01 (about 0.25 % of its level), so
/// that the estimates wander and the alarms have a false-alarm rate to design.
/// Monitoring starts at sample 300, once θ̂ has converged from θ̂₀ = 0. The
/// CUSUM and GLR see θ̂ once per period of the dilution rate (100 samples), over which
/// it decorrelates (lag-one autocorrelation 0.01 on fault-free runs, 0.10 at
/// 50 samples).

#include "common/fault_scenario.hpp"
#include "models/wwtp.hpp"

#include <adaptobs/observers/takagi_sugeno.hpp>

#include <algorithm>
#include <cstdint>
#include <random>

namespace adaptobs::examples::wwtp {

/// The injected change of θ.
struct GrowthFault {
  Index step = 400;    ///< sample at which the change starts
  double size = 0.15;  ///< θ after the change (from 0)
  Index ramp = 0;      ///< samples over which it builds up linearly (0: a step)

  [[nodiscard]] double theta_at(Index k) const {
    if (ramp > 0) return size * std::clamp(static_cast<double>(k - step) / static_cast<double>(ramp), 0.0, 1.0);
    return k >= step ? size : 0.0;
  }
};

inline constexpr Index monitor_from = 300;       ///< θ̂ has converged
inline constexpr Index cusum_stride = 100;       ///< one period of the dilution rate
inline constexpr Index chi_square_window = 100;  ///< samples per χ² decision
inline constexpr double output_noise = 0.01;     ///< std of the biomass measurement noise

/// The scenario's simulation (common/fault_scenario.hpp).
struct Simulation {
  GrowthFault fault;
  double noise = output_noise;

  template <class Visit>
  void operator()(std::uint64_t seed, bool faulty, Index steps, Visit&& visit) const {
    const GrowthFault f = fault;
    auto plant = make_discrete_nonlinear_plant<Dims<double>>(
        [](const Eigen::Vector2d& x, const Vector1<double>& u, const Vector1<double>& th) {
          return transition<double>(x, u, th);
        },
        output_matrix<double>(), initial_state<double>(), [](Index k) { return Vector1<double>(DilutionRate{}(k)); },
        [f, faulty](Index k) { return Vector1<double>(faulty ? f.theta_at(k) : 0.0); }, sampling_period);
    TakagiSugenoObserver observer(model<double>(), paper_gains<double>(), initial_state_estimate<double>(),
                                  initial_parameter_estimate<double>());
    std::mt19937_64 rng(seed);
    std::normal_distribution<double> measurement_noise(0.0, noise);
    for (Index k = 0; k < steps; ++k, plant.advance()) {
      auto sample = plant.sample();
      sample.y(0) += measurement_noise(rng);
      if (accepted(observer.update(sample)) && !visit(k, observer, plant, sample)) return;
    }
  }
};

using MonitorDesign = FaultMonitorDesign<double, 1, 1>;

/// The three tests designed for false alarms every `mean_samples_between_false_alarms`
/// samples each, from fault-free runs of seeds 1 to `seeds`, `steps` long. The
/// stride is searched among multiples of the dilution period, and the first,
/// `cusum_stride`, decorrelates; the nominal value is the mean of θ̂ there.
inline MonitorDesign design_monitor(double mean_samples_between_false_alarms, double drift = 1.0, int seeds = 20,
                                    Index steps = 10300) {
  const auto record = record_fault_free<1, 1>(Simulation{}, seeds, steps, monitor_from);
  return design_fault_monitor(record, drift, mean_samples_between_false_alarms, chi_square_window,
                              {.stride_multiple = cusum_stride});
}

inline MonitoredRun monitored_run(const MonitorDesign& design, Detector which, const GrowthFault& fault,
                                  std::uint64_t seed, bool faulty, Index steps) {
  return examples::monitored_run(Simulation{fault}, design, which, seed, faulty, steps, monitor_from, sampling_period,
                                 static_cast<double>(fault.step));
}

}  // namespace adaptobs::examples::wwtp
