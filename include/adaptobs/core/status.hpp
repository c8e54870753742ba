#pragma once
/// \file
/// Outcome of one observer update.

#include <string_view>

namespace adaptobs {

/// What became of one sample given to an observer's `update`.
///
/// Anything but `accepted` means the observer is bit-for-bit as it was before
/// the call: no estimate, filter or counter moved. Only its health record
/// (core/health.hpp) notes a `nonfinite_result`, so that a run of them, an
/// observer whose estimates ran away, is told apart from one bad sample.
enum class UpdateStatus {
  accepted,               ///< the sample was used and the estimates advanced
  nonfinite_input,        ///< a NaN or Inf in the sample (u, y, a regressor or premise variable)
  nonfinite_result,       ///< the step would have produced NaN or Inf (overflow, NaN system matrix)
  nonincreasing_time,     ///< a continuous-time sample whose time is not after the previous sample's
  indefinite_covariance,  ///< the step would leave a covariance that is not positive definite
  interval_too_long,      ///< a continuous-time interval that needs more than `SamplingOptions::max_substeps` steps
};

[[nodiscard]] constexpr bool accepted(UpdateStatus s) noexcept { return s == UpdateStatus::accepted; }

[[nodiscard]] constexpr std::string_view to_string(UpdateStatus s) noexcept {
  switch (s) {
    case UpdateStatus::accepted: return "accepted";
    case UpdateStatus::nonfinite_input: return "rejected: non-finite input sample";
    case UpdateStatus::nonfinite_result: return "rejected: the step would produce non-finite estimates";
    case UpdateStatus::nonincreasing_time: return "rejected: the sample's time does not advance";
    case UpdateStatus::indefinite_covariance: return "rejected: the step would leave the covariance indefinite";
    case UpdateStatus::interval_too_long:
      return "rejected: the interval since the previous sample needs more than max_substeps integration steps";
  }
  return "unknown";
}

}  // namespace adaptobs
