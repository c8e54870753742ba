#pragma once
/// \file
/// How a continuous-time observer advances between two samples.
///
/// A continuous-time observer is an ODE driven by the measured signals u(t)
/// and y(t). Between two samples \f$t_{k-1} < t_k\f$ it is integrated with
/// fixed-step RK4 (`substeps` steps per interval), and u, y are reconstructed
/// at the stage times from the samples. The reconstruction sets the accuracy
/// floor of a sampled implementation (interval h, smooth signals):
///
/// | reconstruction | needs | error of the estimates |
/// |---|---|---|
/// | `hold` — the value at \f$t_{k-1}\f$ | \f$y_{k-1}\f$ | \f$O(h)\f$ for a smooth signal; exact for a zero-order-hold actuator |
/// | `linear` — straight line between the samples | \f$y_{k-1}, y_k\f$ | \f$O(h^2)\f$ |
/// | `quadratic` — parabola through \f$t_{k-1}\f$, the midpoint and \f$t_k\f$ | the sample's `midpoint` | \f$O(h^4)\f$ with one substep (exact stage values) |
///
/// A real-time loop sampling every \f$T_s\f$ gets the fourth-order behaviour
/// by updating the observer every second sample (h = 2Ts), the sample in
/// between being the midpoint; with `linear` it updates every sample at
/// second order. Integrating the plant and the observer as one ODE (in
/// simulation, `simulation/joint_integration.hpp`) has no floor at all.
///
/// The default reconstruction holds u (digital actuators) and interpolates y linearly.
///
/// **Long intervals.** RK4 is stable only for steps h with hλ inside its
/// stability region (|hλ| ≲ 2.78 on the negative real axis), so a fixed number
/// of steps per interval fails on a gap between samples: with 10-ms samples and
/// one step, a 2-s gap drives a Kalman–Bucy covariance indefinite and a
/// 20-s gap multiplies the errors by 10¹¹. The step is therefore bounded:
/// an interval is cut into `substeps` steps, or more when those would be longer
/// than `max_step`. Left at 0, `max_step` is learned from the first interval
/// (for the Kalman–Bucy filter, the first that fits its stable step, below):
/// 1.25 times its step, so that sampling jitter below 25% never changes the cost
/// of an update, and a gap runs with the step the observer was tuned with.
/// An interval that would need more than `max_substeps` steps is rejected
/// (`UpdateStatus::interval_too_long`), keeping the cost of one update bounded;
/// `resynchronize()` then restarts the time origin at the next sample without
/// touching the estimates, and a learned limit is learned again from the
/// interval after it.
///
/// **The first interval.** A learned limit is only as good as the interval it
/// comes from. An observer that can bound the step its own dynamics allow (the
/// Kalman–Bucy filter, from its model and covariances: `stable_step` below)
/// makes the first interval safe: while no limit is known, an interval whose
/// `substeps` steps would exceed that bound is crossed in steps of the bound
/// and teaches nothing, and the limit is learned from the first interval that
/// fits. Without such a bound (the adaptive observers), a first interval that
/// is itself a gap runs with `substeps` steps whatever its length. For every
/// observer, a tiny first interval (a repeated time stamp) makes every later
/// interval too long until `resynchronize()`. Where the first interval cannot
/// be trusted, give `max_step`.
///
/// **Missing outputs.** A sample may come without some of its outputs (a mask
/// `present`, as for the discrete observers). An output channel is *measured
/// over an interval* when the reconstruction of y there needs only its present
/// values: present at both ends (`linear`, `quadratic`, whose midpoint is then
/// taken as present too) or at the start (`hold`). The observer is handed the
/// interval's mask and integrates its time update for the other channels: they
/// have no output injection and no output error, so that they drive neither
/// the state nor the parameters (docs/readings/continuous_gaps.md). An absent value
/// is kept as NaN in the previous sample (and in a snapshot of it): it is
/// never read.

#include <adaptobs/core/continuous_model.hpp>
#include <adaptobs/core/detail/commit.hpp>
#include <adaptobs/core/detail/finite.hpp>
#include <adaptobs/core/dimensions.hpp>
#include <adaptobs/core/runge_kutta.hpp>
#include <adaptobs/core/status.hpp>
#include <adaptobs/core/validation.hpp>

#include <cmath>
#include <concepts>
#include <limits>
#include <string_view>
#include <utility>

