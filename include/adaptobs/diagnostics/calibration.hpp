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

#include <array>
#include <cmath>
#include <limits>
#include <sstream>
#include <string_view>
#include <vector>

namespace adaptobs {

namespace detail {
/// The exponent e of the power of two \f$2^{-e}\f$ that values up to `largest`
/// are scaled by before their squares are summed: 0 (no scaling) below
/// \f$\sqrt{\text{max}}\,2^{-14}\f$ (about 8e149 in double, 1e15 in float), where
/// up to \f$2^{28}\f$ squares sum without overflow; otherwise that of `largest`,
/// which brings the values below 2. Scaling by a power of two is exact, so the
/// sums are those of the values themselves, scaled.
template <typename Scalar>
[[nodiscard]] int sum_of_squares_exponent(Scalar largest) {
  const Scalar limit = std::sqrt(std::numeric_limits<Scalar>::max()) * Scalar(0x1p-14);
  return largest > limit ? std::ilogb(largest) : 0;
}
}  // namespace detail

/// Sample covariance \f$\frac1n\sum_k v_kv_k^T\f$ of zero-mean vectors (e.g. the
/// output errors of fault-free runs), over every vector of every run. Vectors
/// with entries near the top of the range (`detail::sum_of_squares_exponent`)
/// are summed scaled by a power of two (exactly), so that only a covariance
/// itself beyond the floating-point range is refused.
template <typename Scalar, int N>
[[nodiscard]] Eigen::Matrix<Scalar, N, N> sample_covariance(
    const std::vector<std::vector<Eigen::Matrix<Scalar, N, 1>>>& runs) {
  constexpr std::string_view who = "sample_covariance";
  Index n = -1, count = 0;
  Scalar largest = 0;
  for (const auto& run : runs)
    for (const auto& v : run) {
      if (n < 0) n = v.size();
      require_finite_shape(v, n, 1, who, "runs");
      if (v.size() > 0) largest = std::max(largest, v.cwiseAbs().maxCoeff());
      ++count;
    }
  require(count >= 2, who, "runs", "must hold at least two vectors");
  const int exponent = detail::sum_of_squares_exponent(largest);
  const Scalar down = std::ldexp(Scalar(1), -exponent);
  Eigen::Matrix<Scalar, N, N> sum = Eigen::Matrix<Scalar, N, N>::Zero(n, n);
  for (const auto& run : runs)
    for (const auto& v : run) sum.noalias() += (down * v) * (down * v).transpose();
  Eigen::Matrix<Scalar, N, N> covariance = sum / static_cast<Scalar>(count);
  const Scalar up = std::ldexp(Scalar(1), exponent);
  covariance *= up;  // twice: 2^{2·exponent} itself may be beyond the doubles
  covariance *= up;
  require(covariance.allFinite(), who, "runs", "have a covariance beyond the floating-point range");
  return covariance;
}

/// What the values of fault-free runs read every `stride`-th step (steps 0,
/// stride, 2·stride, ... of each run) show: the moments the scales come from and
/// the autocorrelations the independence that a CUSUM's threshold assumes is
/// checked by (`calibrate_cusum`; the stride search of `design_fault_monitor`).
template <typename Scalar, int N>
struct StrideStatistics {
  static constexpr int max_lag = 5;    ///< autocorrelations over 1 to 5 strides
  Index stride = 1;                    ///< samples between the values read
  Eigen::Matrix<Scalar, N, 1> mean;    ///< mean deviation of a component from the reference
  Eigen::Matrix<Scalar, N, 1> square;  ///< mean square deviation of a component from the reference (may overflow)
  /// Root mean square deviation of a component from the reference: the square
  /// root of `square`, computed scaled, so finite for every finite record.
  Eigen::Matrix<Scalar, N, 1> root_mean_square;
  Index evaluations = 0;  ///< values read over all runs
  Index pairs = 0;        ///< pairs of them five strides apart within a run
  /// Largest |lag-one| (one stride) autocorrelation of a component, about its mean
  /// (NaN without pairs five strides apart).
  Scalar lag_correlation = std::numeric_limits<Scalar>::quiet_NaN();
  /// Largest departure from 1 of a component's long-run variance ratio
  /// \f$1 + 2\sum_{l=1}^{5}\rho_l\f$ (NaN without pairs five strides apart).
  Scalar long_run_excess = std::numeric_limits<Scalar>::quiet_NaN();
  /// Long-run root mean square deviation of a component from the reference,
  /// \f$\sqrt{\overline{d^2} + 2\sum_{l=1}^{5}\gamma_l}\f$ with \f$\gamma_l\f$ its autocovariance
  /// about its mean over l strides: \f$\sqrt{b^2 + \sigma^2(1 + 2\sum_l\rho_l)}\f$ for a
  /// mean b off the reference and a variance σ². A sum of n deviations varies
  /// as n times the long-run variance \f$\sigma^2(1 + 2\sum_l\rho_l)\f$, not n σ², so this
  /// is the scale under which a CUSUM's sums, far in their tail, behave as those
  /// of independent unit draws (`calibrate_cusum`). NaN without pairs five strides
  /// apart, or where the sum under the root is not positive.
  Eigen::Matrix<Scalar, N, 1> long_run_scale;
};

/// The statistics of the values of `runs` every `stride`-th step, as
/// deviations from `reference` (the nominal value, or any value near the runs':
/// it only keeps the sums of squares from cancelling). The autocorrelations are
/// about each component's mean and pooled over the runs, with pairs only within
/// a run. The values are taken as they are: a caller checks their sizes and
/// finiteness first (`calibrate_cusum` checks every value of every run).
/// Deviations near the top of the range are summed scaled by a power of two
/// (`detail::sum_of_squares_exponent`), as by `sample_covariance`: the means,
/// root mean squares and correlations of finite values are finite.
template <typename Scalar, int N>
[[nodiscard]] StrideStatistics<Scalar, N> stride_statistics(
    const std::vector<std::vector<Eigen::Matrix<Scalar, N, 1>>>& runs, const Eigen::Matrix<Scalar, N, 1>& reference,
    Index stride) {
  using Vector = Eigen::Matrix<Scalar, N, 1>;
  constexpr int max_lag = StrideStatistics<Scalar, N>::max_lag;
  require(stride >= 1, "stride_statistics", "stride", "must be at least 1");
  const Index n = reference.size();
  const auto step = static_cast<std::size_t>(stride);
  StrideStatistics<Scalar, N> result;
  result.stride = stride;
  Scalar largest = 0;
  for (const auto& run : runs)
    for (std::size_t k = 0; k < run.size(); k += step)
      if (n > 0) largest = std::max(largest, (run[k] - reference).cwiseAbs().maxCoeff());
  const int exponent = detail::sum_of_squares_exponent(largest);
  const Scalar down = std::ldexp(Scalar(1), -exponent), up = std::ldexp(Scalar(1), exponent);
  // Sums of the scaled deviations d = 2^{-e}(v - reference).
  Vector sum = Vector::Zero(n), squares = Vector::Zero(n);
  for (const auto& run : runs)
    for (std::size_t k = 0; k < run.size(); k += step) {
      sum += down * (run[k] - reference);
      squares += (down * (run[k] - reference)).cwiseAbs2();
      ++result.evaluations;
    }
  if (result.evaluations == 0) return result;
  const auto count = static_cast<Scalar>(result.evaluations);
  const Vector mean = sum / count, square = squares / count;
  result.mean = up * mean;
  result.square = up * (up * square);  // twice: 2^{2e} itself may be beyond the range
  result.root_mean_square = up * square.cwiseSqrt();
  const Vector variance = (square - mean.cwiseAbs2()).cwiseMax(std::numeric_limits<Scalar>::min());

  // Autocorrelations at 1 to 5 strides, about the mean, pooled over the runs.
  std::array<Vector, max_lag> products;
  std::array<Index, max_lag> pairs{};
  products.fill(Vector::Zero(n));
  for (const auto& run : runs)
    for (std::size_t k = 0; k < run.size(); k += step)
      for (int l = 1; l <= max_lag && k >= static_cast<std::size_t>(l) * step; ++l) {
        const std::size_t j = k - static_cast<std::size_t>(l) * step;
        products[static_cast<std::size_t>(l - 1)] +=
            (down * (run[k] - reference) - mean).cwiseProduct(down * (run[j] - reference) - mean);
        ++pairs[static_cast<std::size_t>(l - 1)];
      }
  result.pairs = pairs[max_lag - 1];
  result.long_run_scale = Vector::Constant(n, std::numeric_limits<Scalar>::quiet_NaN());
  if (result.pairs == 0) return result;
  Vector long_run = Vector::Ones(n), long_run_square = square;
  for (int l = 0; l < max_lag; ++l) {
    const Vector covariance =
        products[static_cast<std::size_t>(l)] / static_cast<Scalar>(pairs[static_cast<std::size_t>(l)]);
    const Vector rho = covariance.cwiseQuotient(variance);
    if (l == 0) result.lag_correlation = rho.cwiseAbs().maxCoeff();
    long_run += Scalar(2) * rho;
    long_run_square += Scalar(2) * covariance;
  }
  result.long_run_excess = (long_run.array() - Scalar(1)).abs().maxCoeff();
  for (Index i = 0; i < n; ++i)
    if (long_run_square(i) > 0) result.long_run_scale(i) = up * std::sqrt(long_run_square(i));
  return result;
}

/// What `calibrate_cusum` designed, and what it measured on the runs.
template <typename Scalar, int N>
struct CusumCalibration {
  /// Long-run RMS deviation from nominal of each component, at the stride
  /// (`StrideStatistics::long_run_scale`): the RMS where the values are uncorrelated.
  Eigen::Matrix<Scalar, N, 1> scale;
  Scalar drift = 0;            ///< ν, as given
  Scalar threshold = 0;        ///< h from Siegmund's approximation
  Scalar lag_correlation = 0;  ///< largest |lag-one| (one stride) autocorrelation of a component
  /// Largest departure from 1 of a component's long-run variance ratio
  /// \f$1 + 2\sum_{l=1}^{5}\rho_l\f$ (its autocorrelations over five strides).
  Scalar long_run_excess = 0;
  Scalar bias = 0;        ///< largest |mean − nominal| of a component, in RMS deviations from nominal
  Index evaluations = 0;  ///< values the sums see over all runs
  /// The check on the runs: a design for false alarms every `evaluations / 50`
  /// evaluations (so that about 50 are expected), and the alarms it raised.
  Scalar checked_mean_evaluations = 0;
  Index checked_alarms = 0;
  Index alarms = 0;  ///< alarms of the design itself on the runs
};

/// Settings of `calibrate_cusum`.
struct CusumCalibrationOptions {
  double max_lag_correlation = 0.1;   ///< refuse above this (file comment of diagnostics/cusum.hpp)
  double max_long_run_excess = 0.25;  ///< refuse when |1 + 2Σρ_l − 1| exceeds this
  double max_bias = 0.25;             ///< refuse when a component's mean is this many scales off nominal
  /// Refuse when the rate measured in the check is off its design by more than this factor.
  double rate_tolerance = 2;
};

namespace detail {
/// The alarms of a CUSUM that replays every value of every run, re-armed on
/// `nominal` at the start of each.
template <typename Scalar, int N>
[[nodiscard]] Index cusum_alarms_on_runs(const std::vector<std::vector<Eigen::Matrix<Scalar, N, 1>>>& runs,
                                         const Eigen::Matrix<Scalar, N, 1>& nominal,
                                         const Eigen::Matrix<Scalar, N, 1>& scale, Scalar drift, Scalar threshold,
                                         Index stride) {
  CusumDetector<Scalar, N> detector(nominal, scale, drift, threshold, {.stride = stride});
  for (const auto& run : runs) {
    detector.rearm(nominal);
    for (const auto& v : run) (void)detector.update(v);
  }
  return detector.alarm_count();
}
}  // namespace detail

/// The rate check of `calibrate_cusum` (and of the stride search of
/// `design_fault_monitor`): the false alarms that a CUSUM with these scales and
/// drift, designed for 50 of them on the runs (a threshold for false alarms
/// every evaluations / 50 evaluations, `cusum_threshold`), raises when it replays
/// every value of every run, re-armed on `nominal` at the start of each, reading
/// every `stride`-th. For independent normal values about 50; a count far from
/// it says the values at the stride are not.
///
/// The values are taken as they are, as by `stride_statistics`. Refuses, naming
/// 'runs', runs too short for such a design: with `evaluations` values at the
/// stride, it needs `detail::cusum_threshold_exists(drift, evaluations / 50, n)`.
template <typename Scalar, int N>
[[nodiscard]] Index cusum_rate_check(const std::vector<std::vector<Eigen::Matrix<Scalar, N, 1>>>& runs,
                                     const Eigen::Matrix<Scalar, N, 1>& nominal,
                                     const Eigen::Matrix<Scalar, N, 1>& scale, Scalar drift, Index stride) {
  constexpr std::string_view who = "cusum_rate_check";
  require(stride >= 1, who, "stride", "must be at least 1");
  Index evaluations = 0;  // values at the stride: steps 0, stride, 2·stride, ... of each run
  for (const auto& run : runs) evaluations += (static_cast<Index>(run.size()) + stride - 1) / stride;
  const auto checked = static_cast<double>(static_cast<Scalar>(evaluations) / Scalar(50));
  require(detail::cusum_threshold_exists(static_cast<double>(drift), checked, nominal.size()), who, "runs",
          "hold too few values at the stride for a design expecting 50 false alarms on them (its threshold would be "
          "below 0)");
  const auto threshold = static_cast<Scalar>(cusum_threshold(static_cast<double>(drift), checked, nominal.size()));
  return detail::cusum_alarms_on_runs(runs, nominal, scale, drift, threshold, stride);
}

namespace detail {
/// Whether `alarms` false alarms where 50 were designed are within a factor
/// `tolerance` of them (`CusumCalibrationOptions::rate_tolerance`).
[[nodiscard]] inline bool rate_within(Index alarms, double tolerance) {
  const double ratio = static_cast<double>(alarms) / 50.0;
  return ratio <= tolerance && ratio >= 1 / tolerance;
}
}  // namespace detail

/// Designs a `CusumDetector` that raises false alarms every `mean_evaluations`
/// evaluations (values fed to its sums) on average, and checks the design's
/// assumptions on the runs it was measured on.
///
/// `runs` holds fault-free sequences of the monitored value (e.g. θ̂ after
/// convergence), one per seed, each sampled at every step. The values at every
/// `stride`-th step give the scales, and the threshold comes from
/// `cusum_threshold`. That threshold holds for independent normal values. Far
/// in its tail a CUSUM's sums behave as a random walk, whose spread over n
/// steps is n times the long-run variance \f$\sigma^2(1 + 2\sum_l\rho_l)\f$ of its
/// increments: the scales are therefore the long-run RMS deviations from
/// `nominal` (`StrideStatistics::long_run_scale`, autocovariances over 1 to 5
/// strides), which absorb what correlation the checks below let through. On
/// AR(1) values with a long-run ratio of 1.22 (lag-one correlation 0.1), the
/// RMS made false alarms 1.4 to 7.6 times too frequent at 10² to 10⁶
/// evaluations between them, the more the further in the tail. The long-run
/// scale makes them a factor independent of the tail, 0.6 to 0.9 of the rate
/// designed at drifts 1 to 0.25: conservative, as the larger overshoot of
/// correlated sums over their barriers is not corrected (docs/fault_detection.md,
/// "False-alarm rates in the tail"). The routine checks the assumptions three
/// ways before returning:
/// - each component's mean stays within `max_bias` scales of `nominal`;
/// - its autocorrelations over 1 to 5 strides, about its mean, are small: the
///   lag-one below `max_lag_correlation` and the long-run variance ratio
///   \f$1 + 2\sum_l\rho_l\f$ (which sets a CUSUM's run length far in its tail)
///   within `max_long_run_excess` of 1;
/// - a design for about 50 false alarms on the runs (every evaluations/50)
///   raises between 1/`rate_tolerance` and `rate_tolerance` times that many.
///   This checks the approximation where the runs can; the design asked for,
///   usually far rarer, rests on the same approximation further in its tail.
///
/// Throws `ConfigurationError`, naming the argument to change: 'nominal' for a
/// bias, 'stride' for correlated evaluations, 'runs' for fewer than 500
/// evaluations or a failed rate check.
template <typename Scalar, int N>
[[nodiscard]] CusumCalibration<Scalar, N> calibrate_cusum(
    const std::vector<std::vector<Eigen::Matrix<Scalar, N, 1>>>& runs, const Eigen::Matrix<Scalar, N, 1>& nominal,
    Scalar drift, Scalar mean_evaluations, Index stride, CusumCalibrationOptions options = {}) {
  constexpr std::string_view who = "calibrate_cusum";
  require(nominal.size() >= 1, who, "nominal", "must have at least one component");
  require_finite(nominal, who, "nominal");
  require_positive(drift, who, "drift");
  require_positive(mean_evaluations, who, "mean_evaluations");
  require(stride >= 1, who, "stride", "must be at least 1");
  // Each limit is compared with `>`, which a NaN would silently pass.
  require_positive(options.max_lag_correlation, who, "options.max_lag_correlation");
  require_positive(options.max_long_run_excess, who, "options.max_long_run_excess");
  require_positive(options.max_bias, who, "options.max_bias");
  require(options.rate_tolerance >= 1 && std::isfinite(options.rate_tolerance), who, "options.rate_tolerance",
          "must be finite and at least 1");
  const Index n = nominal.size();
  CusumCalibration<Scalar, N> result;
  result.drift = drift;

  // Every value is checked, not only those at the stride: the replays below
  // feed them all to a detector.
  for (const auto& run : runs)
    for (const auto& v : run) require_finite_shape(v, n, 1, who, "runs");
  const StrideStatistics<Scalar, N> statistics = stride_statistics(runs, nominal, stride);
  result.evaluations = statistics.evaluations;
  require(result.evaluations >= 500, who, "runs", "must hold at least 500 values at the stride");
  const auto count = static_cast<Scalar>(result.evaluations);
  // RMS deviation from nominal over the evaluated values, for the bias (the
  // long-run scale, below, once the correlations are known to be small).
  result.scale = statistics.root_mean_square;
  require((result.scale.array() > Scalar(0)).all(), who, "runs",
          "must vary in every component (a zero scale cannot normalize)");
  result.bias = (statistics.mean.array().abs() / result.scale.array()).maxCoeff();
  if (result.bias > Scalar(options.max_bias)) {
    std::ostringstream os;
    os << "is " << result.bias << " scales from the fault-free runs' mean in some component (more than "
       << options.max_bias << "): a sum would drift toward an alarm without a fault; give the healthy value "
       << "the runs settle on";
    fail_argument(who, "nominal", os.str());
  }
  require(statistics.pairs >= 100, who, "runs",
          "must hold runs of at least six evaluations, 100 pairs five strides apart in all");
  result.lag_correlation = statistics.lag_correlation;
  result.long_run_excess = statistics.long_run_excess;
  if (result.lag_correlation > Scalar(options.max_lag_correlation) ||
      result.long_run_excess > Scalar(options.max_long_run_excess)) {
    std::ostringstream os;
    os << "is too short: values one stride apart are correlated (lag-one autocorrelation " << result.lag_correlation
       << ", limit " << options.max_lag_correlation << "; long-run variance ratio off 1 by " << result.long_run_excess
       << ", limit " << options.max_long_run_excess << "), so the threshold would not give the rate asked for";
    fail_argument(who, "stride", os.str());
  }
  // Within the limits the long-run ratio is at least 1 − max_long_run_excess;
  // a limit of 1 or more may leave a long-run variance that is not positive.
  result.scale = statistics.long_run_scale;
  require((result.scale.array() > Scalar(0)).all(), who, "stride",
          "leaves values whose long-run variance (over five strides) is not positive in some component: they "
          "alternate too regularly for a CUSUM's threshold; lower options.max_long_run_excess");

  result.checked_mean_evaluations = count / Scalar(50);
  if (!detail::cusum_threshold_exists(static_cast<double>(drift), static_cast<double>(result.checked_mean_evaluations),
                                      n)) {
    std::ostringstream os;
    os << "hold too few values at the stride (" << result.evaluations << ") for drift " << drift
       << ": a check expecting 50 false alarms on them needs a threshold below 0; give longer runs or lower the drift";
    fail_argument(who, "runs", os.str());
  }
  result.checked_alarms = cusum_rate_check(runs, nominal, result.scale, drift, stride);
  if (!detail::rate_within(result.checked_alarms, options.rate_tolerance)) {
    std::ostringstream os;
    os << "give " << result.checked_alarms << " false alarms to a design that expects 50 on them: the normalized "
       << "values are too far from independent normal draws (raise the stride)";
    fail_argument(who, "runs", os.str());
  }

  result.threshold =
      static_cast<Scalar>(cusum_threshold(static_cast<double>(drift), static_cast<double>(mean_evaluations), n));
  result.alarms = detail::cusum_alarms_on_runs(runs, nominal, result.scale, drift, result.threshold, stride);
  return result;
}

}  // namespace adaptobs
