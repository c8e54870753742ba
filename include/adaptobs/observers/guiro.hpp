#pragma once
/// \file
/// Continuous-discrete adaptive observer of Guiro, Iggidr, Ngom and Touré
/// (2008, docs/references.md), eq. (2), generalized to p parameters,
/// m outputs, a sampling period T and known inputs.
///
/// System (Guiro et al. 2008, eq. (1)): \f$\dot x = Ax + Bu(t) + g(t) + \varphi(t)\theta\f$,
/// \f$y_k = Cx(kT)\f$, with \f$\theta\in\mathbb{R}^p\f$ and \f$\varphi(t)\in\mathbb{R}^{n\times p}\f$,
/// and \f$g(t)\f$ an optional known input term (zero in the paper).
/// Between samples the observer integrates \f$\dot z = Az + Bu + g(t) + \varphi(t)\hat\theta_k\f$;
/// at the samples it corrects z with the output and θ̂ with the previous
/// a-posteriori output error:
/// \f[ z^-_{k+1} = E z_k + \Psi_k\hat\theta_k + B_du_k + f_k,\qquad
///     z_{k+1} = z^-_{k+1} - K(Cz^-_{k+1} - y_{k+1}),\qquad
///     \hat\theta_{k+1} = \hat\theta_k - \Gamma(Cz_k - y_k), \f]
/// with \f$E = e^{AT}\f$, \f$\Psi_k = EH_k\f$, \f$H_k = \int_{kT}^{(k+1)T}e^{(kT-s)A}\varphi(s)ds\f$
/// (`RegressorIntegral`), \f$B_du_k\f$ the input's contribution over the
/// period (`sampled_lti_model`) and \f$f_k = \int_{kT}^{(k+1)T}e^{((k+1)T-s)A}g(s)ds\f$ the known
/// term's (`DiscreteSample::f`, empty for none; e.g. the `Psi` of a one-column
/// `RegressorIntegral` of g, or \f$\int_0^Te^{As}ds\,g_k\f$ for a term \f$g_k\f$ of the
/// sampled measurements held over the period: docs/readings/guiro.md). It is
/// known and cancels in the errors, which obey \f$v_{k+1} = (U + W(k))v_k\f$
/// (eq. (4)–(5)); gains come from `design_guiro_gains`, and
/// `check_guiro_convergence` checks proposition 2.2.
///
/// Readings of the paper (θ̂ updated with the previous a-posteriori error, the
/// example's C): docs/readings/guiro.md.
///
/// **Sample convention.** Like the library's other observers, `update`
/// consumes the sample of step k, \f$(u_k, y_k, \Psi_k)\f$ (a `DiscreteSample`
/// whose `Psi` is \f$\Psi_k = EH_k\f$, the regressor of the period that starts
/// at \f$t_k\f$, and whose `f`, when given, is \f$f_k\f$ of that same period), and moves from step k to k + 1: it corrects the prediction
/// \f$z^-_k\f$ with \f$y_k\f$ into the paper's \f$z_k\f$, updates θ̂ and
/// predicts \f$z^-_{k+1}\f$. `state()` is the prediction \f$z^-_k\f$ of the
/// current step (before its output is seen) and `corrected_state()` the
/// paper's \f$z_{k-1}\f$, corrected with the last consumed output. The paper
/// starts from an uncorrected \f$z_0\f$; `GuiroOptions::correct_initial_estimate
/// = false` replays that exactly.
///
/// **Missing and partial outputs.** An absent channel zeroes its rows of C in
/// both output errors; none present is the open-loop prediction with θ̂ held
/// (`update(sample, present)`). **Irregular sample times.** The sampled system is
/// LTV: serve \f$(E_k, B_{d,k}, C)\f$ from a `DiscreteLtvModel`, \f$\Psi_k\f$ with each
/// sample, and schedule the gains with `set_gains`. The derivations, and what
/// proposition 2.1 no longer covers: docs/readings/guiro.md.

#include <adaptobs/core/detail/commit.hpp>
#include <adaptobs/core/detail/update_workspace.hpp>
#include <adaptobs/core/dimensions.hpp>
#include <adaptobs/core/discrete_model.hpp>
#include <adaptobs/core/discrete_update.hpp>
#include <adaptobs/core/snapshot.hpp>
#include <adaptobs/core/status.hpp>
#include <adaptobs/core/validation.hpp>

