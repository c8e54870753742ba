#pragma once
/// \file
/// Kalman–Bucy filter on the state augmented with the unknown parameters — the
/// continuous-time baseline of the unified observers (Zhang 2005, appendix, system (16)).
///
/// For \f$\dot\eta = A\eta + Bu + \Phi\theta\f$, \f$\dot\theta = 0\f$, \f$y = C\eta\f$, the extended system
/// \f$\dot\chi = A_e\chi + [Bu; 0]\f$, \f$y = C_e\chi\f$ with
/// \f$A_e = \begin{bmatrix} A & \Phi(t)\\ 0 & 0\end{bmatrix}\f$, \f$C_e = [C\ 0]\f$ is time varying
/// through Φ even for a constant (A, C). The filter
/// \f[ \dot{\hat\chi} = A_e\hat\chi + \begin{bmatrix} Bu\\ 0\end{bmatrix} + L(y - C_e\hat\chi),\quad L = PC_e^TR^{-1},\qquad
///     \dot P = A_eP + PA_e^T + Q - PC_e^TR^{-1}C_eP \f]
/// converges when the extended pair is uniformly observable (the Gramian W(t, s)
/// of the appendix is uniformly positive definite) — and exponentially only with
/// a parameter noise density \f$Q_\theta > 0\f$: with \f$Q_\theta = 0\f$ the gain dies
/// out as P → 0 and \f$\tilde\theta\f$ decays like 1/t. It costs an (n + p)² Riccati
/// equation against the n × n one (or none) of the adaptive observers.
/// The filter works in the original coordinates and is stepped like them
/// (`core/sampled_integration.hpp`); P is re-symmetrized after every sample,
/// and a sample whose step would leave P not positive definite is rejected.
///
/// **The first interval.** Left to learn its step limit (`SamplingOptions::max_step`
/// = 0), the filter bounds the step by its own dynamics until it has learned
/// one: linearized at (t, χ̂, P), the right-hand side has the Jacobian
/// \f$\delta\dot\chi = M\delta\chi\f$, \f$\delta\dot P = M\delta P + \delta PM^T\f$ with
/// \f$M = A_e - LC_e\f$, whose eigenvalues \f$\lambda_i(M)\f$ and \f$\lambda_i(M) + \lambda_j(M)\f$
/// are all within \f$2\|M\|_F\f$ of 0. RK4 is stable for hλ in the left half-disc
/// of radius 2.6, so a step \f$h \le 1/\|M\|_F\f$ keeps every mode inside it with a
/// margin of 1.3 for P's change over the interval. A first interval that is a
/// gap is crossed in such steps and teaches nothing; the limit is learned
/// (1.25 times the step) from the first interval that needs no more than
/// `substeps` of them. Otherwise one RK4 step across a first gap would leave P
/// indefinite, and every later interval, longer still, would be rejected.

#include <adaptobs/baselines/augmented_kalman.hpp>
#include <adaptobs/core/continuous_model.hpp>
#include <adaptobs/core/continuous_update.hpp>
#include <adaptobs/core/detail/cholesky.hpp>
#include <adaptobs/core/detail/commit.hpp>
#include <adaptobs/core/detail/products.hpp>
#include <adaptobs/core/detail/segments.hpp>
#include <adaptobs/core/detail/update_workspace.hpp>
#include <adaptobs/core/dimensions.hpp>
#include <adaptobs/core/sampled_integration.hpp>
#include <adaptobs/core/snapshot.hpp>
#include <adaptobs/core/status.hpp>
#include <adaptobs/core/validation.hpp>

#include <Eigen/Core>

#include <string_view>
#include <utility>

namespace adaptobs {

/// Kalman–Bucy filter on the state augmented with θ, over a continuous model.
///
/// \copydoc kalman_bucy.hpp
template <ContinuousModel Model>
class AugmentedKalmanBucyFilter : public ContinuousUpdate<AugmentedKalmanBucyFilter<Model>, typename Model::Dims> {
  friend ContinuousUpdate<AugmentedKalmanBucyFilter, typename Model::Dims>;

