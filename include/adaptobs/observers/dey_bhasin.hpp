#pragma once
/// \file
/// Adaptive observer for MIMO discrete LTI systems of Dey & Bhasin (2022),
/// eq. (3)–(23) (docs/references.md), and the Suzuki-style observer
/// it is compared with (the same filters with exponential forgetting, §5).
///
/// The plant is unknown but for its structure: order r, q outputs, m inputs,
/// observable canonical form (3)–(4), \f$x_{t+1} = Ax_t + Bu_t\f$, \f$y_t = Cx_t\f$.
/// With a Schur design matrix F of the same structure (6) it reads (7)
/// \f$x_{t+1} = Fx_t + (I_r\otimes y_t)(a - f) + Bu_t\f$, so that the filters
/// (8)–(11) give (12)
/// \f[ x_t = S_tp + F^tx_0,\qquad y_t = \varphi_t^Tp + CF^tx_0,\qquad \varphi_t = S_t^TC^T,\qquad
///     p = [(a - f)^T\ \mathrm{vec}(B)^T]^T, \f]
/// and the observer (13) \f$\hat x_t = S_t\hat p_t + F^t\hat x_0\f$ with \f$\hat p_t\f$ from an
/// adaptation law fed with \f$(\varphi_t,\ z_t = y_t - CF^t\hat x_0)\f$ (16), which
/// obey \f$z_t = \varphi_t^Tp + CF^t\tilde x_0\f$: a linear regression with a
/// vanishing perturbation. The law is a template parameter; the paper's is RLS
/// with covariance resetting (22)–(23), under which \f$\hat p_t\f$ and \f$\hat x_t\f$
/// stay bounded for any bounded input that keeps the plant bounded (theorem 5),
/// and converge when the input is sufficiently rich (theorem 6).
///
/// Timing. `update` with \f$(u_t, y_t)\f$ forms \f$\varphi_t, z_t\f$ from the filters
/// (which hold data up to t − 1), moves \f$\hat p_{t-1}\to\hat p_t\f$ (from t = 1 on:
/// \f$\varphi_0 = 0\f$), forms \f$\hat x_t\f$ (13), and feeds \f$(y_t, u_t)\f$ to the
/// filters. As for every observer of the library, `state()` is then the
/// estimate of the *next* state, here \f$\hat x_{t+1|t} = S_{t+1}\hat p_t + F^{t+1}\hat x_0
/// = F\hat x_t + (I_r\otimes y_t)(\hat a_t - f) + \hat B_tu_t\f$; the paper's \f$\hat x_t\f$
/// of (13), which also uses \f$y_t\f$, is `current_state()`.
///
/// Theorem 5 as printed rests on a false norm bound; the weighted norm
/// \f$\|\tilde p_t\|_{\Gamma_t^{-1}}\f$ repairs it, with a tighter bound (both tested):
/// docs/readings/dey_bhasin.md.
///
/// **Missing and partial outputs.** The regression (16) keeps its present rows;
/// the filters run on \f$C\hat x_t\f$ in absent entries, a vanishing perturbation
/// after finitely many gaps (derivation: docs/readings/dey_bhasin.md). That keeps the
/// true parameters a fixed point, not the least-squares solution unbiased; across
/// recurring gaps the perturbation decays for every gap pattern when the companion
/// matrices of f and a have joint spectral radius below 1. With no
/// channel present the law is not called: \f$\hat p_t = \hat p_{t-1}\f$.
///
/// **Persistent excitation** (definition 1, (15): \f$\varphi_t\f$ is PE when
/// \f$\lambda_{\min}(\sum_{i\le t}\varphi_i\varphi_i^T) \to \infty\f$), watched on demand
/// (`DeyBhasinOptions`): the cumulative information
/// \f$I_t = \sum_{i\le t}\varphi_iR^{-1}\varphi_i^T\f$, which is \f$\Gamma_t^{-1} - \Gamma_0^{-1}\f$
/// of RLS (20) until the first reset (23), and the average of its last L terms,
/// whose smallest eigenvalue and numerical rank tell which directions of p the
/// recent data excite. A sample under a mask contributes its present rows only,
/// \f$\varphi_{P}R_{PP}^{-1}\varphi_{P}^T\f$ (the information of the sub-regression the law
/// is given); one with no channel present contributes 0.