namespace adaptobs {

/// How a sampled signal is rebuilt between two samples.
enum class SignalReconstruction {
  hold,       ///< the previous sample's value over the interval
  linear,     ///< straight line between the previous and the current sample
  quadratic,  ///< parabola through the previous sample, the current sample's midpoint and the current sample
};

/// Stepping options shared by every continuous-time observer.
struct SamplingOptions {
  int substeps = 1;  ///< RK4 steps per sampling interval (≥ 1)
  /// Longest RK4 step, in the time unit of the samples; 0 learns it from the
  /// first interval that teaches it (1.25 × its step; see the file comment).
  double max_step = 0;
  int max_substeps = 1'000'000;  ///< most RK4 steps in one interval; a longer interval is rejected
  SignalReconstruction input = SignalReconstruction::hold;     ///< reconstruction of u
  SignalReconstruction output = SignalReconstruction::linear;  ///< reconstruction of y

  /// Whether a sample that ends an interval must carry its midpoint signals.
  [[nodiscard]] bool needs_midpoint() const noexcept {
    return input == SignalReconstruction::quadratic || output == SignalReconstruction::quadratic;
  }
};

/// Advances the internal state of a continuous-time observer from one sample
/// to the next with RK4, reconstructing u and y at the stage times.
///
/// The first sample only records the time origin and the signals. Each later
/// sample is integrated to; it is rejected (state untouched) when non-finite,
/// when its time does not advance, or when the step produces NaN/Inf.
template <StateSpace D, class InternalState>
class SampledIntegrator {
 public:
  using Scalar = typename D::Scalar;
  using Sample = ContinuousSample<D>;

  SampledIntegrator(const InternalState& like, Sizes sizes, SamplingOptions options, std::string_view who)
      : rk4_(like), candidate_(like), sizes_(sizes), options_(options) {
    require(options.substeps >= 1, who, "options.substeps", "must be at least 1");
    require(std::isfinite(options.max_step) && options.max_step >= 0, who, "options.max_step",
            "must be finite and non-negative (0 learns it from the first intervals)");
    require(options.max_substeps >= options.substeps, who, "options.max_substeps", "must be at least options.substeps");
    previous_.u.setZero(sizes.nu);
    previous_.y.setZero(sizes.ny);
    u_.setZero(sizes.nu);
    y_.setZero(sizes.ny);
    measured_.setConstant(sizes.ny, true);
  }

  /// True once a first sample has fixed the time origin.
  [[nodiscard]] bool started() const noexcept { return started_; }
  /// Time of the last accepted sample.
  [[nodiscard]] Scalar time() const noexcept { return previous_.t; }
  [[nodiscard]] const SamplingOptions& options() const noexcept { return options_; }
  /// Forgets the previous sample and a learned step limit: the next sample
  /// starts the integration anew, and `time()` reads 0, as after construction.
  void restart() noexcept {
    started_ = false;
    learned_step_ = 0;
    previous_.t = Scalar(0);
    previous_.u.setZero();
    previous_.y.setZero();
  }
  /// Forgets the previous sample: the next sample sets a new time origin. A
  /// learned step limit is learned again from the interval after it (one
  /// learned from an unrepresentative interval would otherwise reject every
  /// later one); `options.max_step` stays.
  void resynchronize() noexcept {
    started_ = false;
    learned_step_ = 0;
  }
  /// Longest RK4 step from now on: `options.max_step`, or the learned limit (0 until one is learned).
  [[nodiscard]] Scalar max_step() const noexcept {
    return options_.max_step > 0 ? Scalar(options_.max_step) : learned_step_;
  }

