#pragma once
/// \file
/// What the discrete-time observers over a model (Guyader–Zhang, Guiro,
/// Takagi–Sugeno) and the augmented Kalman filter share, written once: the base
/// class their `update`, `reset` and common accessors come from. The
/// Dey–Bhasin observer, a filter bank with an adaptation law, has its own.

#include <adaptobs/core/detail/update_workspace.hpp>
#include <adaptobs/core/dimensions.hpp>
#include <adaptobs/core/discrete_model.hpp>
#include <adaptobs/core/health.hpp>
#include <adaptobs/core/status.hpp>
#include <adaptobs/core/validation.hpp>

#include <string_view>
#include <type_traits>

namespace adaptobs {

namespace detail {
/// The name `reset` gives the initial state in errors: the paper's letter
/// when the observer's declaration names one, else "x0".
constexpr std::string_view initial_state_name() { return "x0"; }
constexpr std::string_view initial_state_name(std::string_view paper_letter) { return paper_letter; }
}  // namespace detail

/// The declarations an observer deriving from `DiscreteUpdate` makes, written
/// once: the friendship the base needs to reach its private members (`model_`,
/// `theta_`, `work_`, `restart` and `advance`); the names its errors give
/// (`Observer::update`, `Observer::reset`, and the initial state's, by default
/// "x0"); and the common types. A class template does not see the members of a
/// dependent base without qualification, so each observer would otherwise
/// restate them (Eigen's `EIGEN_DENSE_PUBLIC_INTERFACE` answers the same
/// problem). Use it in a public section of a class template whose model
/// parameter is named `Model`:
/// `ADAPTOBS_DISCRETE_UPDATE_INTERFACE(GuyaderZhangObserver, DiscreteSample);`
/// or, naming the initial state as the paper does,
/// `ADAPTOBS_DISCRETE_UPDATE_INTERFACE(GuiroObserver, DiscreteSample, "z0");`
/// (outside namespace adaptobs, qualify the sample: `adaptobs::DiscreteSample`).
#define ADAPTOBS_DISCRETE_UPDATE_INTERFACE(Observer, SampleOf, ...)                                           \
  friend ::adaptobs::DiscreteUpdate<Observer, typename Model::Dims, SampleOf>;                                \
  static constexpr std::string_view name_update = #Observer "::update";                                       \
  static constexpr std::string_view name_reset = #Observer "::reset";                                         \
  static constexpr std::string_view name_initial_state = ::adaptobs::detail::initial_state_name(__VA_ARGS__); \
  using Dims = typename Model::Dims;                                                                          \
  using typename Dims::Scalar, typename Dims::State, typename Dims::Parameters, typename Dims::Output;        \
  using Sample = SampleOf<Dims>

/// Base of a discrete-time observer with a model (CRTP), not used on its own:
/// `update(sample)`, its masked form, `reset` and the accessors every discrete
/// observer has, with the run-time size checks of the sample and the mask.
/// The observer supplies, each under this name (the base reaches them through
/// the friendship the macro above declares; there is no optional hook and no
/// alternative form):
/// - `model_` and `theta_`, its model and parameter estimate;
/// - `Observer::name_update`, `Observer::name_reset` and
///   `Observer::name_initial_state`, the names its errors give (the macro
///   declares them);
/// - `restart(x0, theta0)`, the rest of `reset`;
/// - `checked_assumption`, a `CheckedAssumption` naming the condition of its
///   theorem that its `advance` checks (reporting failures to `health_`), and
///   the remedy; empty for an observer that checks none;
/// - `work_`, a `detail::UpdateWorkspace` of the step's scratch
///   (core/detail/update_workspace.hpp: built on the stack for each step with
///   fixed sizes, kept and sized at construction otherwise, so that no step
///   allocates);
/// - the step `advance(sample, mask, workspace) -> UpdateStatus`, which the
///   base calls with a sample of the right shape whose measured entries are
///   finite (mask null: every channel present) and with `work_`'s workspace.
///   On accepting the sample it writes the base's `output_error_` (sized by the
///   observer's constructor); a rejected step changes nothing. The base counts
///   the accepted steps.
template <class Observer, StateSpace Dims, template <StateSpace> class SampleOf>
class DiscreteUpdate : public Dims {
 public:
  using Sample = SampleOf<Dims>;

  /// One step of the observer's law with the sample (its `advance` cites the
  /// equations). Returns `UpdateStatus::accepted`, or the
  /// reason the sample was rejected (`nonfinite_input` for a NaN/Inf in it,
  /// `nonfinite_result` when the step would produce one, ...); a rejected step
  /// leaves the observer exactly as it was. With run-time sizes, a sample of
  /// the wrong shape throws `ConfigurationError` naming it, before anything is
  /// read; so does, whatever the sizes, a known input term `sample.f` with
  /// neither nx entries nor none.
  [[nodiscard]] UpdateStatus update(const Sample& sample) { return checked_step(sample, nullptr); }

