#pragma once
/// \file
/// Detector design from fault-free runs: the scales and threshold of a
/// `CusumDetector`, checked against the runs, and the output-error covariance of
/// a `ChiSquareTest`.
///
/// No observer in the library comes with an exact distribution of its
/// estimates: their gains are not the small ones of the averaging theory, their
/// excitation is not stationary, and several of them are not fed Gaussian
/// noise. The scale that is right for every observer is therefore the one
/// measured on the user's own model, without a fault: simulate (or record) a few
/// fault-free runs after the estimates have converged, pass the monitored values
/// here, and the design either meets the false-alarm rate asked for on those
/// runs or says why it cannot.

#include <adaptobs/core/dimensions.hpp>
#include <adaptobs/core/validation.hpp>
#include <adaptobs/diagnostics/cusum.hpp>

#include <Eigen/Core>

#include <cmath>
#include <limits>
#include <sstream>
#include <string_view>
#include <vector>

namespace adaptobs {

/// Sample covariance \f$\frac1n\sum_k v_kv_k^T\f$ of zero-mean vectors (e.g. the
/// output errors of fault-free runs), over every vector of every run.
template <typename Scalar, int N>
[[nodiscard]] Eigen::Matrix<Scalar, N, N> sample_covariance(const std::vector<std::vector<Eigen::Matrix<Scalar, N, 1>>>& runs) {
  constexpr std::string_view who = "sample_covariance";
  Index n = -1, count = 0;
  Eigen::Matrix<Scalar, N, N> sum;
  for (const auto& run : runs)
    for (const auto& v : run) {
      if (n < 0) {
        n = v.size();
        sum.setZero(n, n);
      }
      detail::require_shape(v, n, 1, who, "runs");
      detail::require_finite(v, who, "runs");
      sum.noalias() += v * v.transpose();
      ++count;
    }
  detail::require(count >= 2, who, "runs", "must hold at least two vectors");
  return sum / static_cast<Scalar>(count);
}

/// What `calibrate_cusum` designed, and what it measured on the runs.
template <typename Scalar, int N>
struct CusumCalibration {
  Eigen::Matrix<Scalar, N, 1> scale;  ///< RMS deviation from nominal of each component, at the stride
  Scalar drift = 0;                   ///< ν, as given
  Scalar threshold = 0;               ///< h from Siegmund's approximation
  Scalar lag_correlation = 0;         ///< largest lag-one (one stride) autocorrelation of a normalized component
  Index evaluations = 0;              ///< values the sums would see over all runs
  Index alarms = 0;                   ///< alarms the detector raises on the runs
  /// Evaluations per false alarm on the runs (infinite without alarms).
  Scalar measured_mean_evaluations = std::numeric_limits<Scalar>::infinity();
};

/// Settings of `calibrate_cusum`.
struct CusumCalibrationOptions {
  double max_lag_correlation = 0.2;  ///< refuse above this (file comment of diagnostics/cusum.hpp)
  /// Check the rate on the runs when they hold at least this many expected alarms.
  double min_expected_alarms_to_check = 20;
  /// Refuse when the measured rate is off the design by more than this factor.
  double rate_tolerance = 2;
};

/// Designs a `CusumDetector` that raises false alarms every `mean_evaluations`
/// evaluations (values fed to its sums) on average.
///
/// `runs` holds fault-free sequences of the monitored value (e.g. θ̂ after
/// convergence), one per seed, each sampled at every step. The value at every
/// `stride`-th step gives the scales (RMS deviation from `nominal`) and the
/// lag-one autocorrelation of the normalized values; the threshold comes from
/// `cusum_threshold`. Then a detector with that design is run on the runs and
/// its alarms counted.
///
/// Throws `ConfigurationError`, naming the argument to change:
/// - 'stride', when successive evaluations are correlated beyond
///   `max_lag_correlation`: the approximation assumes independent values;
/// - 'runs', when they hold fewer than 100 evaluations, or when they hold
///   enough to check and the measured rate is off the design by more than
///   `rate_tolerance` (the values are far from normal, or the stride too short).
template <typename Scalar, int N>
[[nodiscard]] CusumCalibration<Scalar, N> calibrate_cusum(const std::vector<std::vector<Eigen::Matrix<Scalar, N, 1>>>& runs,
                                                          const Eigen::Matrix<Scalar, N, 1>& nominal, Scalar drift,
                                                          Scalar mean_evaluations, Index stride,
                                                          CusumCalibrationOptions options = {}) {
  constexpr std::string_view who = "calibrate_cusum";
  using Vector = Eigen::Matrix<Scalar, N, 1>;
  detail::require_finite(nominal, who, "nominal");
  detail::require(stride >= 1, who, "stride", "must be at least 1");
  const Index n = nominal.size();
  CusumCalibration<Scalar, N> result;
  result.drift = drift;

  // Scales: RMS deviation from nominal over the evaluated values.
  Vector squares = Vector::Zero(n);
  for (const auto& run : runs)
    for (std::size_t k = 0; k < run.size(); k += static_cast<std::size_t>(stride)) {
      detail::require_shape(run[k], n, 1, who, "runs");
      detail::require_finite(run[k], who, "runs");
      squares += (run[k] - nominal).cwiseAbs2();
      ++result.evaluations;
    }
  detail::require(result.evaluations >= 100, who, "runs", "must hold at least 100 values at the stride");
  result.scale = (squares / static_cast<Scalar>(result.evaluations)).cwiseSqrt();
  detail::require((result.scale.array() > Scalar(0)).all(), who, "runs",
                  "must vary in every component (a zero scale cannot normalize)");

  // Lag-one autocorrelation of each normalized component, pooled over the runs.
  Vector products = Vector::Zero(n), pairs_squares = Vector::Zero(n);
  for (const auto& run : runs)
    for (std::size_t k = static_cast<std::size_t>(stride); k < run.size(); k += static_cast<std::size_t>(stride)) {
      const Vector a = run[k] - nominal, b = run[k - static_cast<std::size_t>(stride)] - nominal;
      products += a.cwiseProduct(b);
      pairs_squares += Scalar(0.5) * (a.cwiseAbs2() + b.cwiseAbs2());
    }
  result.lag_correlation = (products.array() / pairs_squares.array().max(std::numeric_limits<Scalar>::min())).abs().maxCoeff();
  if (result.lag_correlation > Scalar(options.max_lag_correlation)) {
    std::ostringstream os;
    os << "is too short: values one stride apart are correlated (lag-one autocorrelation " << result.lag_correlation
       << " > " << options.max_lag_correlation << "), so the threshold would not give the rate asked for";
    detail::fail_argument(who, "stride", os.str());
  }

  result.threshold = static_cast<Scalar>(
      cusum_threshold(static_cast<double>(drift), static_cast<double>(mean_evaluations), n));

  // The promise, checked on the runs themselves.
  CusumDetector<Scalar, N> detector(nominal, result.scale, drift, result.threshold, {.stride = stride});
  for (const auto& run : runs) {
    detector.rearm(nominal);
    for (const auto& v : run) (void)detector.update(v);
  }
  result.alarms = detector.alarm_count();
  if (result.alarms > 0)
    result.measured_mean_evaluations = static_cast<Scalar>(result.evaluations) / static_cast<Scalar>(result.alarms);
  const double expected = static_cast<double>(result.evaluations) / static_cast<double>(mean_evaluations);
  if (expected >= options.min_expected_alarms_to_check) {
    const double ratio = static_cast<double>(result.alarms) / expected;
    if (!(ratio <= options.rate_tolerance && ratio >= 1 / options.rate_tolerance)) {
      std::ostringstream os;
      os << "give " << result.alarms << " false alarms where the design expects " << expected
         << ": the normalized values are too far from independent normal draws (raise the stride)";
      detail::fail_argument(who, "runs", os.str());
    }
  }
  return result;
}

}  // namespace adaptobs
