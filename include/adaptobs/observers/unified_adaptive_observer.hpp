#pragma once
/// \file
/// The unified continuous-time adaptive observer of Zhang (2005), "Revisiting
/// different adaptive observers through a unified formulation" (docs/references.md).
///
/// An algorithm is a choice of
/// 1. a static transformation (T, K) bringing system (1) to the form (2)
///    \f$\dot x = A_ox + \varphi + \Psi\theta,\ y = C_ox\f$ (`StaticTransform`);
/// 2. a dynamic transformation (F, G, H), eq. (3): \f$\dot\Xi = F\Xi + G\Psi\f$,
///    \f$\Omega = H\Xi\f$, \f$z = x - \Omega\theta\f$ (`DynamicTransform`);
/// 3. an output-error gain L and a regressor R (m × p) for the update law
///    \f$\dot{\hat\theta} = \Gamma R^T\varepsilon\f$, \f$\varepsilon = y - C_o\hat x\f$.
///
/// | algorithm | L | R |
/// |---|---|---|
/// | 1, Bastin–Gevers (§III-A) | k | \f$\xi^T = a_{12}\Xi + \Psi_1\f$ |
/// | 2, Marino–Tomei (§III-B) | k | \f$\xi^T = \Xi_1 + \Psi_1\f$ |
/// | 3, Besançon (§III-C) | \f$[K_1; A_{21}(t)]\f$ | \f$A_{12}\Xi + \Psi_1\f$ |
/// | 4, Zhang 2002 (§III-D) | 0 (K is inside \f$A_o = A - KC\f$) | \f$C\Omega\f$ |
///
/// The paper writes each observer for \f$\hat z\f$, e.g. (Alg. 1–2)
/// \f$\dot{\hat z} = A_o\hat z + \varphi + \gamma\xi^T\hat\theta + k(y - c_o\hat z)\f$, with
/// \f$\hat x = \hat z + \Omega\hat\theta\f$. This class integrates the same observer in
/// the coordinates \f$\hat x\f$ directly: differentiating \f$\hat x = \hat z + H\Xi\hat\theta\f$
/// and using the bracket of (4a),
/// \f[ \dot{\hat x} = A_o\hat x + \varphi + \Psi\hat\theta + L\varepsilon + \Omega\dot{\hat\theta},\qquad
///     \dot{\hat\theta} = \Gamma R^T\varepsilon,\qquad \dot\Xi = F\Xi + G\Psi, \f]
/// valid for every (F, G, H) (the bracket never has to be formed), and
/// \f$\varepsilon = y - C_o\hat x = y - C_o\hat z - C_o\Omega\hat\theta\f$ is the
/// paper's output error in all four cases (\f$C_oH = 0\f$ for Alg. 1–3).
/// The estimate in the original coordinates is \f$\hat\eta = T^{-1}\hat x\f$.
///
/// The whole internal state \f$s = (\hat x, \mathrm{vec}\,\Xi, \hat\theta)\f$ is one
/// vector; `derivative(s, ds, t, u, y)` is its right-hand side, and
/// `odeint_system(observer, signals)` wraps it in the Boost.Odeint system signature. `update(sample)` advances it to
/// the sample's time with RK4 (`core/sampled_integration.hpp`).

#include <adaptobs/adaptation/gradient_law.hpp>
#include <adaptobs/core/continuous_model.hpp>
#include <adaptobs/core/continuous_update.hpp>
#include <adaptobs/core/detail/commit.hpp>
#include <adaptobs/core/detail/products.hpp>
#include <adaptobs/core/detail/segments.hpp>
#include <adaptobs/core/detail/update_workspace.hpp>
#include <adaptobs/core/dimensions.hpp>
#include <adaptobs/core/dynamic_transform.hpp>
#include <adaptobs/core/sampled_integration.hpp>
#include <adaptobs/core/static_transform.hpp>
#include <adaptobs/core/status.hpp>
#include <adaptobs/core/validation.hpp>
#include <adaptobs/diagnostics/excitation_monitor.hpp>

#include <Eigen/Core>

#include <concepts>
#include <limits>
#include <optional>
#include <string_view>
#include <utility>

