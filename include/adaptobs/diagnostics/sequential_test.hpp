#pragma once
/// \file
/// What the sequential tests on an estimate (CUSUM, windowed GLR) share: the
/// normalization of each value by its nominal value and scale, the schedule
/// (stride, hold-off after an alarm, re-anchoring), the alarm and what it names,
/// and the rejection of non-finite values with the test unchanged.
///
/// The stride counts accepted values, not samples: a caller that skips a sample
/// (a rejected update, a lost output) shifts the phase of the evaluations
/// against the excitation by one. Feed the test after every sample, rejected or
/// not, with the estimate as it stands, to keep the phase.

#include <adaptobs/core/dimensions.hpp>
#include <adaptobs/core/snapshot.hpp>
#include <adaptobs/core/status.hpp>
#include <adaptobs/core/validation.hpp>
#include <adaptobs/diagnostics/threshold_alarm.hpp>

#include <Eigen/Core>

#include <string>
#include <string_view>

namespace adaptobs {

/// Settings of a sequential test on an estimate.
struct SequentialTestOptions {
  Index stride = 1;    ///< feed every stride-th value to the statistic (diagnostics/cusum.hpp, "Threshold")
  Index hold_off = 0;  ///< evaluations ignored after an alarm before the statistic runs again
  /// At the first evaluation after the hold-off, take the value seen as the new
  /// nominal: after a confirmed change the test then watches for the next one
  /// around the new operating point (give the estimate the hold-off to settle).
  bool reanchor = false;
};

/// Base of `CusumDetector` and `GlrDetector`, and of any other sequential test
/// on an estimate (CRTP). `Derived` provides two hooks:
/// - `Scalar evaluate(const Vector& z, Index& component, int& sign)`, which
///   updates its statistics with the normalized value
///   \f$z = (v - \bar v) / \sigma\f$ and returns the largest (with its component
///   and sign);
/// - `void clear_statistics()`.
///
/// The base does the rest: the checks, the schedule, the alarm. Such a type is a
/// `ChangeDetector` (diagnostics/change_detector.hpp), so `FaultMonitor` takes it.
template <class Derived, typename Scalar, int N>
class SequentialTest : public ThresholdAlarm<Scalar> {
 public:
  using Vector = Eigen::Matrix<Scalar, N, 1>;

  /// Takes the next value. Returns `nonfinite_input`, with the test unchanged,
  /// for a NaN or Inf in it; a value of the wrong size is a `ConfigurationError`.
  [[nodiscard]] UpdateStatus update(const Vector& value) {
    if constexpr (N == Eigen::Dynamic)
      if (value.size() != nominal_.size())
        require_shape(value, nominal_.size(), 1, std::string(name_) + "::update", "value");
    if (!detail::all_finite(value)) return UpdateStatus::nonfinite_input;
    this->clear_alarm();
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
    z_ = (value - nominal_).cwiseProduct(inverse_scale_);
    Index component = 0;
    int sign = 0;
    const Scalar largest = derived().evaluate(z_, component, sign);
    if (this->decide(largest)) {
      alarm_statistic_ = largest;
      isolated_ = component;
      direction_ = sign;
      derived().clear_statistics();
      holding_ = options_.hold_off;
      reanchor_pending_ = options_.reanchor;
    }
    return UpdateStatus::accepted;
  }

  /// Component (0-based) named by the last alarm, and the sign of its change.
  [[nodiscard]] Index isolated() const noexcept { return isolated_; }
  [[nodiscard]] int direction() const noexcept { return direction_; }
  /// The statistic that raised the last alarm.
  [[nodiscard]] Scalar alarm_statistic() const noexcept { return alarm_statistic_; }
  [[nodiscard]] const Vector& nominal() const noexcept { return nominal_; }