 public:
  using Dims = typename Model::Dims;
  using typename Dims::Scalar, typename Dims::State, typename Dims::Parameters, typename Dims::Input,
      typename Dims::Output;
  using Sample = ContinuousSample<Dims>;
  /// P0, Q (spectral density of the noise on [x; θ]) and R (on y).
  using Covariances = AugmentedKalmanCovariances<Dims>;
  static constexpr int na = Covariances::na;
  using AugmentedMatrix = typename Covariances::AugmentedMatrix;
  static constexpr int internal_size = sum_of_sizes(na, product_of_sizes(na, na));
  /// \f$(\hat x, \hat\theta, \mathrm{vec}\,P)\f$ stacked.
  using InternalState = Eigen::Matrix<Scalar, internal_size, 1>;
  static constexpr std::string_view name = "AugmentedKalmanBucyFilter";
  static constexpr std::string_view name_reset = "AugmentedKalmanBucyFilter::reset";

  AugmentedKalmanBucyFilter(Model model, State eta0, Parameters theta0, Covariances covariances,
                            SamplingOptions options = {})
      : model_(std::move(model)),
        sizes_(model_.sizes()),
        cov_(std::move(covariances)),
        internal_(InternalState::Zero((sizes_.nx + sizes_.np) * (1 + sizes_.nx + sizes_.np))),
        integrator_(internal_, sizes_, options, name) {
    const Sizes& s = sizes_;
    require_initial_estimates(eta0, s.nx, theta0, s.np, name, "eta0", "theta0");
    cov_.validate(s, name);
    (void)r_factor_.compute(cov_.R);  // positive definite: checked above
    work_.resize(s);
    output_error_.setZero(s.ny);
    eta_ = eta0;
    theta_ = theta0;
    set_initial(eta0, theta0);
  }

  /// Right-hand side of \f$(\hat x, \hat\theta, P)\f$ (see the file comment). It
  /// writes only `ds`, so that threads may share one filter (and its
  /// `odeint_system`); with run-time sizes its scratch is allocated at each
  /// call (`update` keeps its own and allocates nothing).
  void derivative(const InternalState& s, InternalState& ds, Scalar t, const Input& u, const Output& y) const {
    Workspace w;
    w.resize(sizes_);
    derivative(s, ds, t, u, y, nullptr, w);
  }

  /// Covariance P of \f$[\hat x; \hat\theta]\f$.
  [[nodiscard]] AugmentedMatrix covariance() const {
    const Index n = sizes_.nx + sizes_.np;
    return Eigen::Map<const AugmentedMatrix>(internal_.data() + n, n, n);
  }

  [[nodiscard]] const Model& model() const noexcept { return model_; }

  /// Its fields for `snapshot` and `restore` (core/snapshot.hpp): the model's
  /// matrices, the covariances, the integrator's previous sample and the
  /// internal state \f$(\hat x, \hat\theta, P)\f$; R's factor is computed again.
  static constexpr std::string_view snapshot_type = name;
  static constexpr int snapshot_version = 1;
  template <class Self, class Archive>
    requires Snapshottable<Model>
  static void visit_state(Self& self, Archive& archive) {
    archive.object("model", self.model_);
    archive("P0", self.cov_.P0);
    archive("Q", self.cov_.Q);
    archive("R", self.cov_.R);
    archive.object("integrator", self.integrator_);
    archive("internal", self.internal_);
    archive("eta", self.eta_);
    archive("theta", self.theta_);
    archive("output_error", self.output_error_);
    AugmentedKalmanBucyFilter::visit_update_state(self, archive);
    if constexpr (Archive::reading) {
      require(self.r_factor_.compute(self.cov_.R), "restore", "snapshot", "holds an R that is not positive definite");
      self.work_.has_masked_factor = false;  // R̄ is factored again from the restored R
    }
  }