#include <utility>

namespace adaptobs {

struct GuiroOptions {
  /// Correct the initial estimate with the first output (true), or use it
  /// unchanged as the paper's \f$z_0\f$ (false: the paper's eq. (2) from k = 0).
  bool correct_initial_estimate = true;
};

/// Guiro–Iggidr–Ngom–Touré observer over the sampled model \f$(E, B_d, C)\f$
/// of a continuous system (see file comment); an LTV discrete model
/// \f$(E_k, B_k, C_k)\f$ is accepted too.
///
/// Its `output_error()` is \f$\varepsilon_k = y_k - Cz^-_k\f$: the innovation that
/// eq. (2), second line, corrects \f$z^-_k\f$ with (also when the paper's uncorrected
/// \f$z_0\f$ skips that correction), not the a-posteriori error \f$Cz_k - y_k\f$ of
/// the θ̂ update.
///
/// \copydoc guiro.hpp
template <DiscreteModel Model>
class GuiroObserver : public DiscreteUpdate<GuiroObserver<Model>, typename Model::Dims, DiscreteSample> {
 public:
  ADAPTOBS_DISCRETE_UPDATE_INTERFACE(GuiroObserver, DiscreteSample, "z0");
  /// No condition is checked per step: `guiro_convergence` checks its gains at design.
  static constexpr CheckedAssumption checked_assumption{};
  using typename Dims::GainMatrix;
  using ParameterGain = typename Dims::template Matrix<Dims::np, Dims::ny>;  ///< Γ, p × m

  /// \param model sampled model \f$(e^{AT}, B_d, C)\f$, e.g. from `sampled_lti_model`;
  /// \param K, Gamma gains, e.g. from `design_guiro_gains`;
  /// \param z0, theta0 initial estimates of \f$x_0\f$ and θ.
  GuiroObserver(Model model, GainMatrix K, ParameterGain Gamma, State z0, Parameters theta0, GuiroOptions options = {})
      : model_(std::move(model)),
        gain_(std::move(K)),
        parameter_gain_(std::move(Gamma)),
        z_(std::move(z0)),
        theta_(std::move(theta0)),
        options_(options) {
    constexpr std::string_view who = "GuiroObserver";
    const Sizes s = model_.sizes();
    require_finite_shape(gain_, s.nx, s.ny, who, "K");
    require_finite_shape(parameter_gain_, s.np, s.ny, who, "Gamma");
    require_initial_estimates(z_, s.nx, theta_, s.np, who, name_initial_state, "theta0");
    corrected_ = z_;
    this->output_error_.setZero(s.ny);
    work_.resize(s);
  }

  /// Prediction \f$z^-_k\f$ of the state at the current step, before its output is consumed.
  [[nodiscard]] const State& state() const noexcept { return z_; }
  /// The paper's \f$z_{k-1}\f$: the estimate at the last consumed sample after
  /// its correction (the initial estimate before any update).
  [[nodiscard]] const State& corrected_state() const noexcept { return corrected_; }
  [[nodiscard]] const GainMatrix& gain() const noexcept { return gain_; }
  [[nodiscard]] const ParameterGain& parameter_gain() const noexcept { return parameter_gain_; }

  /// Gains used from the next update on: K corrects that sample's prediction and
  /// Γ multiplies its output error (file comment, "Irregular sample times", for a
  /// schedule over varying intervals).
  void set_gains(const GainMatrix& K, const ParameterGain& Gamma) {
    constexpr std::string_view who = "GuiroObserver::set_gains";
    require_finite_shape(K, gain_.rows(), gain_.cols(), who, "K");
    require_finite_shape(Gamma, parameter_gain_.rows(), parameter_gain_.cols(), who, "Gamma");
    gain_ = K;
    parameter_gain_ = Gamma;
  }

  [[nodiscard]] const GuiroOptions& options() const noexcept { return options_; }

