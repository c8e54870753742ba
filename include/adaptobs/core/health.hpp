#pragma once
/// \file
/// Whether an observer's run is sound: a record, kept by every observer, that
/// tells an observer whose estimates ran away from one that was handed a bad
/// sample, and one whose theorem's assumption broke before either.
///
/// A rejected sample leaves an observer exactly as it was (core/status.hpp),
/// which is right for one bad sample and silent for a run gone wrong: once the
/// estimates are near the end of the floating-point range every later step
/// overflows, every update returns `nonfinite_result`, and the estimates freeze
/// at some 1e300 while a caller that does not check each status sees nothing.
/// The record turns that into a state with the step at which it began, and a
/// message that says what to do.

#include <adaptobs/core/dimensions.hpp>
#include <adaptobs/core/status.hpp>

#include <sstream>
#include <string>
#include <string_view>

namespace adaptobs {

/// The worst an observer's run has shown since construction or the last reset.
enum class Health {
  healthy,              ///< no sign of trouble
  assumption_violated,  ///< a condition of the observer's convergence theorem failed at some step
  diverged,             ///< the estimates ran away: consecutive steps overflowed
};

[[nodiscard]] constexpr std::string_view to_string(Health h) noexcept {
  switch (h) {
    case Health::healthy: return "healthy";
    case Health::assumption_violated: return "assumption violated";
    case Health::diverged: return "diverged";
  }
  return "unknown";
}

/// The condition of an observer's convergence theorem that its update checks
/// at every step, and what to do when it fails (both empty when it checks none).
struct CheckedAssumption {
  std::string_view condition;
  std::string_view remedy;
};

/// What an observer's `health()` returns: the state, the step at which the
/// run entered it, and a message that names the cause and the remedy.
struct HealthReport {
  Health state = Health::healthy;
  Index step = -1;  ///< the step at which the run entered `state` (-1 while healthy)
  std::string message;
};

/// The record behind `health()`, kept by the observers' update bases: the first
/// step at which the observer's checked assumption failed, with the worst
/// measure of it, and the first of `divergence_refusals` consecutive updates
/// refused as `nonfinite_result`.
///
/// Why consecutive refusals mean divergence: a sample whose entries are finite
/// but extreme (y = 1e300) makes one step overflow and is refused, and the next
/// sound sample is accepted; estimates near the end of the range make every
/// step overflow. A run of refusals tells them apart without a threshold on
/// the estimates, whose scale is the user's. A `nonfinite_input` (the sample's
/// own NaN or Inf) says nothing about the estimates and leaves the count as it is.
template <typename Scalar>
class HealthRecord {
 public:
  /// Consecutive `nonfinite_result` refusals after which the run is `diverged`.
  static constexpr Index divergence_refusals = 3;

  /// Notes the outcome of an update of the sample for step `step`.
  void note(UpdateStatus status, Index step) noexcept {
    if (status == UpdateStatus::accepted) {
      consecutive_refusals_ = 0;
    } else if (status == UpdateStatus::nonfinite_result) {
      if (consecutive_refusals_ == 0) streak_step_ = step;
      if (++consecutive_refusals_ == divergence_refusals && divergence_step_ < 0) divergence_step_ = streak_step_;
    }
  }

  /// Notes that the checked assumption failed at `step`, by `measure` (the
  /// quantity that must stay at most 1); the record keeps the first step and
  /// the largest measure.
  void note_assumption_violated(Index step, Scalar measure) noexcept {
    if (assumption_step_ < 0) assumption_step_ = step;
    if (measure > worst_measure_) worst_measure_ = measure;
  }

  [[nodiscard]] Health state() const noexcept {
    if (divergence_step_ >= 0) return Health::diverged;
    if (assumption_step_ >= 0) return Health::assumption_violated;
    return Health::healthy;
  }
  /// Largest measure of the checked assumption's failure (0 while it held).
  [[nodiscard]] Scalar worst_measure() const noexcept { return worst_measure_; }

  /// The report, worded with the observer's `assumption` (e.g. "assumption 2
  /// (eq. (3)), ||sqrt(mu_k) C_k Upsilon_k|| <= 1") and `remedy` for it.
  [[nodiscard]] HealthReport report(std::string_view assumption, std::string_view remedy) const {
    HealthReport r{state(), -1, std::string(to_string(state()))};
    std::ostringstream os;
    os.precision(3);
    if (assumption_step_ >= 0) {
      os << assumption << " failed at step " << assumption_step_ << " (up to " << worst_measure_
         << " > 1 since): " << remedy;
      r.step = assumption_step_;
    }
    if (divergence_step_ >= 0) {
      if (assumption_step_ >= 0) os << "; then ";
      os << "the estimates ran away: from step " << divergence_step_ << " on, " << divergence_refusals
         << " or more updates in a row were refused because the step overflows. reset() the observer; a smaller "
            "adaptation gain, normalized regressors or a richer input keep it from recurring (docs/tuning.md)";
      r.step = divergence_step_;
    }
    if (r.state != Health::healthy) r.message = std::string(to_string(r.state)) + ": " + os.str();
    return r;
  }

  /// Back to healthy (an observer's `reset`).
  void clear() noexcept { *this = HealthRecord(); }

  /// Its fields for an observer's `visit_state` (core/snapshot.hpp).
  template <class Self, class Archive>
  static void visit_state(Self& self, Archive& archive) {
    archive("assumption_step", self.assumption_step_);
    archive("worst_measure", self.worst_measure_);
    archive("divergence_step", self.divergence_step_);
    archive("streak_step", self.streak_step_);
    archive("consecutive_refusals", self.consecutive_refusals_);
  }

 private:
  Index assumption_step_ = -1;
  Scalar worst_measure_ = Scalar(0);
  Index divergence_step_ = -1;
  Index streak_step_ = -1;
  Index consecutive_refusals_ = 0;
};

}  // namespace adaptobs