#include <adaptobs/adaptation/adaptation_law.hpp>
#include <adaptobs/adaptation/covariance_resetting.hpp>
#include <adaptobs/adaptation/exponential_forgetting.hpp>
#include <adaptobs/core/detail/cholesky.hpp>
#include <adaptobs/core/detail/commit.hpp>
#include <adaptobs/core/detail/products.hpp>
#include <adaptobs/core/detail/update_workspace.hpp>
#include <adaptobs/core/dimensions.hpp>
#include <adaptobs/core/health.hpp>
#include <adaptobs/core/status.hpp>
#include <adaptobs/core/symmetric_eigenvalues.hpp>
#include <adaptobs/core/validation.hpp>
#include <adaptobs/diagnostics/excitation_monitor.hpp>
#include <adaptobs/observers/canonical_form_filters.hpp>

#include <Eigen/Core>

#include <cmath>
#include <limits>
#include <optional>
#include <string_view>
#include <type_traits>
#include <utility>

namespace adaptobs {

/// The excitation diagnostics of `DeyBhasinObserver` (file comment, "Persistent
/// excitation"); both off by default, at no cost to the update.
struct DeyBhasinOptions {
  /// Accumulate \f$I_t = \sum\varphi_iR^{-1}\varphi_i^T\f$ (`information`,
  /// `information_level`): one \f$n_p \times n_p\f$ rank-q update per sample.
  bool information = false;
  /// Window L of the monitor of \f$\frac1L\sum\varphi_iR^{-1}\varphi_i^T\f$ over the last L
  /// samples (`excitation_level`, `excitation_rank`); 0 turns it off.
  Index excitation_window = 0;
};

/// Dey–Bhasin adaptive observer of order `R` with `Q` outputs and `M` inputs
/// (`Eigen::Dynamic` allowed), adapting with `Law` (default: covariance
/// resetting, eq. (23)).
///
/// \copydoc dey_bhasin.hpp
template <typename S, int R, int Q, int M, template <typename, int, int> class Law = CovarianceResettingRls>
class DeyBhasinObserver : public CanonicalFormFilters<S, R, Q, M>::Dims {
 public:
  using Filters = CanonicalFormFilters<S, R, Q, M>;
  using Dims = typename Filters::Dims;
  using Scalar = S;
  using typename Dims::State, typename Dims::Input, typename Dims::Output, typename Dims::Parameters,
      typename Dims::StateMatrix, typename Dims::InputMatrix;
  using Coefficients = typename Filters::Coefficients;
  using Regressor = typename Filters::Regressor;
  using Bank = typename Filters::Bank;
  using AdaptationLawType = Law<S, Dims::np, Dims::ny>;
  using LawOptions = typename AdaptationLawType::Options;
  using Information = Eigen::Matrix<S, Dims::np, Dims::np>;
  using Weight = Eigen::Matrix<S, Dims::ny, Dims::ny>;
  static_assert(DiscreteAdaptationLaw<AdaptationLawType>,
                "DeyBhasinObserver: Law must model adaptobs::DiscreteAdaptationLaw");

  /// One measured sample: input \f$u_t\f$ and output \f$y_t\f$.
  struct Sample {
    Input u;
    Output y;
  };

  /// \param f  first-column entries of F (eq. (6), the paper's vector f); F must be Schur stable;
  /// \param x0 initial state estimate \f$\hat x_0\f$ (n = rq entries, fixing q);
  /// \param a0 first-column entries of \f$\hat A_0\f$ (the paper's \f$\hat a_0\f$);
  /// \param B0 initial estimate \f$\hat B_0\f$ (n × m);
  /// \param options the adaptation law's options, e.g. `{.k0 = 1000, .kmin = 1e-4, .R = I}`;
  /// \param diagnostics the excitation diagnostics kept (none by default).
  DeyBhasinObserver(const Coefficients& f, State x0, const Coefficients& a0, const InputMatrix& B0, LawOptions options,
                    DeyBhasinOptions diagnostics = {})
      : filters_(f, outputs_of(f, x0), B0.cols()),
        law_(initial_parameters(filters_, a0, B0), std::move(options), filters_.outputs()),
        x0_(std::move(x0)),
        track_information_(diagnostics.information) {
    constexpr std::string_view who = "DeyBhasinObserver";
    // n = rq with the filters' q: a compile-time Q is not the q of x0's length.
    require_finite_shape(x0_, filters_.states(), 1, who, "x0");
    const Sizes s = filters_.sizes();
    require(diagnostics.excitation_window >= 0, who, "diagnostics.excitation_window", "must be non-negative");
    if (diagnostics.excitation_window > 0) excitation_.emplace(diagnostics.excitation_window, s.np);
    information_.setZero(s.np, s.np);
    weight_factor_ = detail::CholeskyFactor<Weight>(s.ny);
    factor_weight(who, "options.R");
    bank_.setZero(s.ny + s.nu, filters_.order());
    last_.setZero(s.ny + s.nu);
    phi_.setZero(s.np, s.ny);
    z_.setZero(s.ny);
    prediction_error_.setZero(s.ny);
    work_.resize(filters_);
    restart_filters();
  }

