#pragma once
/// \file
/// What a change detector is (the `ChangeDetector` concept): a test that takes
/// one vector per step and says whether it raised an alarm, as the CUSUM
/// (cusum.hpp), the GLR (glr.hpp) and the χ² test (chi_square_test.hpp) do.
/// `FaultMonitor` (fault_monitor.hpp) drives any three such detectors.

#include <adaptobs/core/dimensions.hpp>
#include <adaptobs/core/status.hpp>

#include <concepts>

namespace adaptobs {

/// A detector of changes in a stream of `Vector`s:
/// - `update(v)` takes the next vector and returns an `UpdateStatus`; one it
///   does not accept (`accepted(status)` false) leaves the detector unchanged;
/// - `alarm()` says whether the last vector taken raised an alarm;
/// - `alarm_count()` counts the alarms raised so far.
template <class D, class Vector>
concept ChangeDetector = requires(D& d, const D& cd, const Vector& v) {
  { d.update(v) } -> std::same_as<UpdateStatus>;
  { cd.alarm() } -> std::convertible_to<bool>;
  { cd.alarm_count() } -> std::convertible_to<Index>;
};

}  // namespace adaptobs
