#pragma once
/// \file
/// The public update of the continuous-time observers and the Kalman–Bucy
/// filter, written once: the base class their `update`, `reset`, estimates, time and
/// internal state come from.

#include <adaptobs/core/continuous_model.hpp>
#include <adaptobs/core/detail/update_workspace.hpp>
#include <adaptobs/core/dimensions.hpp>
#include <adaptobs/core/health.hpp>
#include <adaptobs/core/sampled_integration.hpp>
#include <adaptobs/core/status.hpp>
#include <adaptobs/core/validation.hpp>

#include <string_view>

namespace adaptobs {

/// Base of an observer integrated between its samples (CRTP), not used on its
/// own. The observer stacks everything it integrates in one vector
/// `internal_` of type `InternalState`, advanced by a `SampledIntegrator`
/// named `integrator_`, and keeps its estimates in `sizes_`, `eta_` (original
/// coordinates), `theta_` and `output_error_`. It supplies, each under this
/// name (the base is its friend; there is no optional hook):
/// - `Observer::name` and `Observer::name_reset`, the names its errors give;
/// - `work_`, the scratch of its right-hand side, kept and sized at
///   construction so that no update allocates;
/// - `derivative(s, ds, t, u, y, measured, work) const`, the right-hand side of
///   `internal_` with the output channels in `measured` (null: all) measured
///   and the others predicted, which writes only `ds` and the scratch `work` it
///   is handed: the update hands it `work_`. Its public `derivative(s, ds, t, u, y) const`
///   (the one `odeint_system` calls) computes in a workspace of its own and
///   writes only `ds`, so that concurrent calls on one observer are safe;
/// - `refresh_estimates()`, which reads `eta_` and `theta_` out of `internal_`;
/// - `finish_update(sample, present, stepping)`, run after an accepted sample
///   (the output error at the sample, 0 for an absent channel; per-step diagnostics);
/// - `set_initial(eta0, theta0)`, which restarts `internal_` and its diagnostics;
/// - `check_step(candidate)`, which may adjust an integrated state and returns
///   `accepted` or the reason to reject it;
/// - `stable_step(s, t, u, y, measured, work) const`, the longest RK4 step its
///   dynamics at (t, s) allow with the channels in `measured` measured, or 0 when
///   it has no such bound: while no step limit is known,
///   it keeps a first interval that is a gap from leaving RK4's stability
///   region (core/sampled_integration.hpp);
/// - a `visit_state` that calls `visit_update_state`, the base's own fields.
template <class Observer, StateSpace Dims>
class ContinuousUpdate : public Dims {
  using Scalar = typename Dims::Scalar;

 public:
  using Sample = ContinuousSample<Dims>;

  /// Advances the estimates to `sample.t` (see `SampledIntegrator`, which bounds
  /// the RK4 step over long intervals). Returns `UpdateStatus::accepted`, or why
  /// the sample was rejected (non-finite, time not advancing, an interval too
  /// long, a non-finite step, or the observer's own check of the step); a
  /// rejected sample leaves the observer exactly as it was.
  [[nodiscard]] UpdateStatus update(const Sample& sample) { return checked_update(sample, nullptr); }

  /// The same with only the output channels in `present` measured at
  /// `sample.t`; the entries of `sample.y` of the others are ignored (they may
  /// be NaN). Over an interval in which a channel is not measured (core/sampled_integration.hpp),
  /// the observer runs its time update for it: the channel has no output
  /// injection and no output error, so that it drives neither \f$\hat\eta\f$ nor
  /// \f$\hat\theta\f$; with no channel measured that is the open-loop prediction
  /// \f$\dot{\hat\eta} = A\hat\eta + Bu + \Phi\hat\theta\f$, \f$\dot{\hat\theta} = 0\f$
  /// (docs/readings/continuous_gaps.md). All channels present is
  /// `update(sample)`, bit for bit. The output error of an absent channel reads 0.
  [[nodiscard]] UpdateStatus update(const Sample& sample, const OutputMask<Dims>& present) {
    return checked_update(sample, detail::partial_mask<Dims>(present, sizes().ny, Observer::name));
  }

  /// Whether the run is sound (core/health.hpp): `diverged` from the sample at
  /// which consecutive intervals began to overflow, with a message naming the
  /// remedy. No condition of the observer's theorem is checked per sample.
  [[nodiscard]] HealthReport health() const { return health_.report({}, {}); }
  /// Number of accepted samples since construction or the last reset.
  [[nodiscard]] Index step() const noexcept { return samples_; }