  /// Eq. (16), (22)–(23) and (13) with the sample \f$(u_t, y_t)\f$ (any type with members `u`, `y`).
  ///
  /// Returns `nonfinite_input` for a NaN/Inf in the sample and
  /// `nonfinite_result` when the step would produce one (or the law broke
  /// down); in both cases the observer is left exactly as it was.
  template <class AnySample>
    requires requires(const AnySample& s) {
      s.u;
      s.y;
    }
  [[nodiscard]] UpdateStatus update(const AnySample& sample) {
    return step_with(sample.u, sample.y, nullptr);
  }

  /// The same with only the output channels in `present` measured (file comment,
  /// "Missing and partial outputs"); absent entries of `sample.y` are ignored
  /// (they may be NaN or Inf). All channels present is `update(sample)`, bit for
  /// bit; none is the time update.
  template <class AnySample>
    requires requires(const AnySample& s) {
      s.u;
      s.y;
    }
  [[nodiscard]] UpdateStatus update(const AnySample& sample, const OutputMask<Dims>& present) {
    return step_with(sample.u, sample.y,
                     detail::partial_mask<Dims>(present, filters_.outputs(), "DeyBhasinObserver::update"));
  }

  /// \f$\hat x_{t+1|t} = S_{t+1}\hat p_t + F^{t+1}\hat x_0\f$: the estimate of the next state
  /// (\f$\hat x_0\f$ before the first sample).
  [[nodiscard]] const State& state() const noexcept { return next_state_; }
  /// \f$\hat x_t = S_t\hat p_t + F^t\hat x_0\f$ (13) at the last sample t (\f$\hat x_0\f$ before the first).
  [[nodiscard]] const State& current_state() const noexcept { return state_; }
  /// \f$\hat p_t = [(\hat a_t - f)^T\ \mathrm{vec}(\hat B_t)^T]^T\f$.
  [[nodiscard]] const Parameters& parameters() const noexcept { return law_.parameters(); }
  /// \f$\hat a_t\f$: first-column entries of \f$\hat A_t\f$.
  [[nodiscard]] Coefficients a_hat() const {
    return parameters().template head<R>(filters_.order()) + filters_.coefficients();
  }
  /// \f$\hat A_t = \bar A(\hat a_t)\otimes I_q\f$ (3).
  [[nodiscard]] StateMatrix A_hat() const { return block_companion_matrix<Q>(a_hat(), filters_.outputs()); }
  /// \f$\hat B_t\f$ (n × m).
  [[nodiscard]] InputMatrix B_hat() const {
    return Eigen::Map<const InputMatrix>(parameters().data() + filters_.order(), filters_.states(), filters_.inputs());
  }
  /// \f$\varphi_t\f$ of the last sample (zero before the first).
  [[nodiscard]] const Regressor& regressor() const noexcept { return phi_; }
  /// \f$z_t = y_t - CF^t\hat x_0\f$ (16) of the last sample (0 in the entries of absent channels).
  [[nodiscard]] const Output& measurement() const noexcept { return z_; }
  /// Output error of the last accepted update: the a-priori prediction error of
  /// the regression (16), \f$\varepsilon_t = z_t - \varphi_t^T\hat p_{t-1}\f$, which
  /// the RLS law (22) corrects \f$\hat p_{t-1}\to\hat p_t\f$ with (not the a-posteriori
  /// \f$z_t - \varphi_t^T\hat p_t\f$). Since \f$\varphi_t^T = CS_t\f$ it is
  /// \f$y_t - C\hat x_{t|t-1}\f$, \f$\hat x_{t|t-1} = S_t\hat p_{t-1} + F^t\hat x_0\f$ the
  /// `state()` before the update: the innovation, which fault detectors test
  /// (diagnostics/chi_square_test.hpp). Absent channels zero; 0 before the
  /// first update; at t = 0 (\f$\varphi_0 = 0\f$) it is \f$z_0\f$.
  [[nodiscard]] const Output& output_error() const noexcept { return prediction_error_; }
  /// \f$S_tp + F^t\hat x_0\f$ for any p at the last sample t: the state (12) of the model
  /// with parameters p (with \f$\hat x_0 = x_0\f$ and the true p it is \f$x_t\f$).
  [[nodiscard]] State state_with(const Parameters& p) const {
    require_shape(p, filters_.parameters(), 1, "DeyBhasinObserver::state_with", "p");
    State x(filters_.states());
    filters_.state(bank_, p, current_free_, x);
    return x;
  }
  /// The filter bank \f$\Sigma_t^T\f$ ((q + m) × r).
  [[nodiscard]] const Bank& filter_bank() const noexcept { return bank_; }
  [[nodiscard]] const Filters& filters() const noexcept { return filters_; }
  [[nodiscard]] const AdaptationLawType& law() const noexcept { return law_; }
  /// Number of accepted samples since construction or the last reset.
  [[nodiscard]] Index step() const noexcept { return step_; }
  /// Whether the run is sound (core/health.hpp): `diverged` from the sample at
  /// which consecutive steps began to overflow, with a message naming the
  /// remedy. No condition of the theorem is checked per sample.
  [[nodiscard]] HealthReport health() const { return health_.report({}, {}); }

