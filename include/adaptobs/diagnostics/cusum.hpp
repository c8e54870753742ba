#pragma once
/// \file
/// Two-sided CUSUM tests on the deviation of an estimate from its nominal value,
/// one per component, with the threshold set from a mean time between false alarms.
///
/// **Statistic** (Page 1954; Basseville & Nikiforov 1993, ch. 2). Each value
/// \f$v_k\f$ (typically \f$\hat\theta_k\f$) is normalized per component,
/// \f$z_{k,i} = (v_{k,i} - v^{nom}_i)/s_i\f$, and drives two one-sided sums
/// \f[ g^+_{k,i} = \max(0,\ g^+_{k-1,i} + z_{k,i} - \nu),\qquad
///     g^-_{k,i} = \max(0,\ g^-_{k-1,i} - z_{k,i} - \nu), \f]
/// where the drift ν is half the smallest shift, in units of s, worth detecting.
/// An alarm is raised when some sum exceeds the threshold h; the sums then
/// restart from zero, so that alarms form a renewal process whose mean spacing
/// is the run length the threshold was designed for.
///
/// **Isolation.** The alarm names the component whose sum exceeds h by the most
/// (`isolated()`), and its sign (`direction()`): with one sum per component, a
/// change of \f$\theta_i\f$ drives \f$g_i\f$ fastest, so the first and largest
/// crossing points at the parameter that moved. A change that moves several
/// components at once is named by the largest of them.
///
/// **Threshold.** When the \f$z_{k,i}\f$ fed to the sums are independent
/// standard normal draws, each one-sided sum's mean run length to a false
/// alarm follows Siegmund's (1985) corrected diffusion approximation
/// (`cusum_mean_run_length`), and with 2N independent sums racing the alarm
/// rate is 2N times each one's. An estimate \f$\hat\theta_k\f$ is not
/// independent from step to step: it moves in small increments. `stride`
/// feeds only every stride-th value to the sums; choose it at least the lag
/// over which the estimate decorrelates (for a periodic excitation, one period)
/// and check by `calibrate_cusum` (diagnostics/calibration.hpp), which measures
/// the scales s and that correlation on fault-free runs and refuses a stride
/// too short for the approximation.
///
/// Fixed sizes allocate nothing; every method is real-time safe.

#include <adaptobs/core/dimensions.hpp>
#include <adaptobs/core/status.hpp>
#include <adaptobs/core/validation.hpp>

#include <Eigen/Core>

#include <cmath>
#include <string_view>

namespace adaptobs {

/// Siegmund's overshoot correction \f$\rho = -\zeta(1/2)/\sqrt{2\pi} \approx 0.583\f$,
/// doubled: a standard normal sum crosses a barrier b on average 1.166 beyond it.
inline constexpr double siegmund_overshoot = 1.166;

/// Mean number of independent \f$N(\mu, 1)\f$ increments before a one-sided
/// CUSUM with drift ν > 0 exceeds h, by Siegmund's approximation (Siegmund
/// 1985; Basseville & Nikiforov 1993, ch. 5): with \f$\Delta = \mu - \nu\f$ and \f$b = h + 1.166\f$,
/// \f[ \bar L = \frac{e^{-2\Delta b} + 2\Delta b - 1}{2\Delta^2},\qquad \bar L = b^2 \text{ for } \Delta = 0. \f]
/// μ = 0 gives the mean run length to a false alarm, μ > ν the mean detection delay.
[[nodiscard]] inline double cusum_mean_run_length(double drift, double threshold, double mean = 0.0) {
  const double delta = mean - drift;
  const double b = threshold + siegmund_overshoot;
  const double x = 2 * delta * b;
  if (std::abs(x) < 1e-6) return b * b * (1 - x / 3);  // series of the formula about Δ = 0
  return (std::exp(-x) + x - 1) / (2 * delta * delta);
}

/// The threshold h at which \f$2\times\f$`components` one-sided sums, each fed
/// independent standard normal increments with drift ν, raise false alarms every
/// `mean_evaluations` increments on average (each sum then every
/// 2·components·mean_evaluations increments, `cusum_mean_run_length`).
[[nodiscard]] inline double cusum_threshold(double drift, double mean_evaluations, Index components = 1) {
  constexpr std::string_view who = "cusum_threshold";
  detail::require_positive(drift, who, "drift");
  detail::require_positive(mean_evaluations, who, "mean_evaluations");
  detail::require(components >= 1, who, "components", "must be at least 1");
  const double per_sum = mean_evaluations * 2 * static_cast<double>(components);
  // The run length at h = 0 is the least any threshold achieves.
  detail::require(per_sum > cusum_mean_run_length(drift, 0.0), who, "mean_evaluations",
                  "is shorter than the run length at threshold 0: lower the drift");
  double low = 0, high = 1;
  while (cusum_mean_run_length(drift, high) < per_sum) {
    low = high;
    high *= 2;
  }
  while (high - low > 1e-12 * high) {
    const double mid = 0.5 * (low + high);
    (cusum_mean_run_length(drift, mid) < per_sum ? low : high) = mid;
  }
  return 0.5 * (low + high);
}

/// Settings of a `CusumDetector`.
struct CusumOptions {
  Index stride = 1;    ///< feed every stride-th value to the sums (file comment, "Threshold")
  Index hold_off = 0;  ///< evaluations ignored after an alarm before the sums run again
  /// At the first evaluation after the hold-off, take the value seen as the new
  /// nominal: after a confirmed change the detector then watches for the next
  /// one around the new operating point (give the estimate the hold-off to settle).
  bool reanchor = false;
};

template <typename Scalar, int N = Eigen::Dynamic>
class CusumDetector {
 public:
  using Vector = Eigen::Matrix<Scalar, N, 1>;

