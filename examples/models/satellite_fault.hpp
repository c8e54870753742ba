#pragma once
/// \file
/// A thruster fault on the controlled satellite of Guyader & Zhang (2003) §4, watched by a
/// `FaultMonitor` on its Guyader–Zhang observer; shared by the
/// `satellite_fault` example, the tests and the benchmarks.
///
/// The fault multiplies one thrust efficiency \f$\theta_I\f$ by \f$1 + \delta\f$ from
/// `time` on, at once or along a linear ramp of `ramp` seconds (an incipient
/// fault). The default is the tangential thruster losing 40 % of its efficiency
/// at t = 150 s: \f$\theta_2\f$ from 1.5 to 0.9.
///
/// The tests start at `monitor_from` = 100 s, once the estimates have
/// converged from the paper's initial guess (0.5, 0.5). The CUSUM and GLR see
/// \f$\hat\theta\f$ every 10 s, one period of the thrust pulses: the estimate
/// moves only while a pulse excites it, so values one period apart are nearly
/// independent (lag-one autocorrelation 0.01 on fault-free runs), as the
/// threshold's approximation requires, while values 5 s apart are not (0.5).

#include "common/fault_scenario.hpp"
#include "models/satellite.hpp"

#include <adaptobs/observers/guyader_zhang.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace adaptobs::examples::satellite {

/// The injected change of one thrust efficiency.
struct ThrusterFault {
  Index parameter = 1;          ///< 0-based index into θ (1: tangential)
  double time = 150;            ///< s, start of the change
  double relative_size = -0.4;  ///< δ: θ_I becomes (1 + δ) θ_I
  double ramp = 0;              ///< s over which the change builds up linearly (0: a step)

  /// θ at time t of a faulty run.
  [[nodiscard]] Eigen::Vector2d parameters_at(double t) const {
    const double progress = ramp > 0 ? std::clamp((t - time) / ramp, 0.0, 1.0) : (t >= time ? 1.0 : 0.0);
    Eigen::Vector2d theta = true_parameters<double>();
    theta(parameter) *= 1 + relative_size * progress;
    return theta;
  }
};

inline constexpr Index monitor_from = 1000;      ///< sample (100 s): θ̂ has converged
inline constexpr Index cusum_stride = 100;       ///< samples: one 10-s period of the thrust pulses
inline constexpr Index chi_square_window = 100;  ///< samples per χ² decision: one pulse period

/// The satellite's Guyader–Zhang observer of the `satellite` example.
inline auto make_observer() {
  return GuyaderZhangObserver(model<double>(), paper_gain<double>(), mu, initial_state_estimate<double>(),
                              initial_parameter_estimate<double>());
}

/// The scenario's simulation (common/fault_scenario.hpp), output noise 0.01 as in the paper.
struct Simulation {
  ThrusterFault fault;
  double noise = 0.01;

  template <class Visit>
  void operator()(std::uint64_t seed, bool faulty, Index steps, Visit&& visit) const {
    auto plant = make_plant<double>(noise, seed);
    auto observer = make_observer();
    for (Index k = 0; k < steps; ++k, plant.advance()) {
      if (faulty) plant.set_parameters(fault.parameters_at(static_cast<double>(k) * sampling_period));
      if (accepted(observer.update(plant.sample())) && !visit(k, observer, plant, plant.sample())) return;
    }
  }
};

using MonitorDesign = FaultMonitorDesign<double, 2, 2>;

/// The three tests designed for a mean time between false alarms of
/// `mean_time_between_false_alarms` seconds each, from fault-free runs of
/// seeds 1 to `seeds`, `seconds` long, with CUSUM drift ν = `drift` scales.
/// The stride is searched among multiples of the pulse period, and the first,
/// `cusum_stride`, decorrelates; the nominal value is the mean of θ̂ there
/// (within 0.01 scales of the true θ on seeds 1 to 20).
inline MonitorDesign design_monitor(double mean_time_between_false_alarms, double drift = 1.0, int seeds = 20,
                                    double seconds = 3100) {
  const auto steps = static_cast<Index>(std::llround(seconds / sampling_period));
  const auto record = record_fault_free<2, 2>(Simulation{}, seeds, steps, monitor_from);
  return design_fault_monitor(record, drift, mean_time_between_false_alarms / sampling_period, chi_square_window,
                              {.stride_multiple = cusum_stride});
}

/// One monitored run of `seconds` (alarms of the test `which`, times in seconds).
inline MonitoredRun monitored_run(const MonitorDesign& design, Detector which, const ThrusterFault& fault,
                                  std::uint64_t seed, bool faulty, double seconds) {
  const auto steps = static_cast<Index>(std::llround(seconds / sampling_period));
  return examples::monitored_run(Simulation{fault}, design, which, seed, faulty, steps, monitor_from, sampling_period,
                                 fault.time);
}

}  // namespace adaptobs::examples::satellite