  /// \f$I_t = \sum_{i\le t}\varphi_iR^{-1}\varphi_i^T\f$ over the samples since construction or
  /// `reset` (file comment, "Persistent excitation"); kept through covariance resets and
  /// `restart_adaptation`. Zero unless `DeyBhasinOptions::information`.
  [[nodiscard]] const Information& information() const noexcept { return information_; }
  /// \f$\lambda_{\min}(I_t)\f$: growing without bound under persistent excitation (15).
  /// Empty unless `DeyBhasinOptions::information`, or once a sum beyond the
  /// floating-point range has made \f$I_t\f$ non-finite (until `reset`).
  [[nodiscard]] std::optional<Scalar> information_level() const {
    if (!track_information_ || !detail::all_finite(information_)) return std::nullopt;
    return symmetric_eigenvalues(information_)(0);
  }
  /// \f$\lambda_{\min}\f$ of \f$\frac1L\sum_{i=t-L+1}^{t}\varphi_iR^{-1}\varphi_i^T\f$, the last L samples.
  /// Empty while the monitor is off, its window has not filled, or a contribution
  /// in the window overflowed (`ExcitationMonitor::available`).
  [[nodiscard]] std::optional<Scalar> excitation_level() const {
    if (!excitation_ready()) return std::nullopt;
    return excitation_->level();
  }
  /// Numerical rank of that average: the number of its eigenvalues above
  /// `relative_tolerance` times the largest, i.e. of the directions of p the last L
  /// samples excite. Empty when `excitation_level` is.
  [[nodiscard]] std::optional<Index> excitation_rank(Scalar relative_tolerance) const {
    if (!excitation_ready()) return std::nullopt;
    const auto lambda = symmetric_eigenvalues(excitation_->average());
    const Scalar largest = lambda(lambda.size() - 1);
    if (!(largest > Scalar(0))) return Index(0);
    return Index((lambda.array() > relative_tolerance * largest).count());
  }
  /// The same at the tolerance \f$10^3n_p\varepsilon\f$, well above the rounding of the
  /// running sum and of its eigenvalues (about \f$n_p\varepsilon\lambda_{\max}\f$).
  [[nodiscard]] std::optional<Index> excitation_rank() const {
    return excitation_rank(Scalar(1000) * Scalar(filters_.parameters()) * std::numeric_limits<Scalar>::epsilon());
  }
  /// The window's monitor, when on.
  [[nodiscard]] const std::optional<ExcitationMonitor<Scalar, Dims::np>>& excitation_monitor() const noexcept {
    return excitation_;
  }
  [[nodiscard]] Sizes sizes() const noexcept { return filters_.sizes(); }
  [[nodiscard]] const State& initial_state() const noexcept { return x0_; }