 private:
  struct Workspace {
    AugmentedMatrix ae, factor;   // A_e (its last np rows stay 0); P's Cholesky factor in check_step
    AugmentedMatrix closed_loop;  // A_e − LC_e, in stable_step
    Eigen::Matrix<Scalar, na, Dims::ny> pct, gain;
    Output y, epsilon;  // y with its unmeasured channels predicted; ε
    // With unmeasured channels: C̄ = DC, and the factor of R̄ = DRD + (I − D) for the mask `factored`.
    typename Dims::OutputMatrix c_masked;
    typename Dims::OutputMatrixSquare r_masked;
    detail::CholeskyFactor<typename Dims::OutputMatrixSquare> r_masked_factor;
    OutputMask<Dims> factored;  // the mask of r_masked_factor, once `has_masked_factor`
    bool has_masked_factor = false;
    void resize(const Sizes& s) {
      const Index n = s.nx + s.np;
      ae.setZero(n, n);
      factor.setZero(n, n);
      closed_loop.setZero(n, n);
      pct.setZero(n, s.ny);
      gain.setZero(n, s.ny);
      y.setZero(s.ny);
      epsilon.setZero(s.ny);
      c_masked.setZero(s.ny, s.nx);
      r_masked.setZero(s.ny, s.ny);
      r_masked_factor = detail::CholeskyFactor<typename Dims::OutputMatrixSquare>(s.ny);
      factored.setConstant(s.ny, true);
    }
  };

  // The right-hand side with the output channels in `measured` measured (all
  // for null) and the scratch `w` (the update's `work_`, or the public
  // overload's own). An unmeasured channel has no measurement term
  // (docs/readings/continuous_gaps.md): the gain is that of C̄ = DC and
  // R̄ = DRD + (I − D), D = diag(measured), as in the discrete filter, so that
  // its columns for those channels are 0 and P follows Ṗ = A_e P + P A_eᵀ + Q
  // where no channel is measured. Where the regressor reads y, an unmeasured
  // channel's y is the prediction C x̂.
  void derivative(const InternalState& s, InternalState& ds, Scalar t, const Input& u, const Output& measured_y,
                  const OutputMask<Dims>* measured, Workspace& w) const {
    const Index nx = sizes_.nx, np = sizes_.np, n = nx + np;
    const auto x = detail::segment<Dims::nx>(s, 0, nx);
    const auto theta = detail::segment<Dims::np>(s, nx, np);
    const Eigen::Map<const AugmentedMatrix> P(s.data() + n, n, n);
    auto dx = detail::segment<Dims::nx>(ds, 0, nx);
    auto dtheta = detail::segment<Dims::np>(ds, nx, np);
    Eigen::Map<AugmentedMatrix> dP(ds.data() + n, n, n);
    decltype(auto) sys = model_.at(t);
    const Output& y = measurement(s, t, u, measured_y, measured, sys, w);
    const typename Dims::OutputMatrix& c = measured ? w.c_masked : sys.C;
    w.epsilon = y;
    detail::subtract_product(w.epsilon, c, x);
    detail::zero_absent_rows<Dims>(w.epsilon, measured);
    detail::set_product(dx, sys.A, x);
    detail::add_product(dx, sys.B, u);
    detail::add_product(dx, w.ae.topRightCorner(nx, np), theta);
    detail::add_product(dx, w.gain.topRows(nx), w.epsilon);
    detail::set_product(dtheta, w.gain.bottomRows(np), w.epsilon);
    dP = cov_.Q;
    detail::add_product(dP, w.ae, P);
    detail::add_product(dP, P, w.ae.transpose());
    detail::subtract_product(dP, w.gain, w.pct.transpose());
  }

  // The measurement part of the right-hand side at t, into `w`: A_e = [A Φ; 0 0]
  // (w.ae), C̄ (w.c_masked, with a mask), P C̄ᵀ (w.pct) and the gain
  // L = P C̄ᵀ R̄⁻¹ (w.gain). Returns y with its unmeasured channels predicted
  // (C x̂), the y the regressor reads.
  template <class SystemAt>
  const Output& measurement(const InternalState& s, Scalar t, const Input& u, const Output& measured_y,
                            const OutputMask<Dims>* measured, const SystemAt& sys, Workspace& w) const {
    const Index nx = sizes_.nx, np = sizes_.np, n = nx + np;
    const auto x = detail::segment<Dims::nx>(s, 0, nx);
    const Eigen::Map<const AugmentedMatrix> P(s.data() + n, n, n);
    if (measured) {
      detail::predict_unmeasured<Dims>(sys.C, x, measured_y, *measured, w.y);
      w.c_masked = sys.C;
      detail::zero_absent_rows<Dims>(w.c_masked, measured);
    }
    const Output& y = measured ? w.y : measured_y;
    w.ae.topLeftCorner(nx, nx) = sys.A;
    w.ae.topRightCorner(nx, np) = model_.regressor(t, u, y);
    // L = P C_eᵀ R⁻¹ with C_e = [C 0] (C̄ and R̄ for unmeasured channels).
    const typename Dims::OutputMatrix& c = measured ? w.c_masked : sys.C;
    detail::set_product(w.pct, P.leftCols(nx), c.transpose());
    w.gain = w.pct;
    masked_r_factor(measured, w).solve_on_the_right_in_place(w.gain);
    return y;
  }

