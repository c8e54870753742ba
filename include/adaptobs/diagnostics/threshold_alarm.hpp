#pragma once
/// \file
/// The alarm bookkeeping of a test that compares a statistic with a threshold,
/// kept once for the chi-square test and the sequential tests (CUSUM, GLR).

#include <adaptobs/core/dimensions.hpp>

namespace adaptobs {

/// Base of a threshold test, not used on its own: its threshold h, whether the
/// last value taken raised an alarm, and how many alarms were raised.
template <typename Scalar>
class ThresholdAlarm {
 public:
  /// The last value taken raised an alarm (a windowed test: it completed a window that did).
  [[nodiscard]] bool alarm() const noexcept { return alarm_; }
  /// Alarms raised since construction or the last reset.
  [[nodiscard]] Index alarm_count() const noexcept { return alarms_; }
  [[nodiscard]] Scalar threshold() const noexcept { return threshold_; }

 protected:
  explicit ThresholdAlarm(Scalar threshold = 0) : threshold_(threshold) {}

  /// Raises, and counts, an alarm when `statistic` exceeds the threshold; returns whether it did.
  bool decide(Scalar statistic) noexcept {
    alarm_ = statistic > threshold_;
    if (alarm_) ++alarms_;
    return alarm_;
  }
  /// No alarm for the value being taken (until `decide` says otherwise).
  void clear_alarm() noexcept { alarm_ = false; }

  /// The alarm's part of a detector's `visit_state` (core/snapshot.hpp).
  template <class Self, class Archive>
  static void visit_alarm_state(Self& self, Archive& archive) {
    archive("threshold", self.threshold_);
    archive("alarms", self.alarms_);
    archive("alarm", self.alarm_);
  }

  /// No alarm, and none counted.
  void clear_alarms() noexcept {
    alarm_ = false;
    alarms_ = 0;
  }

  Scalar threshold_;

 private:
  Index alarms_ = 0;
  bool alarm_ = false;
};

}  // namespace adaptobs