  /// Integrates `state` with `rhs(x, dxdt, t, u, y, measured)` from the
  /// previous sample to `sample.t`, with only the output channels in `present`
  /// (null: all of them) measured at `sample.t`; the entries of y of the others
  /// are ignored. `measured` is the mask of the channels measured over the
  /// interval (the file comment), null when all are: then the integration is
  /// bit for bit that of a sample without a mask. `validate(candidate)` may
  /// adjust the integrated state (for example re-symmetrize a covariance) and
  /// returns `accepted`, or the reason to reject it; nothing is committed
  /// unless it accepts. While no step limit is known (none given, none learned
  /// yet), `stable_step(state, t, u, y, measured)` at the previous sample bounds
  /// the step of the interval (0: no bound; see the file comment).
  template <class Rhs, class Validate, class StableStep>
  UpdateStatus advance(const Sample& sample, const OutputMask<D>* present, InternalState& state, Rhs&& rhs,
                       std::string_view who, Validate&& validate, StableStep&& stable_step) {
    if constexpr (!D::is_fixed) check_sizes(sample, who);
    if (!std::isfinite(sample.t) || !detail::finite_measured(sample.y, present, sample.u))
      return UpdateStatus::nonfinite_input;
    if (sample.midpoint && !detail::finite_measured(sample.midpoint->y, present, sample.midpoint->u))
      return UpdateStatus::nonfinite_input;
    if (!started_) {
      remember(sample, present);
      started_ = true;
      return UpdateStatus::accepted;
    }
    if (options_.needs_midpoint() && !sample.midpoint)
      fail_argument(who, "sample.midpoint", "must be set for a quadratic signal reconstruction");
    if (!(sample.t > previous_.t)) return UpdateStatus::nonincreasing_time;

    const Scalar t0 = previous_.t;
    const Scalar interval = sample.t - t0;
    const OutputMask<D>* measured = measured_over_interval(present);
    const Scalar bound =
        max_step() > 0 ? Scalar(0) : Scalar(stable_step(std::as_const(state), t0, previous_.u, previous_.y, measured));
    const int steps = steps_for(interval, bound);
    if (steps == 0) return UpdateStatus::interval_too_long;
    const auto system = [&](const InternalState& x, InternalState& dxdt, Scalar t) {
      const Scalar s = (t - t0) / interval;
      reconstruct(options_.input, s, previous_.u, sample.midpoint ? &sample.midpoint->u : nullptr, sample.u, u_);
      reconstruct(options_.output, s, previous_.y, sample.midpoint ? &sample.midpoint->y : nullptr, sample.y, y_);
      rhs(x, dxdt, t, u_, y_, measured);
    };
    candidate_ = state;
    const Scalar h = interval / Scalar(steps);
    for (int i = 0; i < steps; ++i) rk4_.step(system, candidate_, t0 + Scalar(i) * h, h, candidate_);
    if (!detail::all_finite(candidate_)) return UpdateStatus::nonfinite_result;
    if (const UpdateStatus verdict = validate(candidate_); verdict != UpdateStatus::accepted) return verdict;
    // An interval cut by the stable step is no sample of the observer's rate.
    if (!(learned_step_ > 0) && steps == options_.substeps) learned_step_ = Scalar(1.25) * h;
    detail::commit(state, candidate_);
    remember(sample, present);
    return UpdateStatus::accepted;
  }

  /// `advance` of a sample with every output present, with `rhs(x, dxdt, t, u, y)`.
  template <class Rhs, class Validate, class StableStep>
  UpdateStatus advance(const Sample& sample, InternalState& state, Rhs&& rhs, std::string_view who, Validate&& validate,
                       StableStep&& stable_step) {
    const auto measured_rhs = [&rhs](const InternalState& x, InternalState& dxdt, Scalar t, const typename D::Input& u,
                                     const typename D::Output& y, const OutputMask<D>*) { rhs(x, dxdt, t, u, y); };
    const auto measured_stable_step = [&stable_step](const InternalState& x, Scalar t, const typename D::Input& u,
                                                     const typename D::Output& y,
                                                     const OutputMask<D>*) { return stable_step(x, t, u, y); };
    return advance(sample, nullptr, state, measured_rhs, who, std::forward<Validate>(validate), measured_stable_step);
  }

  /// `advance` without a bound on the first interval's step.
  template <class Rhs, class Validate>
  UpdateStatus advance(const Sample& sample, InternalState& state, Rhs&& rhs, std::string_view who,
                       Validate&& validate) {
    return advance(sample, state, std::forward<Rhs>(rhs), who, std::forward<Validate>(validate), no_stable_step);
  }

  /// `advance` without a check of the step's result beyond finiteness.
  template <class Rhs>
  UpdateStatus advance(const Sample& sample, InternalState& state, Rhs&& rhs, std::string_view who) {
    return advance(sample, state, std::forward<Rhs>(rhs), who, [](InternalState&) { return UpdateStatus::accepted; });
  }

  /// The `stable_step` of an observer that has no bound.
  static constexpr auto no_stable_step = [](const InternalState&, Scalar, const typename D::Input&,
                                            const typename D::Output&) { return Scalar(0); };

  /// Its fields for `snapshot` and `restore` (core/snapshot.hpp): the previous
  /// sample, the learned step limit and whether integration has started; the
  /// options are settings.
  template <class Self, class Archive>
  static void visit_state(Self& self, Archive& archive) {
    archive.setting("substeps", self.options_.substeps);
    archive.setting("max_substeps", self.options_.max_substeps);
    archive.setting("input", static_cast<int>(self.options_.input));
    archive.setting("output", static_cast<int>(self.options_.output));
    archive("max_step", self.options_.max_step);
    archive("previous_t", self.previous_.t);
    archive("previous_u", self.previous_.u);
    archive("previous_y", self.previous_.y);
    archive("learned_step", self.learned_step_);
    archive("started", self.started_);
  }

 private:
  // RK4 steps for an interval (see the file comment), with the step limit, or
  // else `bound`; 0 when more than max_substeps.
  // The count is compared in double, where every int is exact, before it is
  // converted: in float a max_substeps near INT_MAX rounds up to 2^31, which
  // let a count of 2^31 through to int(), undefined.
  [[nodiscard]] int steps_for(Scalar interval, Scalar bound) const {
    const Scalar limit = max_step() > 0 ? max_step() : bound;
    if (!(limit > 0)) return options_.substeps;
    const double needed = double(std::ceil(interval / limit));
    if (needed <= double(options_.substeps)) return options_.substeps;
    return needed <= double(options_.max_substeps) ? int(needed) : 0;
  }