  /// Restarts the adaptation law's gain at its initial value (Γ₀, or \f$k_0I\f$
  /// for covariance resetting), keeping \f$\hat p\f$, the filters and t: the
  /// resetting of eq. (23) on demand. After a detected parameter change
  /// (diagnostics/cusum.hpp) the law then weighs the new data as it weighed the
  /// first, instead of the small gain that a long history of old data left it with.
  /// The law's own counters (e.g. the resets of `CovarianceResettingRls`) restart too.
  void restart_adaptation() {
    const Parameters p = law_.parameters();
    law_.restart(p);
  }

  /// Restarts from \f$\hat x_0\f$ and \f$\hat p_0\f$ at t = 0: filters cleared, law restarted.
  void reset(const State& x0, const Parameters& p0) {
    constexpr std::string_view who = "DeyBhasinObserver::reset";
    require_initial_estimates(x0, filters_.states(), p0, filters_.parameters(), who, "x0", "p0");
    law_.restart(p0);
    x0_ = x0;
    restart_filters();
    health_.clear();
    information_.setZero();
    if (excitation_) excitation_->reset();
  }

  /// \f$[(a - f)^T\ \mathrm{vec}(B)^T]^T\f$ for first-column entries a and input matrix B.
  [[nodiscard]] Parameters parameters_of(const Coefficients& a, const InputMatrix& B) const {
    return initial_parameters(filters_, a, B);
  }

  /// Its fields for `snapshot` and `restore` (core/snapshot.hpp): the filters'
  /// coefficients, the law's estimate and counters, the filter bank and the
  /// estimates, and the excitation diagnostics when they are on. The law names the
  /// class: a Suzuki observer's snapshot is not a Dey–Bhasin one's. Without the
  /// diagnostics the field list is the one version 1 always had, so a snapshot
  /// of an earlier build restores into an observer built without them; with them
  /// their settings must agree (an observer with and one without refuse each
  /// other's snapshots, naming the first field that differs).
  static constexpr std::string_view snapshot_type =
      std::is_same_v<AdaptationLawType, ExponentialForgettingRls<S, Dims::np, Dims::ny>> ? "SuzukiObserver"
                                                                                         : "DeyBhasinObserver";
  static constexpr int snapshot_version = 1;
  template <class Self, class Archive>
  static void visit_state(Self& self, Archive& archive) {
    archive.object("filters", self.filters_);
    archive.object("law", self.law_);
    if constexpr (Archive::reading) self.factor_weight("restore", "snapshot");
    archive("x0", self.x0_);
    archive("bank", self.bank_);
    archive("last", self.last_);
    archive("current_free", self.current_free_);
    archive("phi", self.phi_);
    archive("z", self.z_);
    archive("prediction_error", self.prediction_error_);
    archive("state", self.state_);
    archive("next_state", self.next_state_);
    archive("step", self.step_);
    archive.object("health", self.health_);
    bool diagnostics = self.track_information_ || self.excitation_;
    if constexpr (Archive::reading) diagnostics = diagnostics || archive.contains("information");
    if (diagnostics) {
      archive.setting("information", self.track_information_);
      archive.setting("excitation_window", self.excitation_ ? self.excitation_->window() : 0);
      if (self.track_information_) archive("information_sum", self.information_);
      if (self.excitation_) archive.object("excitation", *self.excitation_);
    }
  }

 private:
  struct Workspace {
    Bank bank;
    State free;
    Regressor phi;
    Output z;
    Output error;  // z_t − φ_tᵀ p̂_{t−1}
    Output y;      // ȳ_t: y_t with its absent entries predicted
    State x;
    State next;
    Regressor weighted;    // φ̄_t L̄⁻ᵀ, R̄ = L̄L̄ᵀ: the sample's information is its Gram matrix
    Weight masked_weight;  // R̄ = DRD + (I − D)
    detail::CholeskyFactor<Weight> masked_factor;
    void resize(const Filters& filters) {
      const Sizes s = filters.sizes();
      bank.setZero(s.ny + s.nu, filters.order());
      free.setZero(s.nx);
      phi.setZero(s.np, s.ny);
      z.setZero(s.ny);
      error.setZero(s.ny);
      y.setZero(s.ny);
      x.setZero(s.nx);
      next.setZero(s.nx);
      weighted.setZero(s.np, s.ny);
      masked_weight.setZero(s.ny, s.ny);
      masked_factor = detail::CholeskyFactor<Weight>(s.ny);
    }
  };