  // The RK4 step the filter's dynamics at (t, χ̂, P) allow, 1/‖A_e − LC̄_e‖_F (file
  // comment): the bound on the steps of an interval while no limit is known.
  Scalar stable_step(const InternalState& s, Scalar t, const Input& u, const Output& y,
                     const OutputMask<Dims>* measured, Workspace& w) const {
    const Index nx = sizes_.nx;
    decltype(auto) sys = model_.at(t);
    (void)measurement(s, t, u, y, measured, sys, w);
    w.closed_loop = w.ae;
    detail::subtract_product(w.closed_loop.leftCols(nx), w.gain, measured ? w.c_masked : sys.C);
    return Scalar(1) / w.closed_loop.norm();
  }

  // P of an integrated step made exactly symmetric, then tested by a Cholesky
  // factorization: RK4 on the Riccati equation keeps P neither symmetric nor,
  // with a step too long for its dynamics, positive definite. A step that would
  // leave it so is rejected as `UpdateStatus::indefinite_covariance`.
  UpdateStatus check_step(InternalState& candidate) {
    const Index n = sizes_.nx + sizes_.np;
    Eigen::Map<AugmentedMatrix> p(candidate.data() + n, n, n);
    for (Index j = 0; j < n; ++j)
      for (Index i = j + 1; i < n; ++i) p(i, j) = p(j, i) = Scalar(0.5) * (p(i, j) + p(j, i));
    work_.factor = p;
    return detail::cholesky_in_place(work_.factor) ? UpdateStatus::accepted : UpdateStatus::indefinite_covariance;
  }

  auto covariance_map() {
    const Index n = sizes_.nx + sizes_.np;
    return Eigen::Map<AugmentedMatrix>(internal_.data() + n, n, n);
  }

  void set_initial(const State& eta0, const Parameters& theta0) {
    detail::segment<Dims::nx>(internal_, 0, sizes_.nx) = eta0;
    detail::segment<Dims::np>(internal_, sizes_.nx, sizes_.np) = theta0;
    covariance_map() = cov_.P0;
    refresh_estimates();
  }

  // The output error \f$y_k - C_e\hat\chi(t_k)\f$ at the integrated estimate
  // (work_.epsilon holds the last RK4 stage's).
  void finish_update(const Sample& sample, const OutputMask<Dims>* present, bool) {
    output_error_ = sample.y;
    detail::subtract_product(output_error_, model_.at(sample.t).C, eta_);
    detail::zero_absent_rows<Dims>(output_error_, present);
  }

  // The factor of R, or of R̄ = DRD + (I − D) for a mask, computed once per mask
  // (R̄ is positive definite with R).
  const detail::CholeskyFactor<typename Dims::OutputMatrixSquare>& masked_r_factor(const OutputMask<Dims>* measured,
                                                                                   Workspace& w) const {
    if (!measured) return r_factor_;
    if (!w.has_masked_factor || !(w.factored == *measured).all()) {
      detail::masked_covariance<Dims>(cov_.R, *measured, w.r_masked);
      (void)w.r_masked_factor.compute(w.r_masked);
      w.factored = *measured;
      w.has_masked_factor = true;
    }
    return w.r_masked_factor;
  }

  void refresh_estimates() {
    eta_ = detail::segment<Dims::nx>(internal_, 0, sizes_.nx);
    theta_ = detail::segment<Dims::np>(internal_, sizes_.nx, sizes_.np);
  }

  Model model_;
  Sizes sizes_;
  Covariances cov_;
  InternalState internal_;
  SampledIntegrator<Dims, InternalState> integrator_;
  detail::CholeskyFactor<typename Dims::OutputMatrixSquare> r_factor_;  // of R
  State eta_;
  Parameters theta_;
  Output output_error_;  // ε(t_k) of the last accepted sample
  Workspace work_;
};

}  // namespace adaptobs
