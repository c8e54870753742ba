#pragma once
/// \file
/// Discrete-time MIMO LTV adaptive observer of Guyader & Zhang
/// (Guyader & Zhang 2003, eq. (2a)–(2c); docs/references.md).
///
/// System (Guyader & Zhang 2003, eq. (1), noise free, with the known input term
/// \f$f_k\f$ of Remark 1, `DiscreteSample::f`, zero when empty):
/// \f[ x_{k+1} = A_k x_k + B_k u_k + f_k + \Psi_k\theta,\qquad y_k = C_k x_k. \f]
/// The observer filters the regressor through the stable error dynamics
/// \f$A_k - K_kC_k\f$ (eq. (2a)), corrects θ̂ along \f$\Upsilon_k^TC_k^T\f$ times
/// the output error (eq. (2b)), and moves x̂ with θ̂ through \f$\Upsilon_{k+1}\f$
/// (eq. (2c), with \f$f_k\f$ added as it is to the state: (2c′) of
/// docs/readings/guyader_zhang.md). \f$f_k\f$ cancels in \f$\tilde x\f$, and with
/// \f$\eta_k = \tilde x_k - \Upsilon_k\tilde\theta_k\f$ the errors obey (proof of theorem 1)
/// \f[ \eta_{k+1} = (A_k - K_kC_k)\eta_k,\qquad
///     \tilde\theta_{k+1} = (I - \mu_k\Upsilon_k^TC_k^TC_k\Upsilon_k)\tilde\theta_k
///                         - \mu_k\Upsilon_k^TC_k^TC_k\eta_k, \f]
/// which converge exponentially under assumptions 1–3 (theorem 1).
///
/// **Missing and partial outputs.** A sample that carries only the channels
/// of a mask \f$D_k = \mathrm{diag}(\text{present})\f$ measures \f$D_ky_k = D_kC_kx_k\f$: the
/// system of eq. (1) with output matrix \f$\bar C_k = D_kC_k\f$, whose absent rows are
/// zero. The observer runs (2a)–(2c) with \f$\bar C_k\f$ in place of \f$C_k\f$ — the
/// output error of an absent channel is 0, and so is its row of \f$C_k\Upsilon_k\f$ — and
/// the proof of theorem 1 goes through unchanged, with
/// \f$\eta_{k+1} = (A_k - K_k\bar C_k)\eta_k\f$. With no channel present this is the time
/// update \f$\Upsilon_{k+1} = A_k\Upsilon_k + \Psi_k\f$, \f$\hat\theta_{k+1} = \hat\theta_k\f$,
/// \f$\hat x_{k+1} = A_k\hat x_k + B_ku_k + \Psi_k\hat\theta_k\f$: filtering Υ through
/// \f$A_k - K_kC_k\f$ instead would leave \f$K_kC_k\Upsilon_k\tilde\theta_k\f$ in η's recursion,
/// a coupling the proof has no term for. What the theorem then asks is of the
/// sequence actually run: assumption 1 of the products of \f$A_k - K_k\bar C_k\f$ (a gap
/// of g steps multiplies η by \f$A^g\f$, which the surrounding corrected steps must
/// outweigh), and assumption 3 of \f$\sum\mu\Upsilon_k^T\bar C_k^T\bar C_k\Upsilon_k\f$, the
/// information the present channels deliver — which is what the excitation
/// monitor accumulates.

#include <adaptobs/core/detail/commit.hpp>
#include <adaptobs/core/detail/products.hpp>
#include <adaptobs/core/detail/update_workspace.hpp>
#include <adaptobs/core/dimensions.hpp>
#include <adaptobs/core/discrete_model.hpp>
#include <adaptobs/core/discrete_update.hpp>
#include <adaptobs/core/snapshot.hpp>
#include <adaptobs/core/spectral_norm.hpp>
#include <adaptobs/core/status.hpp>
#include <adaptobs/core/validation.hpp>
#include <adaptobs/diagnostics/excitation_monitor.hpp>

#include <algorithm>
#include <cmath>
#include <optional>
#include <utility>