  // R = LLᵀ of the law (the identity for an unweighted law), positive definite by the
  // law's own check; again after a restore, which may bring another R.
  void factor_weight(std::string_view who, std::string_view argument) {
    if constexpr (requires { law_.options().R; }) {
      weight_ = law_.options().R;
    } else {
      weight_.setIdentity(filters_.outputs(), filters_.outputs());
    }
    if (!weight_factor_.compute(weight_)) fail_argument(who, argument, "must be positive definite");
  }

  static Index outputs_of(const Coefficients& f, const State& x0) {
    require(f.size() >= 1, "DeyBhasinObserver", "f", "must have at least one entry (the order r)");
    require(x0.size() >= f.size() && x0.size() % f.size() == 0, "DeyBhasinObserver", "x0",
            "must have n = r q entries, a multiple of the order r = size of f");
    return x0.size() / f.size();
  }

  static Parameters initial_parameters(const Filters& filters, const Coefficients& a0, const InputMatrix& B0) {
    constexpr std::string_view who = "DeyBhasinObserver";
    const Index r = filters.order();
    require_finite_shape(a0, r, 1, who, "a0");
    require_finite_shape(B0, filters.states(), filters.inputs(), who, "B0");
    Parameters p(filters.parameters());
    p.template head<R>(r) = a0 - filters.coefficients();
    p.template segment<product_of_sizes(M, Dims::nx)>(r, B0.size()) = B0.reshaped();
    return p;
  }

  void restart_filters() {
    bank_.setZero();
    last_.setZero();
    phi_.setZero();
    z_.setZero();
    prediction_error_.setZero();
    current_free_ = x0_;
    state_ = x0_;
    next_state_ = x0_;
    step_ = 0;
  }

  // `present` is null when every channel is.
  template <class U, class Y>
  UpdateStatus step_with(const U& u, const Y& y, const OutputMask<Dims>* present) {
    // At every size: a sample of any type may hold vectors of run-time size
    // even when the observer's are fixed (free when both are fixed).
    require_shape(u, filters_.inputs(), 1, "DeyBhasinObserver::update", "sample.u");
    require_shape(y, filters_.outputs(), 1, "DeyBhasinObserver::update", "sample.y");
    const UpdateStatus status = work_.run([&](Workspace& w) { return advance(u, y, present, w); });
    health_.note(status, step_);
    return status;
  }

  template <class U, class Y>
  UpdateStatus advance(const Eigen::MatrixBase<U>& u, const Eigen::MatrixBase<Y>& y, const OutputMask<Dims>* present,
                       Workspace& w) {
    if (!detail::finite_measured(y, present, u)) return UpdateStatus::nonfinite_input;
    const Index q = filters_.outputs();
    const bool first = step_ == 0;

    // Filters (8)–(9) and F^t x̂_0, advanced with the previous sample.
    w.bank = bank_;
    w.free = current_free_;
    if (!first) {
      filters_.advance(w.bank, last_);
      filters_.apply_transition_to_state(w.free);
    }
    /// (12) \f$\varphi_t = S_t^TC^T\f$ and (16) \f$z_t = y_t - CF^t\hat x_0\f$.
    filters_.regressor(w.bank, w.phi);
    w.z = y - w.free.head(q);
    const bool adapt = !first && (!present || present->any());

    /// (22)–(23) (or the chosen law): \f$\hat p_{t-1} \to \hat p_t\f$ from t = 1 on, with
    /// the present rows of (16) only under a mask.
    const Parameters* p = &law_.parameters();
    if (adapt) {
      if (!(present ? law_.propose(w.phi, w.z, *present) : law_.propose(w.phi, w.z)))
        return UpdateStatus::nonfinite_result;
      p = &law_.proposal();
    }
    /// (13) \f$\hat x_t = S_t\hat p_t + F^t\hat x_0\f$, and the prediction of \f$x_{t+1}\f$ (7)
    /// from \f$\bar y_t\f$: \f$y_t\f$, its absent entries replaced by those of \f$C\hat x_t\f$.
    filters_.state(w.bank, *p, w.free, w.x);
    // The a-priori error z_t − φ_tᵀ p̂_{t−1} of (22) (p̂_{t−1}: the law's estimate until it commits).
    w.error = w.z;
    detail::subtract_product(w.error, w.phi.transpose(), law_.parameters());
    w.y = y;
    if (present)
      for (Index i = 0; i < q; ++i)
        if (!(*present)(i)) {
          w.y(i) = w.x(i);
          w.z(i) = 0;
          w.error(i) = 0;
        }
    filters_.predict(w.x, *p, w.y, u, w.next);
    if (!detail::all_finite(w.x, w.next, w.bank, w.phi, w.z, w.error)) return UpdateStatus::nonfinite_result;

    if (adapt) law_.commit();
    detail::commit(bank_, w.bank);
    detail::commit(current_free_, w.free);
    detail::commit(phi_, w.phi);
    detail::commit(z_, w.z);
    detail::commit(prediction_error_, w.error);
    detail::commit(state_, w.x);
    detail::commit(next_state_, w.next);
    last_.head(q) = w.y;
    last_.tail(filters_.inputs()) = u;
    ++step_;
    if (track_information_ || excitation_) add_information(present, w);
    return UpdateStatus::accepted;
  }