namespace adaptobs {

/// What an algorithm of the unified formulation provides (see the file comment):
/// its transforms as data members, the gain L and the regressor R as functions
/// of the transformed system (2) at the current instant, and a check of its
/// own convergence conditions, run at construction.
template <class A, class D>
concept UnifiedAlgorithm =
    StateSpace<D> &&
    requires(const A& a, const TransformedSystem<D>& so, typename D::Scalar t, typename D::GainMatrix& L,
             const Eigen::Matrix<typename D::Scalar, A::filter_rows, D::np>& Xi,
             const typename D::RegressorMatrix& Omega, const typename D::RegressorMatrix& Psi,
             typename D::OutputRegressor& R, const Sizes& sizes) {
      { A::filter_rows } -> std::convertible_to<int>;
      { A::name } -> std::convertible_to<std::string_view>;
      { a.static_transform } -> std::convertible_to<const StaticTransform<D>&>;
      {
        a.dynamic_transform
      } -> std::convertible_to<const DynamicTransform<typename D::Scalar, D::nx, A::filter_rows>&>;
      a.injection_gain(so, t, L);
      a.regressor(so, Xi, Omega, Psi, R);
      a.check(so, sizes, true);
    };

/// Options of `UnifiedAdaptiveObserver`.
struct UnifiedObserverOptions {
  SamplingOptions sampling{};  ///< RK4 substeps and signal reconstruction between samples
  /// Window (in accepted samples) of the excitation monitor of \f$R^TR\f$
  /// (\f$\Omega^TC^TC\Omega\f$ of eq. (15) for Alg. 4); 0 turns it off.
  Index excitation_window = 0;
};

/// Continuous-time adaptive observer of the unified formulation, for any
/// `Algorithm` (Bastin–Gevers, Marino–Tomei, Besançon, Zhang, or a new variant)
/// and any parameter update law (`GradientLaw` by default).
///
/// \copydoc unified_adaptive_observer.hpp
template <ContinuousModel Model, UnifiedAlgorithm<typename Model::Dims> Algorithm,
          ContinuousAdaptationLaw<typename Model::Dims> Law = GradientLaw<typename Model::Dims>>
class UnifiedAdaptiveObserver
    : public ContinuousUpdate<UnifiedAdaptiveObserver<Model, Algorithm, Law>, typename Model::Dims> {
  friend ContinuousUpdate<UnifiedAdaptiveObserver, typename Model::Dims>;

 public:
  using Dims = typename Model::Dims;
  using typename Dims::Scalar, typename Dims::State, typename Dims::Parameters, typename Dims::Input,
      typename Dims::Output, typename Dims::RegressorMatrix, typename Dims::GainMatrix;
  using Sample = ContinuousSample<Dims>;
  static constexpr int nr = Algorithm::filter_rows;
  using FilterState = Eigen::Matrix<Scalar, nr, Dims::np>;  ///< Ξ
  using FilterMatrix = Eigen::Matrix<Scalar, nr, nr>;       ///< F
  static constexpr int internal_size = sum_of_sizes(sum_of_sizes(Dims::nx, product_of_sizes(nr, Dims::np)), Dims::np);
  /// \f$(\hat x, \mathrm{vec}\,\Xi, \hat\theta)\f$ stacked.
  using InternalState = Eigen::Matrix<Scalar, internal_size, 1>;
  static constexpr std::string_view name = Algorithm::name;
  static constexpr std::string_view name_reset = "UnifiedAdaptiveObserver::reset";

  /// \param eta0 initial estimate \f$\hat\eta(t_0)\f$ in the original coordinates;
  /// \param theta0 initial \f$\hat\theta(t_0)\f$. Ξ starts at 0. The time origin
  /// t₀ is the time of the first sample.
  UnifiedAdaptiveObserver(Model model, Algorithm algorithm, Law law, State eta0, Parameters theta0,
                          UnifiedObserverOptions options = {})
      : model_(std::move(model)),
        algorithm_(std::move(algorithm)),
        law_(std::move(law)),
        sizes_(model_.sizes()),
        r_(algorithm_.dynamic_transform.rows()),
        internal_(make_internal(sizes_, r_)),
        integrator_(internal_, sizes_, options.sampling, name) {
    constexpr std::string_view who = name;
    const Sizes& s = sizes_;
    require(s.np >= 1, who, "model", "must have at least one unknown parameter");
    require_shape(algorithm_.static_transform.T(), s.nx, s.nx, who, "static_transform.T");
    require_shape(algorithm_.static_transform.K(), s.nx, s.ny, who, "static_transform.K");
    if constexpr (requires { law_.gamma(); }) require_shape(law_.gamma(), s.np, s.np, who, "law.gamma");
    require(algorithm_.dynamic_transform.state_size() == s.nx, who, "dynamic_transform",
            "must act on a state of the model's size");
    require_initial_estimates(eta0, s.nx, theta0, s.np, who, "eta0", "theta0");
    require(options.excitation_window >= 0, who, "options.excitation_window", "must be non-negative");
    if (options.excitation_window > 0) excitation_.emplace(options.excitation_window, s.np);
    work_.resize(s, r_);
    output_error_.setZero(s.ny);
    refresh_time_invariant_system();
    // The algorithm's own convergence conditions (form of C_o, stability, SPR, ...).
    const TransformedSystem<Dims>& so0 = system_at(Scalar(0), work_);
    algorithm_.check(so0, s, is_time_invariant(model_));
    eta_ = eta0;
    theta_ = theta0;
    set_initial(eta0, theta0);
  }

  /// Right-hand side of the internal state at time t for the signals u(t), y(t).
  /// It writes only `ds`, so that threads may share one observer (and its
  /// `odeint_system`); with run-time sizes its scratch is allocated at each
  /// call (`update` keeps its own and allocates nothing).
  void derivative(const InternalState& s, InternalState& ds, Scalar t, const Input& u, const Output& y) const {
    Workspace w;
    w.resize(sizes_, r_);
    derivative(s, ds, t, u, y, nullptr, w);
  }

  /// \f$\hat x\f$ in the coordinates of system (2).
  [[nodiscard]] auto transformed_state() const { return detail::segment<Dims::nx>(internal_, 0, sizes_.nx); }
  /// Ξ of eq. (3a).
  [[nodiscard]] Eigen::Map<const FilterState> filter() const {
    return Eigen::Map<const FilterState>(internal_.data() + sizes_.nx, r_, sizes_.np);
  }
  /// \f$\Omega = H\Xi\f$ (eq. (3b)).
  [[nodiscard]] RegressorMatrix omega() const {
    RegressorMatrix omega(sizes_.nx, sizes_.np);
    algorithm_.dynamic_transform.output(filter(), omega);
    return omega;
  }
  /// \f$\hat z = \hat x - \Omega\hat\theta\f$ (the paper's observer state).
  [[nodiscard]] State transformed_estimate_z() const { return State(transformed_state() - omega() * theta_); }
  /// Matrices of (2) at time t.
  [[nodiscard]] TransformedSystem<Dims> transformed_system(Scalar t) const {
    Workspace w;
    w.resize(sizes_, r_);
    return system_at(t, w);
  }
  [[nodiscard]] const Algorithm& algorithm() const noexcept { return algorithm_; }
  [[nodiscard]] const Law& law() const noexcept { return law_; }
  [[nodiscard]] const Model& model() const noexcept { return model_; }

  /// Output injection K of the static transform from now on (e.g. the gain of a
  /// `RiccatiDifferentialEquation` at the current sample). With a time-invariant
  /// model the algorithm's conditions are checked again, as at construction: a K
  /// that breaks them (e.g. A − KC not Hurwitz) throws `ConfigurationError` and
  /// the observer keeps its previous K.
  void set_output_injection(const GainMatrix& K) {
    if (is_time_invariant(model_)) {
      const GainMatrix previous = algorithm_.static_transform.K();
      algorithm_.static_transform.set_output_injection(K);
      refresh_time_invariant_system();
      try {
        algorithm_.check(so_, sizes_, true);
      } catch (...) {
        algorithm_.static_transform.set_output_injection(previous);
        refresh_time_invariant_system();
        throw;
      }
    } else {
      algorithm_.static_transform.set_output_injection(K);
    }
  }

  /// Excitation level over the last window: the smallest eigenvalue of the
  /// average of \f$R^TR\f$ (for Alg. 4 \f$\Omega^TC^TC\Omega\f$, whose integral is
  /// the Gramian of eq. (15)); empty while the monitor is off, not full, or
  /// holding an overflowed contribution (`ExcitationMonitor::available`).
  [[nodiscard]] std::optional<Scalar> excitation_level() const {
    if (!excitation_ || !excitation_->full() || !excitation_->available()) return std::nullopt;
    return excitation_->level();
  }

  /// Its fields for `snapshot` and `restore` (core/snapshot.hpp): the model's
  /// matrices, the algorithm's transforms and gains, the law, the integrator's
  /// previous sample, the internal state (ẑ, Ξ, θ̂) and the diagnostics. The
  /// transformed system of a time-invariant model is computed again from them.
  static constexpr std::string_view snapshot_type = Algorithm::name;
  static constexpr int snapshot_version = 1;
  template <class Self, class Archive>
  static void visit_state(Self& self, Archive& archive) {
    archive.object("model", self.model_);
    archive.object("algorithm", self.algorithm_);
    archive.object("law", self.law_);
    archive.object("integrator", self.integrator_);
    archive("internal", self.internal_);
    archive("eta", self.eta_);
    archive("theta", self.theta_);
    archive("output_error", self.output_error_);
    archive.setting("excitation_window", self.excitation_ ? self.excitation_->window() : 0);
    if (self.excitation_) archive.object("excitation", *self.excitation_);
    UnifiedAdaptiveObserver::visit_update_state(self, archive);
    if constexpr (Archive::reading) self.refresh_time_invariant_system();
  }

 private:
  struct Workspace {
    TransformedSystem<Dims> so, so_measured;  // (2) at t; with the injection of measured channels only
    FilterMatrix F, F_measured;               // F(t), of so and of so_measured
    RegressorMatrix Psi, Omega;
    State phi;
    Output y, epsilon;  // y with its unmeasured channels predicted; ε
    typename Dims::OutputRegressor R;
    GainMatrix L;
    typename DynamicTransform<Scalar, Dims::nx, nr>::OutputMatrix AoH;  // A_o H of a projected F
    // The t at which so and F were computed, and the (t, u, y) at which Psi
    // was; NaN for none.
    Scalar so_t = std::numeric_limits<Scalar>::quiet_NaN();
    Scalar psi_t = std::numeric_limits<Scalar>::quiet_NaN();
    Input psi_u;
    Output psi_y;
    void resize(const Sizes& s, Index r) {
      so.resize(s);
      so_measured.resize(s);
      F.setZero(r, r);
      F_measured.setZero(r, r);
      AoH.setZero(s.nx, r);
      Psi.setZero(s.nx, s.np);
      Omega.setZero(s.nx, s.np);
      phi.setZero(s.nx);
      y.setZero(s.ny);
      epsilon.setZero(s.ny);
      R.setZero(s.ny, s.np);
      L.setZero(s.nx, s.ny);
      so_t = psi_t = std::numeric_limits<Scalar>::quiet_NaN();
      psi_u.setZero(s.nu);
      psi_y.setZero(s.ny);
    }
  };

  static InternalState make_internal(const Sizes& s, Index r) { return InternalState::Zero(s.nx + r * s.np + s.np); }

  // The matrices of (2) at t: the cached ones of a time-invariant model, else
  // computed into `w` (and F(t) with them), unless `w` holds them at this t
  // already (RK4's two midpoint stages share their time).
  const TransformedSystem<Dims>& system_at(Scalar t, Workspace& w) const {
    if (is_time_invariant(model_)) return so_;
    if (t == w.so_t) return w.so;
    algorithm_.static_transform.apply(model_.at(t), w.so);
    algorithm_.dynamic_transform.filter_matrix(w.so.Ao, w.F, w.AoH);
    w.so_t = t;
    return w.so;
  }

  // The right-hand side with the output channels in `measured` measured (all
  // for null) and the scratch `w` (the update's `work_`, or the public
  // overload's own). Unmeasured channels (docs/readings/continuous_gaps.md)
  // lose their output injection, K̄ = KD with D = diag(measured), in A_o, φ and
  // F, and their ε is 0; their y, where the regressor reads it, is the
  // prediction C_o x̂.
  void derivative(const InternalState& s, InternalState& ds, Scalar t, const Input& u, const Output& measured_y,
                  const OutputMask<Dims>* measured, Workspace& w) const {
    const Index n = sizes_.nx, p = sizes_.np;
    const auto x = detail::segment<Dims::nx>(s, 0, n);
    const Eigen::Map<const FilterState> Xi(s.data() + n, r_, p);
    const auto theta = detail::segment<Dims::np>(s, n + r_ * p, p);
    auto dx = detail::segment<Dims::nx>(ds, 0, n);
    Eigen::Map<FilterState> dXi(ds.data() + n, r_, p);
    auto dtheta = detail::segment<Dims::np>(ds, n + r_ * p, p);
    const auto& st = algorithm_.static_transform;
    const auto& dt = algorithm_.dynamic_transform;

    /// (2): \f$A_o, C_o\f$ at t, \f$\Psi = T\Phi\f$, \f$\varphi = TBu + Ky\f$.
    const TransformedSystem<Dims>& so = measured ? injecting_measured(system_at(t, w), *measured, w) : system_at(t, w);
    const Output& y = measured ? detail::predict_unmeasured<Dims>(so.Co, x, measured_y, *measured, w.y) : measured_y;
    transformed_regressor(t, u, y, w);
    st.drive(so, u, y, w.phi);
    /// (3b): \f$\Omega = H\Xi\f$; output error \f$\varepsilon = y - C_o\hat x\f$.
    dt.output(Xi, w.Omega);
    w.epsilon = y;
    detail::subtract_product(w.epsilon, so.Co, x);
    detail::zero_absent_rows<Dims>(w.epsilon, measured);
    /// Update law: \f$\dot{\hat\theta} = \Gamma R^T\varepsilon\f$ with the algorithm's R.
    algorithm_.regressor(so, Xi, w.Omega, w.Psi, w.R);
    detail::zero_absent_rows<Dims>(w.R, measured);  // the excitation of the measured channels only
    law_.derivative(w.R, w.epsilon, theta, dtheta);
    /// (3a): \f$\dot\Xi = F\Xi + G\Psi\f$.
    if (measured) dt.filter_matrix(so.Ao, w.F_measured, w.AoH);
    dt.derivative(measured ? w.F_measured : is_time_invariant(model_) ? f_ : w.F, Xi, w.Psi, dXi);
    /// \f$\dot{\hat x} = A_o\hat x + \varphi + \Psi\hat\theta + L\varepsilon + \Omega\dot{\hat\theta}\f$.
    algorithm_.injection_gain(so, t, w.L);
    detail::set_product(dx, so.Ao, x);
    dx += w.phi;
    detail::add_product(dx, w.Psi, theta);
    detail::add_product(dx, w.L, w.epsilon);
    detail::add_product(dx, w.Omega, dtheta);
  }

  // Ψ = TΦ(t, u, y) into w.Psi, unless it holds Ψ at this (t, u, y) already:
  // RK4's two midpoint stages share their time and signals, and Φ (sines and
  // cosines on the papers' plants) is the largest cost of a stage. The model's Φ
  // is a function of (t, u, y) (ContinuousModel).
  void transformed_regressor(Scalar t, const Input& u, const Output& y, Workspace& w) const {
    if (t == w.psi_t && u == w.psi_u && y == w.psi_y) return;
    algorithm_.static_transform.regressor(model_.regressor(t, u, y), w.Psi);
    w.psi_t = t;
    w.psi_u = u;
    w.psi_y = y;
  }

  // (2) with K̄ = KD: A_o + K(I − D)C_o and K̄, into w.so_measured.
  static const TransformedSystem<Dims>& injecting_measured(const TransformedSystem<Dims>& so,
                                                           const OutputMask<Dims>& measured, Workspace& w) {
    w.so_measured = so;
    for (Index i = 0; i < measured.size(); ++i) {
      if (measured(i)) continue;
      w.so_measured.Ao += so.K.col(i) * so.Co.row(i);
      w.so_measured.K.col(i).setZero();
    }
    return w.so_measured;
  }

  // No check of its own: every finite integrated state is accepted.
  UpdateStatus check_step(InternalState&) const noexcept { return UpdateStatus::accepted; }

  // No bound on the RK4 step: the first interval's step is taken as it comes
  // (core/sampled_integration.hpp; give SamplingOptions::max_step where it may be a gap).
  Scalar stable_step(const InternalState&, Scalar, const Input&, const Output&, const OutputMask<Dims>*,
                     Workspace&) const noexcept {
    return Scalar(0);
  }

  void refresh_time_invariant_system() {
    work_.so_t = work_.psi_t = std::numeric_limits<Scalar>::quiet_NaN();  // T or the model may have changed
    if (is_time_invariant(model_)) {
      so_.resize(sizes_);
      algorithm_.static_transform.apply(model_.at(Scalar(0)), so_);
      f_.setZero(r_, r_);
      algorithm_.dynamic_transform.filter_matrix(so_.Ao, f_, work_.AoH);
    }
  }

  // After an accepted sample: the excitation of the step just integrated (once
  // there was one) and ε(t_k) at the integrated estimate (work_.epsilon holds
  // the last RK4 stage's).
  void finish_update(const Sample& sample, const OutputMask<Dims>* present, bool stepping) {
    if (stepping && excitation_) excitation_->add(work_.R);
    output_error_ = sample.y;
    detail::subtract_product(output_error_, system_at(sample.t, work_).Co, transformed_state());
    detail::zero_absent_rows<Dims>(output_error_, present);
  }

  // Ξ = 0, and the excitation monitor empty.
  void set_initial(const State& eta0, const Parameters& theta0) {
    if (excitation_) excitation_->reset();
    internal_.setZero();
    detail::segment<Dims::nx>(internal_, 0, sizes_.nx) = algorithm_.static_transform.to_transformed(eta0);
    detail::segment<Dims::np>(internal_, sizes_.nx + r_ * sizes_.np, sizes_.np) = theta0;
    refresh_estimates();
  }

  void refresh_estimates() {
    algorithm_.static_transform.to_original(detail::segment<Dims::nx>(internal_, 0, sizes_.nx), eta_);
    theta_ = detail::segment<Dims::np>(internal_, sizes_.nx + r_ * sizes_.np, sizes_.np);
  }

  Model model_;
  Algorithm algorithm_;
  Law law_;
  Sizes sizes_;
  Index r_;
  InternalState internal_;
  SampledIntegrator<Dims, InternalState> integrator_;
  State eta_;
  Parameters theta_;
  Output output_error_;         // ε(t_k) of the last accepted sample
  TransformedSystem<Dims> so_;  // cached for a time-invariant model
  FilterMatrix f_;
  std::optional<ExcitationMonitor<Scalar, Dims::np>> excitation_;
  Workspace work_;
};

namespace detail {
/// The observer of a paper's algorithm with the gradient law of adaptation gain
/// Γ (np × np; a wrong shape is named `argument` in the algorithm's words): the
/// common end of the `make_*_observer` factories.
template <ContinuousModel Model, class Algorithm>
[[nodiscard]] UnifiedAdaptiveObserver<Model, Algorithm> make_gradient_observer(
    Model model, Algorithm algorithm, typename Model::Dims::ParameterMatrix gamma, std::string_view argument,
    typename Model::Dims::State eta0, typename Model::Dims::Parameters theta0, UnifiedObserverOptions options) {
  const Index np = model.sizes().np;
  require_shape(gamma, np, np, Algorithm::name, argument);
  return UnifiedAdaptiveObserver<Model, Algorithm>(std::move(model), std::move(algorithm),
                                                   GradientLaw<typename Model::Dims>(std::move(gamma)), std::move(eta0),
                                                   std::move(theta0), options);
}
}  // namespace detail

}  // namespace adaptobs