namespace adaptobs {

/// Options of `GuyaderZhangObserver`.
struct GuyaderZhangOptions {
  /// Window L of the assumption-3 excitation monitor (eq. (4)); 0 turns it off
  /// and saves its per-step cost (one p × p outer product).
  Index excitation_window = 0;
  /// Step size \f$\mu_k = \mu / \max(1, \mu\|\bar C_k\Upsilon_k\|_F^2)\f$ instead of μ, so
  /// that assumption 2, \f$\|\sqrt{\mu_k}\bar C_k\Upsilon_k\|_2 \le 1\f$, holds at every step
  /// by construction (theorem 1 allows a time-varying \f$\mu_k\f$). Off, μ is used as
  /// given, bit for bit. Turn it on whenever outputs can be lost: without the
  /// output injection Υ grows as \f$\sum A^j\Psi\f$ over a gap (on the satellite, a
  /// few lost samples already push \f$\|\sqrt\mu C\Upsilon\|\f$ to 2, and after a 20-s
  /// outage the observer diverges).
  bool normalized_step = false;
};

/// Guyader–Zhang adaptive observer over a discrete model (LTI or LTV).
///
/// Each `update` consumes \f$(u_k, y_k, \Psi_k)\f$, and \f$f_k\f$ when the sample has one, and advances the estimates
/// from step k to k + 1. The gain \f$K_k\f$ and step size \f$\mu_k\f$ are
/// constant unless changed with `set_gain` / `set_mu` between updates. Its
/// `output_error()` is \f$\varepsilon_k = y_k - C_k\hat x_k\f$, the innovation of
/// eq. (2b)–(2c).
///
/// \copydoc guyader_zhang.hpp
template <DiscreteModel Model>
class GuyaderZhangObserver : public DiscreteUpdate<GuyaderZhangObserver<Model>, typename Model::Dims, DiscreteSample> {
 public:
  ADAPTOBS_DISCRETE_UPDATE_INTERFACE(GuyaderZhangObserver, DiscreteSample);
  /// Checked at every accepted step, by the measure \f$\|\sqrt{\mu_k}\bar C_k\Upsilon_k\|_2\f$
  /// that `assumption2_norm` returns. Past 1 the error recursion of θ̃ (file
  /// comment) may expand along \f$\Upsilon_k^TC_k^T\f$; past √2 it does, and θ̂ diverges.
  static constexpr CheckedAssumption checked_assumption{
      "assumption 2 (eq. (3)), ||sqrt(mu_k) C_k Upsilon_k|| <= 1,",
      "divide mu by at least the square of that measure (guyader_zhang_mu_bound gives the bound from the "
      "regressors), or set options.normalized_step"};
  using typename Dims::GainMatrix, typename Dims::RegressorMatrix;

  /// \param K output-injection gain making \f$A_k - KC_k\f$ exponentially stable (assumption 1);
  /// \param mu step size \f$\mu > 0\f$ small enough for assumption 2.
  /// Compile-time sizes of K, x0 or θ0 that disagree with the model's are
  /// refused by a `static_assert` naming the argument.
  template <class DK, class DX, class DT>
  GuyaderZhangObserver(Model model, const Eigen::MatrixBase<DK>& K, Scalar mu, const Eigen::MatrixBase<DX>& x0,
                       const Eigen::MatrixBase<DT>& theta0, GuyaderZhangOptions options = {})
      : model_(std::move(model)),
        gain_(detail::fitted<GainMatrix>(K)),
        mu_(mu),
        x_(detail::fitted<State>(x0)),
        theta_(detail::fitted<Parameters>(theta0)),
        normalized_step_(options.normalized_step) {
    static_assert(detail::fits_size<DK, Dims::nx, Dims::ny>, "GuyaderZhangObserver: K must be nx x ny");
    static_assert(detail::fits_size<DX, Dims::nx, 1>, "GuyaderZhangObserver: x0 must be an nx-vector");
    static_assert(detail::fits_size<DT, Dims::np, 1>, "GuyaderZhangObserver: theta0 must be an np-vector");
    constexpr std::string_view who = "GuyaderZhangObserver";
    const Sizes s = model_.sizes();
    require_finite_shape(gain_, s.nx, s.ny, who, "K");
    require_positive(mu_, who, "mu");
    require_initial_estimates(x_, s.nx, theta_, s.np, who);
    require(options.excitation_window >= 0, who, "options.excitation_window", "must be non-negative");
    if (options.excitation_window > 0) excitation_.emplace(options.excitation_window, s.np);

    upsilon_.setZero(s.nx, s.np);
    last_c_upsilon_.setZero(s.ny, s.np);
    this->output_error_.setZero(s.ny);
    work_.resize(s);
    if (is_time_invariant(model_)) update_closed_loop();
  }