  /// Definition 1 (15), weighted as the regression (16) is: the committed sample adds
  /// \f$\bar\varphi_t\bar R^{-1}\bar\varphi_t^T = \Phi^T\Phi\f$, \f$\Phi = \bar L^{-1}\bar\varphi_t^T\f$, with
  /// \f$\bar\varphi_t = \varphi_tD\f$ and \f$\bar R = DRD + (I - D) = \bar L\bar L^T\f$ (D = I without a mask),
  /// i.e. \f$\varphi_PR_{PP}^{-1}\varphi_P^T\f$ of the present channels P.
  void add_information(const OutputMask<Dims>* present, Workspace& w) {
    const detail::CholeskyFactor<Weight>* factor = &weight_factor_;
    w.weighted = phi_;  // the committed φ_t: for dynamic sizes `commit` swapped w.phi
    if (present) {
      for (Index j = 0; j < w.weighted.cols(); ++j)
        if (!(*present)(j)) w.weighted.col(j).setZero();
      detail::masked_covariance<Dims>(weight_, *present, w.masked_weight);
      // R̄ is positive definite with R (a principal block beside the identity).
      if (!w.masked_factor.compute(w.masked_weight)) return;
      factor = &w.masked_factor;
    }
    factor->solve_lower_transposed_on_the_right(w.weighted);
    // An entry beyond the range (φ near overflow against a small R) enters as the
    // largest finite number: the monitor then reports the overflow for L samples,
    // and I_t becomes non-finite, as its sum would.
    if (!detail::all_finite(w.weighted))
      w.weighted =
          w.weighted.unaryExpr([](Scalar v) { return std::isfinite(v) ? v : std::numeric_limits<Scalar>::max(); });
    /// (15) \f$I_t = I_{t-1} + \Phi^T\Phi\f$
    if (track_information_) detail::add_product(information_, w.weighted, w.weighted.transpose());
    if (excitation_) excitation_->add(w.weighted.transpose());
  }

  bool excitation_ready() const { return excitation_ && excitation_->full() && excitation_->available(); }

  Filters filters_;
  AdaptationLawType law_;
  State x0_;
  Bank bank_;                        // Σ_tᵀ
  typename Filters::Channels last_;  // [y_t; u_t], fed to the bank at the next sample
  State current_free_;               // F^t x̂_0
  Regressor phi_;                    // φ_t
  Output z_;                         // z_t
  Output prediction_error_;          // z_t − φ_tᵀ p̂_{t−1}
  State state_;                      // x̂_t (13)
  State next_state_;                 // x̂_{t+1|t}
  Index step_ = 0;
  HealthRecord<S> health_;
  bool track_information_;
  Information information_;  // I_t (15), 0 while off
  std::optional<ExcitationMonitor<Scalar, Dims::np>> excitation_;
  Weight weight_;  // the law's R (the identity for an unweighted law)
  detail::CholeskyFactor<Weight> weight_factor_;
  // Dynamic sizes keep their workspace allocated from construction on; fixed sizes use the stack.
  detail::UpdateWorkspace<Workspace, Dims::is_fixed> work_;
};

/// The Suzuki–Nakamura–Koga style observer of Dey & Bhasin (2022) §5: the same filters,
/// adapted by RLS with exponential forgetting (`ExponentialForgettingRls`).
template <typename S, int R, int Q, int M>
using SuzukiObserver = DeyBhasinObserver<S, R, Q, M, ExponentialForgettingRls>;

}  // namespace adaptobs