  // Signal at the normalized time s ∈ [0, 1] of the interval. Written entry by
  // entry: one loop per signal type, where Eigen expressions would instantiate
  // a scaled sum per reconstruction and per type in every observer's update.
  template <class V>
  static void reconstruct(SignalReconstruction how, Scalar s, const V& v0, const V* mid, const V& v1, V& out) {
    switch (how) {
      case SignalReconstruction::hold: out = v0; return;
      case SignalReconstruction::linear:
        for (Index i = 0; i < out.size(); ++i) out(i) = (Scalar(1) - s) * v0(i) + s * v1(i);
        return;
      case SignalReconstruction::quadratic: {
        // Lagrange basis on the nodes 0, 1/2, 1.
        const Scalar l0 = Scalar(2) * (s - Scalar(0.5)) * (s - Scalar(1));
        const Scalar lm = Scalar(-4) * s * (s - Scalar(1));
        const Scalar l1 = Scalar(2) * s * (s - Scalar(0.5));
        for (Index i = 0; i < out.size(); ++i) out(i) = l0 * v0(i) + lm * (*mid)(i) + l1 * v1(i);
        return;
      }
    }
  }

  // The channels measured over the interval ending at a sample with `present`
  // (file comment): null when all are.
  const OutputMask<D>* measured_over_interval(const OutputMask<D>* present) {
    measured_ = previous_.y.array().isFinite();
    if (present && options_.output != SignalReconstruction::hold) measured_ = measured_ && *present;
    return measured_.all() ? nullptr : &measured_;
  }

  // An absent output is remembered as NaN: it is not known.
  void remember(const Sample& sample, const OutputMask<D>* present) {
    previous_.t = sample.t;
    previous_.u = sample.u;
    previous_.y = sample.y;
    if (present)
      for (Index i = 0; i < previous_.y.size(); ++i)
        if (!(*present)(i)) previous_.y(i) = std::numeric_limits<Scalar>::quiet_NaN();
  }

  void check_sizes(const Sample& sample, std::string_view who) const {
    require_shape(sample.u, sizes_.nu, 1, who, "sample.u");
    require_shape(sample.y, sizes_.ny, 1, who, "sample.y");
    if (sample.midpoint) {
      require_shape(sample.midpoint->u, sizes_.nu, 1, who, "sample.midpoint.u");
      require_shape(sample.midpoint->y, sizes_.ny, 1, who, "sample.midpoint.y");
    }
  }

  struct Measurement {
    Scalar t{};
    typename D::Input u;
    typename D::Output y;
  };

  RungeKutta4<InternalState> rk4_;
  InternalState candidate_;
  Sizes sizes_;
  SamplingOptions options_;
  Measurement previous_;
  Scalar learned_step_ = 0;
  bool started_ = false;
  typename D::Input u_;
  typename D::Output y_;
  OutputMask<D> measured_;
};

/// An observer that integrates a right-hand side between its samples (the
/// unified observers, the Kalman–Bucy filter): its stacked internal state s and
/// \f$\dot s\f$ = `derivative(s, ds, t, u, y)` with the input and output at time t.
template <class O>
concept ContinuousTimeObserver =
    requires(const O& o, const typename O::InternalState& s, typename O::InternalState& ds, typename O::Scalar t,
             const typename O::Input& u, const typename O::Output& y) {
      { o.sizes() } -> std::same_as<Sizes>;
      o.derivative(s, ds, t, u, y);
    };

/// The right-hand side of `observer` as a Boost.Odeint system `f(s, ds, t)`, with
/// `signals(t, u, y)` (const) writing the input and output at time t: to
/// integrate the observer with any Odeint stepper, e.g. as a reference for its
/// own integration. The system refers to `observer`, which must outlive it. It
/// is const and writes only `ds` (u and y are its call's own, allocated at each
/// call with run-time sizes): one system, or one observer, may be shared by
/// threads integrating at once, as long as nothing updates the observer then.
template <ContinuousTimeObserver O, class Signals>
[[nodiscard]] auto odeint_system(const O& observer, Signals signals) {
  using Input = typename O::Input;
  using Output = typename O::Output;
  return [&observer, signals = std::move(signals), sizes = observer.sizes()](
             const typename O::InternalState& s, typename O::InternalState& ds, typename O::Scalar t) {
    Input u = Input::Zero(sizes.nu);
    Output y = Output::Zero(sizes.ny);
    signals(t, u, y);
    observer.derivative(s, ds, t, u, y);
  };
}

}  // namespace adaptobs