  /// Its fields for `snapshot` and `restore` (core/snapshot.hpp): the model,
  /// K, Γ, the estimates and whether the first sample was consumed; the
  /// option is a setting.
  static constexpr std::string_view snapshot_type = "GuiroObserver";
  static constexpr int snapshot_version = 1;
  template <class Self, class Archive>
    requires Snapshottable<Model>
  static void visit_state(Self& self, Archive& archive) {
    archive.object("model", self.model_);
    archive("K", self.gain_);
    archive("Gamma", self.parameter_gain_);
    archive("z", self.z_);
    archive("corrected", self.corrected_);
    archive("theta", self.theta_);
    archive.setting("correct_initial_estimate", self.options_.correct_initial_estimate);
    archive("started", self.started_);
    GuiroObserver::visit_update_state(self, archive);
  }

 private:
  // The rest of `reset`: the next sample is again the first (its prediction z0
  // is corrected or not as at construction).
  void restart(const State& z0, const Parameters& theta0) {
    z_ = z0;
    corrected_ = z0;
    theta_ = theta0;
    started_ = false;
  }

  struct Workspace {
    Output innovation;  // y_k − C z^-_k
    Output residual;    // C z_k − y_k
    State corrected;    // z_k
    State predicted;    // z^-_{k+1}
    Parameters theta;   // θ̂_{k+1}
    void resize(const Sizes& s) {
      innovation.setZero(s.ny);
      residual.setZero(s.ny);
      corrected.setZero(s.nx);
      predicted.setZero(s.nx);
      theta.setZero(s.np);
    }
  };

  /// One sample: correction of \f$z^-_k\f$ with \f$y_k\f$, θ̂ update, prediction
  /// over the period with \f$\Psi_k\f$, \f$u_k\f$ and \f$f_k\f$ (eq. (2)); `nonfinite_result`,
  /// changing nothing, when the step would produce a NaN/Inf.
  UpdateStatus advance(const Sample& sample, const OutputMask<Dims>* present, Workspace& w) {
    const auto& system = model_.at(this->step());
    this->check_system_sizes(system);

    /// Eq. (2), second line: \f$z_k = z^-_k - K(Cz^-_k - y_k)\f$ (skipped for the
    /// paper's uncorrected \f$z_0\f$), with the innovation \f$y_k - Cz^-_k\f$.
    w.innovation = sample.y;
    w.innovation.noalias() -= system.C * z_;
    detail::zero_absent_rows<Dims>(w.innovation, present);
    w.corrected = z_;
    if (started_ || options_.correct_initial_estimate) w.corrected.noalias() += gain_ * w.innovation;

    /// Eq. (2), third line: \f$\hat\theta_{k+1} = \hat\theta_k - \Gamma(Cz_k - y_k)\f$, with the
    /// a-posteriori output error \f$Cz_k - y_k\f$.
    w.residual.noalias() = system.C * w.corrected;
    w.residual -= sample.y;
    detail::zero_absent_rows<Dims>(w.residual, present);
    w.theta = theta_;
    w.theta.noalias() -= parameter_gain_ * w.residual;

    /// Eq. (2), first line integrated over the period with \f$\hat\theta_k\f$:
    /// \f$z^-_{k+1} = Ez_k + \Psi_k\hat\theta_k + B_du_k + f_k\f$, \f$\Psi_k = EH_k\f$.
    w.predicted.noalias() = system.A * w.corrected;
    w.predicted.noalias() += sample.Psi * theta_;
    // Without an input (B is n × 0) there is no term: Eigen's coefficient product
    // would offset the empty B's null data pointer.
    if (sample.u.size() > 0) w.predicted.noalias() += system.B * sample.u;
    detail::add_known_input(w.predicted, sample.f);

    if (!detail::all_finite(w.predicted, w.corrected, w.theta)) return UpdateStatus::nonfinite_result;
    detail::commit(z_, w.predicted);
    detail::commit(corrected_, w.corrected);
    detail::commit(theta_, w.theta);
    detail::commit(this->output_error_, w.innovation);
    started_ = true;
    return UpdateStatus::accepted;
  }

  Model model_;
  GainMatrix gain_;
  ParameterGain parameter_gain_;
  State z_;          // z^-_k
  State corrected_;  // z_{k−1}
  Parameters theta_;
  GuiroOptions options_;
  bool started_ = false;
  detail::UpdateWorkspace<Workspace, Dims::is_fixed> work_;
};

}  // namespace adaptobs