  /// Run-time sizes (nx, nu, ny, np).
  [[nodiscard]] Sizes sizes() const noexcept { return self().sizes_; }
  /// State estimate \f$\hat\eta(t_k)\f$ in the model's coordinates.
  [[nodiscard]] const typename Dims::State& state() const noexcept { return self().eta_; }
  /// Parameter estimate \f$\hat\theta(t_k)\f$.
  [[nodiscard]] const typename Dims::Parameters& parameters() const noexcept { return self().theta_; }
  /// Time of the last accepted sample.
  [[nodiscard]] Scalar time() const noexcept { return self().integrator_.time(); }
  /// Whether an accepted sample has set the time origin: the next sample ends an
  /// interval (and so has a midpoint).
  [[nodiscard]] bool started() const noexcept { return self().integrator_.started(); }
  /// How the samples are integrated: substeps, step limits, signal reconstruction.
  [[nodiscard]] const SamplingOptions& sampling_options() const noexcept { return self().integrator_.options(); }
  /// Output error \f$\varepsilon(t_k) = y_k - C(t_k)\hat\eta(t_k)\f$ of the last accepted
  /// sample (0 before the first), at the estimate integrated to \f$t_k\f$ — at the
  /// first sample, the initial estimate: the error that drives the observer (its
  /// file comment), which fault detectors test (diagnostics/chi_square_test.hpp).
  /// The integration to \f$t_k\f$ uses y reconstructed between the samples: with
  /// `SignalReconstruction::hold` it uses y up to \f$t_{k-1}\f$ only, so
  /// \f$\varepsilon(t_k)\f$ is a prediction error (an innovation); with `linear` or
  /// `quadratic` \f$y_k\f$ has already acted on the estimate over the interval.
  [[nodiscard]] const typename Dims::Output& output_error() const noexcept { return self().output_error_; }

  /// Everything the observer integrates, stacked (for an external integrator
  /// driving `derivative`, see `odeint_system`).
  [[nodiscard]] const auto& internal_state() const noexcept { return self().internal_; }
  /// Replaces the internal state. Returns false, changing nothing, when `s`
  /// holds NaN or Inf or fails the observer's own check of an integrated step
  /// (the Kalman–Bucy filter's: a covariance that is not positive definite,
  /// which every later update would reject); a wrong size throws `ConfigurationError`.
  template <class O = Observer>
  bool set_internal_state(const typename O::InternalState& s) {
    Observer& o = self();
    require_shape(s, o.internal_.rows(), 1, Observer::name, "s");
    if (!detail::all_finite(s)) return false;
    typename O::InternalState candidate = s;  // the check may adjust it (symmetrize P)
    if (o.check_step(candidate) != UpdateStatus::accepted) return false;
    o.internal_ = candidate;
    o.refresh_estimates();
    return true;
  }

  /// Keeps every estimate but forgets the previous sample: the next one sets a
  /// new time origin (and a learned step limit is learned again from the
  /// interval after it, core/sampled_integration.hpp). For resuming after an interval rejected as
  /// `UpdateStatus::interval_too_long`, or after intervals rejected as
  /// `nonfinite_result` because of the previous sample itself: its held input
  /// or output acts over the next interval, so an accepted but extreme sample
  /// (say u = 1e308) makes every later interval overflow until it is forgotten.
  void resynchronize() noexcept { self().integrator_.resynchronize(); }

  /// Restarts from \f$\hat\eta_0, \hat\theta_0\f$ as after construction; the next
  /// sample sets the time origin.
  void reset(const typename Dims::State& eta0, const typename Dims::Parameters& theta0) {
    Observer& o = self();
    require_initial_estimates(eta0, o.sizes_.nx, theta0, o.sizes_.np, Observer::name_reset, "eta0", "theta0");
    o.set_initial(eta0, theta0);
    o.output_error_.setZero();
    o.integrator_.restart();
    health_.clear();
    samples_ = 0;
  }

 protected:
  /// The base's part of an observer's `visit_state` (core/snapshot.hpp): the
  /// sample counter and the health record.
  template <class Self, class Archive>
  static void visit_update_state(Self& self, Archive& archive) {
    archive("samples", self.samples_);
    archive.object("health", self.health_);
  }

 private:
  UpdateStatus checked_update(const Sample& sample, const OutputMask<Dims>* present) {
    using InternalState = typename Observer::InternalState;
    Observer& o = self();
    const bool stepping = o.integrator_.started();
    const auto rhs = [&o](const InternalState& s, InternalState& ds, Scalar t, const typename Dims::Input& u,
                          const typename Dims::Output& y,
                          const OutputMask<Dims>* measured) { o.derivative(s, ds, t, u, y, measured, o.work_); };
    const auto check = [&o](InternalState& candidate) { return o.check_step(candidate); };
    const auto stable_step = [&o](const InternalState& s, Scalar t, const typename Dims::Input& u,
                                  const typename Dims::Output& y, const OutputMask<Dims>* measured) {
      return o.stable_step(s, t, u, y, measured, o.work_);
    };
    const UpdateStatus status =
        o.integrator_.advance(sample, present, o.internal_, rhs, Observer::name, check, stable_step);
    health_.note(status, samples_);
    if (status != UpdateStatus::accepted) return status;
    ++samples_;
    o.refresh_estimates();
    o.finish_update(sample, present, stepping);
    return status;
  }

  Observer& self() noexcept { return static_cast<Observer&>(*this); }
  const Observer& self() const noexcept { return static_cast<const Observer&>(*this); }

  HealthRecord<Scalar> health_;
  Index samples_ = 0;
};

}  // namespace adaptobs