  /// \param nominal healthy value \f$v^{nom}\f$; \param scale positive per-component
  /// scales s (e.g. from `calibrate_cusum`); \param drift ν > 0; \param threshold h > 0.
  CusumDetector(Vector nominal, Vector scale, Scalar drift, Scalar threshold, CusumOptions options = {})
      : nominal_(std::move(nominal)), inverse_scale_(scale.size()), drift_(drift), threshold_(threshold),
        options_(options) {
    constexpr std::string_view who = "CusumDetector";
    const Index n = nominal_.size();
    detail::require(n >= 1, who, "nominal", "must have at least one component");
    detail::require_finite(nominal_, who, "nominal");
    detail::require_shape(scale, n, 1, who, "scale");
    detail::require(((scale.array() > Scalar(0)) && scale.array().isFinite()).all(), who, "scale",
                    "must be positive and finite");
    detail::require_positive(drift, who, "drift");
    detail::require_positive(threshold, who, "threshold");
    detail::require(options.stride >= 1, who, "options.stride", "must be at least 1");
    detail::require(options.hold_off >= 0, who, "options.hold_off", "must be non-negative");
    inverse_scale_ = scale.cwiseInverse();
    upper_.setZero(n);
    lower_.setZero(n);
  }

  /// Takes the next value. Returns `nonfinite_input`, with the detector
  /// unchanged, for a NaN or Inf in it; a value of the wrong size is a
  /// `ConfigurationError` (dynamic sizes).
  [[nodiscard]] UpdateStatus update(const Vector& value) {
    if constexpr (N == Eigen::Dynamic) detail::require_shape(value, nominal_.size(), 1, "CusumDetector::update", "value");
    if (!value.allFinite()) return UpdateStatus::nonfinite_input;
    alarm_ = false;
    // Every stride-th value is evaluated: a countdown, not a division per value.
    if (skip_ > 0) {
      --skip_;
      return UpdateStatus::accepted;
    }
    skip_ = options_.stride - 1;
    if (holding_ > 0) {
      --holding_;
      return UpdateStatus::accepted;
    }
    if (reanchor_pending_) {
      nominal_ = value;
      reanchor_pending_ = false;
      return UpdateStatus::accepted;
    }
    // The sums, then their largest; which one it is matters only for an alarm,
    // and is looked up then (branches on every sum would mispredict at random).
    Scalar largest = 0;
    for (Index i = 0; i < nominal_.size(); ++i) {
      const Scalar z = (value(i) - nominal_(i)) * inverse_scale_(i);
      upper_(i) = std::max(Scalar(0), upper_(i) + z - drift_);
      lower_(i) = std::max(Scalar(0), lower_(i) - z - drift_);
      largest = std::max(largest, std::max(upper_(i), lower_(i)));
    }
    if (largest > threshold_) {
      alarm_ = true;
      ++alarms_;
      alarm_statistic_ = largest;
      for (Index i = 0; i < nominal_.size(); ++i)
        if (upper_(i) == largest || lower_(i) == largest) {
          isolated_ = i;
          direction_ = upper_(i) == largest ? 1 : -1;
          break;
        }
      upper_.setZero();
      lower_.setZero();
      holding_ = options_.hold_off;
      reanchor_pending_ = options_.reanchor;
    }
    return UpdateStatus::accepted;
  }

  /// An alarm was raised by the last accepted value.
  [[nodiscard]] bool alarm() const noexcept { return alarm_; }
  /// Component (0-based) named by the last alarm, and the sign of its change.
  [[nodiscard]] Index isolated() const noexcept { return isolated_; }
  [[nodiscard]] int direction() const noexcept { return direction_; }
  /// The sum that raised the last alarm.
  [[nodiscard]] Scalar alarm_statistic() const noexcept { return alarm_statistic_; }
  [[nodiscard]] Index alarm_count() const noexcept { return alarms_; }
  /// The sums \f$g^+_i, g^-_i\f$ after the last value (zero right after an alarm).
  [[nodiscard]] const Vector& upper() const noexcept { return upper_; }
  [[nodiscard]] const Vector& lower() const noexcept { return lower_; }
  /// \f$\max_i \max(g^+_i, g^-_i)\f$.
  [[nodiscard]] Scalar statistic() const { return std::max(upper_.maxCoeff(), lower_.maxCoeff()); }
  [[nodiscard]] Scalar threshold() const noexcept { return threshold_; }
  [[nodiscard]] const Vector& nominal() const noexcept { return nominal_; }

  /// Re-anchors on a new nominal value (after a confirmed change) and restarts
  /// the sums, the stride and the hold-off; the alarm count is kept.
  void rearm(const Vector& nominal) {
    detail::require_shape(nominal, nominal_.size(), 1, "CusumDetector::rearm", "nominal");
    detail::require_finite(nominal, "CusumDetector::rearm", "nominal");
    nominal_ = nominal;
    restart();
  }

  /// Back to the state after construction, alarm count included.
  void reset() {
    restart();
    alarms_ = 0;
  }

 private:
  void restart() {
    upper_.setZero();
    lower_.setZero();
    skip_ = 0;
    holding_ = 0;
    reanchor_pending_ = false;
    alarm_ = false;
  }

  Vector nominal_;
  Vector inverse_scale_;
  Scalar drift_;
  Scalar threshold_;
  CusumOptions options_;
  Vector upper_;
  Vector lower_;
  Index skip_ = 0;  // values still to pass over before the next evaluation
  Index holding_ = 0;
  Index alarms_ = 0;
  Index isolated_ = 0;
  int direction_ = 0;
  Scalar alarm_statistic_ = 0;
  bool alarm_ = false;
  bool reanchor_pending_ = false;
};

}  // namespace adaptobs
