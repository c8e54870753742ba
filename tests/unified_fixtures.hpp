#pragma once
// Helpers of the continuous-time observer tests: the examples' designs, a run
// loop recording the relative errors, and fitted decay rates.

#include "models/unified_designs.hpp"

#include <adaptobs/core/status.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

namespace adaptobs::testing::unified {

namespace siso = adaptobs::examples::siso;
namespace periodic = adaptobs::examples::periodic;
using adaptobs::examples::designs::quadratic;

// The examples' designs, compiled once in the library adaptobs_example_designs.
using adaptobs::examples::designs::bastin_gevers_observer;
using adaptobs::examples::designs::bastin_gevers_transform;
using adaptobs::examples::designs::besancon_observer;
using adaptobs::examples::designs::besancon_transform;
using adaptobs::examples::designs::kalman_bucy_filter;
using adaptobs::examples::designs::marino_tomei_observer;
using adaptobs::examples::designs::marino_tomei_transform;
using adaptobs::examples::designs::PeriodicModel;
using adaptobs::examples::designs::siso_zhang_observer;
using adaptobs::examples::designs::SisoModel;
using adaptobs::examples::designs::spr_report;
using adaptobs::examples::designs::zhang_observer;

/// Errors at every sample of a run.
struct Trace {
  std::vector<double> t, theta_rel, state_error, state_norm;

  /// max |η̂ − η| over the last tenth of the run, relative to max |η| there.
  [[nodiscard]] double state_rel_last_tenth() const {
    const double from = 0.9 * t.back();
    double error = 0, norm = 0;
    for (std::size_t i = 0; i < t.size(); ++i) {
      if (t[i] < from) continue;
      error = std::max(error, state_error[i]);
      norm = std::max(norm, state_norm[i]);
    }
    return error / norm;
  }

  /// Exponential rate (1/s) of the envelope of ‖θ̃‖/‖θ‖: least-squares slope of
  /// the log of its maximum over windows of `window` s from `from` on, while
  /// the envelope stays above the sampling floor (1e-7).
  [[nodiscard]] double theta_decay_rate(double from, double window) const {
    std::vector<double> centers, logs;
    for (double start = from; start + window <= t.back(); start += window) {
      double envelope = 0;
      for (std::size_t i = 0; i < t.size(); ++i)
        if (t[i] >= start && t[i] < start + window) envelope = std::max(envelope, theta_rel[i]);
      if (envelope < 1e-7) break;
      centers.push_back(start + window / 2);
      logs.push_back(std::log(envelope));
    }
    EXPECT_GE(centers.size(), 2u) << "too few windows above the floor to fit a rate";
    if (centers.size() < 2) return 0;
    double n = double(centers.size()), sx = 0, sy = 0, sxx = 0, sxy = 0;
    for (std::size_t i = 0; i < centers.size(); ++i) {
      sx += centers[i];
      sy += logs[i];
      sxx += centers[i] * centers[i];
      sxy += centers[i] * logs[i];
    }
    return -(n * sxy - sx * sy) / (n * sxx - sx * sx);
  }
};

struct NoHook {
  void operator()(double, double) const {}
};

/// Feeds `duration` seconds of the plant's samples to the observer;
/// `after_update(t_{k−1}, t_k)` runs after each accepted step.
template <class Observer, class Plant, class Hook = NoHook>
Trace run(Observer& observer, Plant& plant, double duration, Hook after_update = {}) {
  Trace trace;
  const auto record = [&] {
    trace.t.push_back(plant.time());
    trace.theta_rel.push_back(double((observer.parameters() - plant.parameters()).norm() / plant.parameters().norm()));
    trace.state_error.push_back(double((observer.state() - plant.state()).norm()));
    trace.state_norm.push_back(double(plant.state().norm()));
  };
  EXPECT_EQ(observer.update(plant.sample()), UpdateStatus::accepted);
  record();
  const double period = [&] {
    auto copy = plant;
    copy.advance();
    return copy.time() - plant.time();
  }();
  const long steps = std::lround(duration / period);
  for (long k = 0; k < steps; ++k) {
    const double t0 = plant.time();
    plant.advance();
    const UpdateStatus status = observer.update(plant.sample());
    EXPECT_EQ(status, UpdateStatus::accepted) << "at t = " << plant.time();
    if (status != UpdateStatus::accepted) break;
    after_update(t0, plant.time());
    record();
  }
  return trace;
}

}  // namespace adaptobs::testing::unified