  /// State estimate \f$\hat x_k\f$.
  [[nodiscard]] const State& state() const noexcept { return x_; }
  /// Filtered regressor \f$\Upsilon_k\f$ (eq. (2a)).
  [[nodiscard]] const RegressorMatrix& upsilon() const noexcept { return upsilon_; }
  [[nodiscard]] const GainMatrix& gain() const noexcept { return gain_; }
  [[nodiscard]] Scalar mu() const noexcept { return mu_; }

  /// Gain \f$K_k\f$ used from the next update on (e.g. from `KalmanGainRecursion`).
  void set_gain(const GainMatrix& K) {
    require_finite_shape(K, gain_.rows(), gain_.cols(), "GuyaderZhangObserver::set_gain", "K");
    gain_ = K;
    if (is_time_invariant(model_)) update_closed_loop();
  }

  /// Step size \f$\mu_k > 0\f$ used from the next update on.
  void set_mu(Scalar mu) {
    require_positive(mu, "GuyaderZhangObserver::set_mu", "mu");
    mu_ = mu;
  }

  /// \f$\|\sqrt{\mu_k}C_k\Upsilon_k\|_2\f$ of the last accepted step (0 before the first).
  [[nodiscard]] Scalar assumption2_norm() const {
    const Scalar norm = spectral_norm(last_c_upsilon_);
    // A normalized μ_k that underflowed to 0 is 1/‖C̄Υ‖²_F (see `advance`).
    if (last_mu_ > Scalar(0) || norm == Scalar(0)) return std::sqrt(last_mu_) * norm;
    return norm * inverse_frobenius_norm(last_c_upsilon_);
  }

  /// Assumption 2 (eq. (3)) held at the last accepted step: \f$\|\sqrt{\mu_k}C_k\Upsilon_k\| \le 1\f$.
  [[nodiscard]] bool assumption2_holds() const { return assumption2_norm() <= Scalar(1); }

  /// Excitation level α of assumption 3 (eq. (4)) over the last L accepted
  /// steps, i.e. the smallest eigenvalue of \f$\frac1L\sum\mu_i\Upsilon_i^TC_i^TC_i\Upsilon_i\f$.
  /// 1/α steps is the averaging theory's time constant of θ̂, which holds only
  /// while \f$\mu_k\|C_k\Upsilon_k\|^2 \ll 1\f$; `guyader_zhang_convergence`
  /// (design/guyader_zhang_tuning.hpp) gives the exact rate over a regressor sequence.
  /// empty while the monitor is off, its window has not filled, or a contribution
  /// in the window overflowed (`ExcitationMonitor::available`).
  [[nodiscard]] std::optional<Scalar> excitation_level() const {
    if (!excitation_ || !excitation_->full() || !excitation_->available()) return std::nullopt;
    return excitation_->level();
  }

  /// Its fields for `snapshot` and `restore` (core/snapshot.hpp): the model, K,
  /// μ, the estimates, Υ and the diagnostics; the options are settings.
  static constexpr std::string_view snapshot_type = "GuyaderZhangObserver";
  static constexpr int snapshot_version = 1;
  template <class Self, class Archive>
    requires Snapshottable<Model>
  static void visit_state(Self& self, Archive& archive) {
    archive.object("model", self.model_);
    archive("K", self.gain_);
    archive("mu", self.mu_);
    archive("x", self.x_);
    archive("theta", self.theta_);
    archive("upsilon", self.upsilon_);
    archive("closed_loop", self.closed_loop_);
    archive("last_c_upsilon", self.last_c_upsilon_);
    archive("last_mu", self.last_mu_);
    archive.setting("normalized_step", self.normalized_step_);
    archive.setting("excitation_window", self.excitation_ ? self.excitation_->window() : 0);
    if (self.excitation_) archive.object("excitation", *self.excitation_);
    GuyaderZhangObserver::visit_update_state(self, archive);
  }