  /// The same with only the output channels in `present` measured (the
  /// observer's file comment, "Missing and partial outputs"); absent entries of
  /// `sample.y` are ignored (they may be NaN or Inf). All channels present is
  /// `update(sample)`, bit for bit; none is the time update alone.
  [[nodiscard]] UpdateStatus update(const Sample& sample, const OutputMask<Dims>& present) {
    return checked_step(sample, detail::partial_mask<Dims>(present, sizes().ny, Observer::name_update));
  }

  /// Whether the run is sound (core/health.hpp): `diverged` from the step at
  /// which consecutive updates began to overflow, `assumption_violated` from
  /// the first step at which the checked assumption of the observer's theorem
  /// failed, with a message naming the cause and the remedy.
  [[nodiscard]] HealthReport health() const {
    return health_.report(Observer::checked_assumption.condition, Observer::checked_assumption.remedy);
  }

  /// Run-time sizes (nx, nu, ny, np).
  [[nodiscard]] Sizes sizes() const noexcept { return self().model_.sizes(); }
  /// Parameter estimate \f$\hat\theta_k\f$.
  [[nodiscard]] const typename Dims::Parameters& parameters() const noexcept { return self().theta_; }
  /// Output error of the last accepted update, absent channels zero (0 before
  /// the first): the error the observer corrects its estimates with (its class
  /// comment gives the formula), which fault detectors test
  /// (diagnostics/chi_square_test.hpp).
  [[nodiscard]] const typename Dims::Output& output_error() const noexcept { return output_error_; }
  /// Number k of accepted samples since construction or the last reset.
  [[nodiscard]] Index step() const noexcept { return step_; }
  [[nodiscard]] const auto& model() const noexcept { return self().model_; }

  /// Restarts from the initial estimates at step `start_step`, as after
  /// construction with the current gains (the observer's `restart` clears its
  /// own memory: filtered regressors, covariance, diagnostics).
  void reset(const typename Dims::State& x0, const typename Dims::Parameters& theta0, Index start_step = 0) {
    constexpr std::string_view who = Observer::name_reset;
    const Sizes s = sizes();
    require_initial_estimates(x0, s.nx, theta0, s.np, who, Observer::name_initial_state);
    require(start_step >= 0, who, "start_step", "must be non-negative");
    self().restart(x0, theta0);
    output_error_.setZero();
    health_.clear();
    step_ = start_step;
  }

 protected:
  /// The output error of the last accepted step, sized and written by the observer.
  typename Dims::Output output_error_;
  /// The record behind `health()`; the base notes every outcome, the observer
  /// the failures of its checked assumption.
  HealthRecord<typename Dims::Scalar> health_;

  /// The base's part of an observer's `visit_state` (core/snapshot.hpp): the
  /// step counter, the last output error and the health record.
  template <class Self, class Archive>
  static void visit_update_state(Self& self, Archive& archive) {
    archive("step", self.step_);
    archive("output_error", self.output_error_);
    archive.object("health", self.health_);
  }

  /// Checks the matrices the model gives for the current step against its
  /// sizes, before the step reads them: with run-time sizes a time-varying
  /// model can return anything, and a wrong size would be read out of bounds.
  /// Throws `ConfigurationError` naming `model.at(k)`, with nothing changed.
  /// Free for fixed sizes or a time-invariant model (checked at construction).
  /// (`DiscreteLtvModel` checks its own; a model of the user's may not.)
  template <class System>
  void check_system_sizes(const System& system) const {
    using Model = std::remove_cvref_t<decltype(self().model_)>;
    if constexpr (!Dims::is_fixed && !Model::time_invariant)
      if (!is_time_invariant(self().model_))
        require_system_sizes(system, sizes(), Observer::name_update, "model.at(k)");
  }

 private:
  UpdateStatus checked_step(const Sample& sample, const OutputMask<Dims>* present) {
    if constexpr (!Dims::is_fixed) detail::require_sample_sizes(sample, sizes(), Observer::name_update);
    detail::require_known_input_size(sample, sizes().nx, Observer::name_update);
    if (!detail::finite_sample(sample, present)) return UpdateStatus::nonfinite_input;
    const UpdateStatus status = self().work_.run([&](auto& w) { return self().advance(sample, present, w); });
    health_.note(status, step_);
    if (status == UpdateStatus::accepted) ++step_;
    return status;
  }

  Observer& self() noexcept { return static_cast<Observer&>(*this); }
  const Observer& self() const noexcept { return static_cast<const Observer&>(*this); }

  Index step_ = 0;
};

}  // namespace adaptobs