  /// Re-anchors on a new nominal value (after a confirmed change) and restarts
  /// the statistics, the stride and the hold-off; the alarm count and what the
  /// last alarm named are kept.
  void rearm(const Vector& nominal) {
    // The refusal's name is built only on the way to the throw: it runs in the
    // loop, after a confirmed change, and allocates nothing otherwise.
    if (nominal.size() != nominal_.size() || !detail::all_finite(nominal))
      require_finite_shape(nominal, nominal_.size(), 1, std::string(name_) + "::rearm", "nominal");
    nominal_ = nominal;
    restart();
  }

  /// Back to the state after construction: the nominal value it was built
  /// with, no alarm counted or named.
  void reset() {
    nominal_ = initial_nominal_;
    restart();
    this->clear_alarms();
    isolated_ = 0;
    direction_ = 0;
    alarm_statistic_ = 0;
  }

 protected:
  /// \param who the class's name, a string literal (kept for later messages).
  SequentialTest(std::string_view who, Vector nominal, const Vector& scale, Scalar threshold,
                 SequentialTestOptions options)
      : ThresholdAlarm<Scalar>(threshold),
        name_(who),
        nominal_(std::move(nominal)),
        initial_nominal_(nominal_),
        options_(options) {
    const Index n = nominal_.size();
    require(n >= 1, who, "nominal", "must have at least one component");
    require_finite(nominal_, who, "nominal");
    require_shape(scale, n, 1, who, "scale");
    require(((scale.array() > Scalar(0)) && scale.array().isFinite()).all(), who, "scale",
            "must be positive and finite");
    inverse_scale_ = scale.cwiseInverse();
    // A subnormal scale has no finite reciprocal: every deviation would read ∞.
    require(inverse_scale_.allFinite(), who, "scale", "must have finite reciprocals (no subnormal entries)");
    require_positive(threshold, who, "threshold");
    require(options.stride >= 1, who, "options.stride", "must be at least 1");
    require(options.hold_off >= 0, who, "options.hold_off", "must be non-negative");
    z_.setZero(n);
  }

  [[nodiscard]] Index components() const noexcept { return nominal_.size(); }

  /// The sequential test's part of a detector's `visit_state` (core/snapshot.hpp):
  /// nominal, scales and the position in stride, hold-off and re-anchoring; the
  /// options are settings.
  template <class Self, class Archive>
  static void visit_sequential_state(Self& self, Archive& archive) {
    archive.setting("stride", self.options_.stride);
    archive.setting("hold_off", self.options_.hold_off);
    archive.setting("reanchor", self.options_.reanchor);
    archive("nominal", self.nominal_);
    archive("initial_nominal", self.initial_nominal_);
    archive("inverse_scale", self.inverse_scale_);
    archive("z", self.z_);
    archive("skip", self.skip_);
    archive("holding", self.holding_);
    archive("isolated", self.isolated_);
    archive("direction", self.direction_);
    archive("alarm_statistic", self.alarm_statistic_);
    archive("reanchor_pending", self.reanchor_pending_);
    if constexpr (Archive::reading)
      require(self.skip_ >= 0 && self.skip_ < self.options_.stride && self.holding_ >= 0 &&
                  self.holding_ <= self.options_.hold_off,
              "restore", "snapshot", "holds a stride or hold-off position outside its option");
    ThresholdAlarm<Scalar>::visit_alarm_state(self, archive);
  }

 private:
  Derived& derived() { return static_cast<Derived&>(*this); }

  void restart() {
    derived().clear_statistics();
    skip_ = 0;
    holding_ = 0;
    reanchor_pending_ = false;
    this->clear_alarm();
  }

  std::string_view name_;  // the class's name, a string literal
  Vector nominal_;
  Vector initial_nominal_;  // what `reset` returns to
  Vector inverse_scale_;
  Vector z_;  // the normalized value being evaluated
  SequentialTestOptions options_;
  Index skip_ = 0;  // values still to pass over before the next evaluation
  Index holding_ = 0;
  Index isolated_ = 0;
  int direction_ = 0;
  Scalar alarm_statistic_ = 0;
  bool reanchor_pending_ = false;
};

}  // namespace adaptobs