 private:
  // The rest of `reset`: \f$\Upsilon = 0\f$ and the diagnostics emptied.
  void restart(const State& x0, const Parameters& theta0) {
    x_ = x0;
    theta_ = theta0;
    upsilon_.setZero();
    last_c_upsilon_.setZero();
    last_mu_ = Scalar(0);
    if (excitation_) excitation_->reset();
  }

  // Intermediate results of one step, committed only when all are finite.
  struct Workspace {
    typename Dims::Output innovation;
    typename Dims::Output scaled_innovation;  // ε, or √μ_k ε when μ_k underflowed
    typename Dims::OutputRegressor c_upsilon;
    Parameters theta_step;
    Parameters theta;
    RegressorMatrix upsilon;
    State x;
    void resize(const Sizes& s) {
      innovation.setZero(s.ny);
      scaled_innovation.setZero(s.ny);
      c_upsilon.setZero(s.ny, s.np);
      theta_step.setZero(s.np);
      theta.setZero(s.np);
      upsilon.setZero(s.nx, s.np);
      x.setZero(s.nx);
    }
  };

  /// One step of eq. (2a)–(2c′) with the sample \f$(u_k, y_k, \Psi_k, f_k)\f$;
  /// `nonfinite_result`, changing nothing, when it would produce a NaN/Inf.
  UpdateStatus advance(const Sample& sample, const OutputMask<Dims>* present, Workspace& w) {
    const auto& system = model_.at(this->step());
    this->check_system_sizes(system);

    // Output error y_k − C_k x̂_k and C_k Υ_k, shared by (2a)–(2c); with a mask,
    // their absent rows are those of C̄_k = D_kC_k, i.e. zero.
    w.innovation = sample.y;
    detail::subtract_product(w.innovation, system.C, x_);
    detail::set_product(w.c_upsilon, system.C, upsilon_);
    detail::zero_absent_rows<Dims>(w.innovation, present);
    detail::zero_absent_rows<Dims>(w.c_upsilon, present);

    /// (2b) \f$\hat\theta_{k+1} = \hat\theta_k + \mu_k\Upsilon_k^TC_k^T(y_k - C_k\hat x_k)\f$
    Scalar mu_k = mu_;
    Scalar error_scale = Scalar(1);
    if (normalized_step_) {
      const Scalar energy = mu_ * w.c_upsilon.squaredNorm();
      if (energy > Scalar(1)) mu_k = mu_ / energy;
      // Beyond about 10^154, ‖C̄Υ‖²_F overflows and μ_k underflows to 0, which
      // would freeze θ̂: the step is then taken as √μ_k C̄Υᵀ(√μ_k ε).
      if (!(mu_k > Scalar(0))) mu_k = error_scale = inverse_frobenius_norm(w.c_upsilon);
    }
    // √μ_k ε is stored before the product: Eigen's dynamic-size product kernels
    // take a scalar factor out of their operands and apply it after the sum,
    // where C̄Υᵀε itself has overflowed.
    w.scaled_innovation = error_scale * w.innovation;
    detail::set_product(w.theta_step, w.c_upsilon.transpose(), w.scaled_innovation);
    w.theta_step *= mu_k;
    w.theta = theta_ + w.theta_step;

    /// (2a) \f$\Upsilon_{k+1} = (A_k - K_kC_k)\Upsilon_k + \Psi_k\f$; for an LTV model or a
    /// mask evaluated as \f$A_k\Upsilon_k - K_k(\bar C_k\Upsilon_k)\f$, reusing \f$\bar C_k\Upsilon_k\f$.
    w.upsilon = sample.Psi;
    if (is_time_invariant(model_) && present == nullptr) {
      detail::add_product(w.upsilon, closed_loop_, upsilon_);
    } else {
      detail::add_product(w.upsilon, system.A, upsilon_);
      detail::subtract_product(w.upsilon, gain_, w.c_upsilon);
    }

    /// (2c′) \f$\hat x_{k+1} = A_k\hat x_k + B_ku_k + f_k + \Psi_k\hat\theta_k + K_k(y_k - C_k\hat x_k)
    ///        + \Upsilon_{k+1}(\hat\theta_{k+1} - \hat\theta_k)\f$ (eq. (2c) with Remark 1's known term)
    detail::set_product(w.x, system.A, x_);
    detail::add_product(w.x, system.B, sample.u);
    detail::add_known_input(w.x, sample.f);
    detail::add_product(w.x, sample.Psi, theta_);
    detail::add_product(w.x, gain_, w.innovation);
    detail::add_product(w.x, w.upsilon, w.theta_step);

    // A non-finite C_kΥ_k would make θ̂_{k+1} non-finite too (∞·0 is NaN): the check of
    // θ̂ covers it, so the excitation monitor below never sees one.
    if (!detail::all_finite(w.x, w.theta, w.upsilon)) return UpdateStatus::nonfinite_result;

    detail::commit(x_, w.x);
    detail::commit(theta_, w.theta);
    detail::commit(upsilon_, w.upsilon);
    detail::commit(last_c_upsilon_, w.c_upsilon);
    detail::commit(this->output_error_, w.innovation);
    last_mu_ = mu_k * error_scale;  // μ_k, 0 when it underflowed
    check_assumption2(last_c_upsilon_, mu_k);
    if (excitation_) {
      if (last_mu_ > Scalar(0)) [[likely]] {
        excitation_->add(last_c_upsilon_, last_mu_);
      } else {
        // √μ_k C̄Υ, from the committed value: for dynamic sizes `commit` swapped,
        // and the workspace holds the previous step's C̄Υ.
        w.c_upsilon = error_scale * last_c_upsilon_;
        excitation_->add(w.c_upsilon);
      }
    }
    return UpdateStatus::accepted;
  }

  // Assumption 2 at this step, for `health()`. ‖·‖_F bounds ‖·‖_2 from above,
  // so the spectral norm is computed only when μ_k‖C̄Υ‖²_F exceeds both 1 and
  // the worst measure so far; the normalized step keeps it at most 1.
  void check_assumption2(const typename Dims::OutputRegressor& c_upsilon, Scalar mu_k) {
    if (normalized_step_) return;
    const Scalar worst = std::max(Scalar(1), this->health_.worst_measure());
    if (!(mu_k * c_upsilon.squaredNorm() > worst * worst)) return;
    const Scalar measure = std::sqrt(mu_k) * spectral_norm(c_upsilon);
    if (measure > Scalar(1)) this->health_.note_assumption_violated(this->step(), measure);
  }

  // 1/‖M‖_F from the scaled entries, for an M whose squared norm overflows
  // (then √μ_k of the normalized step: μ_k = 1/‖C̄Υ‖²_F itself underflows).
  static Scalar inverse_frobenius_norm(const typename Dims::OutputRegressor& m) {
    const Scalar scale = m.cwiseAbs().maxCoeff();
    return Scalar(1) / (scale * (m / scale).norm());
  }

  void update_closed_loop() {
    const auto& system = model_.at(0);
    closed_loop_ = system.A;
    closed_loop_.noalias() -= gain_ * system.C;
  }

  Model model_;
  GainMatrix gain_;
  Scalar mu_;
  State x_;
  Parameters theta_;
  RegressorMatrix upsilon_;
  typename Dims::StateMatrix closed_loop_;  // A − K C, cached for a time-invariant model
  typename Dims::OutputRegressor last_c_upsilon_;
  Scalar last_mu_ = Scalar(0);
  bool normalized_step_;
  std::optional<ExcitationMonitor<Scalar, Dims::np>> excitation_;
  // Dynamic sizes keep their workspace allocated from construction on; fixed sizes use the stack.
  detail::UpdateWorkspace<Workspace, Dims::is_fixed> work_;
};

}  // namespace adaptobs
