#pragma once
/// \file
/// Kalman filter on the state augmented with the unknown parameters — the
/// classical alternative to an adaptive observer (Guyader & Zhang 2003, §1; Zhang 2005, appendix).
///
/// The extended system of the discrete model \f$x_{k+1} = A_kx_k + B_ku_k + f_k + \Psi_k\theta_k\f$,
/// \f$\theta_{k+1} = \theta_k\f$, \f$y_k = C_kx_k\f$ (\f$f_k\f$ the known input term of
/// `DiscreteSample::f`, zero when empty) is
/// \f[ \xi_{k+1} = \underbrace{\begin{bmatrix} A_k & \Psi_k \\ 0 & I\end{bmatrix}}_{F_k}\xi_k
///     + \begin{bmatrix} B_ku_k + f_k \\ 0\end{bmatrix},\qquad
///     y_k = \underbrace{\begin{bmatrix} C_k & 0\end{bmatrix}}_{H_k}\xi_k, \f]
/// time varying through \f$\Psi_k\f$ even for constant \f$(A, B, C)\f$. The known terms
/// \f$B_ku_k + f_k\f$ move the mean only, not the covariance. Each update
/// corrects with \f$y_k\f$ (covariance in Joseph form
/// \f$(I - LH)P(I - LH)^T + LRL^T\f$) and predicts to step k + 1.
///
/// **Missing and partial outputs.** A sample carrying only the channels of a
/// mask \f$D = \mathrm{diag}(\text{present})\f$ is corrected with the measured
/// sub-vector alone: \f$\bar H = [DC\ \ 0]\f$ and \f$\bar R = DRD + (I - D)\f$. The absent
/// channels' rows of \f$\bar H\f$ and entries of the innovation are zero and \f$\bar R\f$
/// decouples them, so \f$\bar S = \bar HP\bar H^T + \bar R\f$ is block diagonal, the gain's
/// absent columns are zero, and the step equals the Kalman correction with the
/// present rows of C and the present block of R. No channel present leaves
/// only the prediction.

#include <adaptobs/core/detail/cholesky.hpp>
#include <adaptobs/core/detail/commit.hpp>
#include <adaptobs/core/detail/products.hpp>
#include <adaptobs/core/detail/update_workspace.hpp>
#include <adaptobs/core/dimensions.hpp>
#include <adaptobs/core/discrete_model.hpp>
#include <adaptobs/core/discrete_update.hpp>
#include <adaptobs/core/snapshot.hpp>
#include <adaptobs/core/status.hpp>
#include <adaptobs/core/validation.hpp>

#include <Eigen/Core>

#include <string_view>
#include <utility>

namespace adaptobs {

/// Covariances of the augmented Kalman filter, of size (nx + np).
template <StateSpace D>
struct AugmentedKalmanCovariances {
  static constexpr int na = sum_of_sizes(D::nx, D::np);
  using AugmentedMatrix = Eigen::Matrix<typename D::Scalar, na, na>;
  AugmentedMatrix P0;                ///< initial covariance of [x; θ] (positive definite)
  AugmentedMatrix Q;                 ///< process noise of [x; θ] (positive semidefinite)
  typename D::OutputMatrixSquare R;  ///< output noise (positive definite)

  /// The checks both augmented filters make of their covariances, each named
  /// `covariances.<member>` in the error.
  void validate(const Sizes& s, std::string_view who) const {
    const Index n = s.nx + s.np;
    require_shape(P0, n, n, who, "covariances.P0");
    require_positive_definite(P0, who, "covariances.P0");
    require_shape(Q, n, n, who, "covariances.Q");
    require_positive_semidefinite(Q, who, "covariances.Q");
    require_shape(R, s.ny, s.ny, who, "covariances.R");
    require_positive_definite(R, who, "covariances.R");
  }
};

/// Kalman filter on the state augmented with the parameters (file comment).
/// Its `output_error()` is \f$\varepsilon_k = y_k - C_k\hat x_{k|k-1}\f$, the Kalman
/// innovation \f$y_k - H_k\hat\xi_{k|k-1}\f$ of the correction (before it).
///
/// \copydoc augmented_kalman.hpp
template <DiscreteModel Model>
class AugmentedKalmanFilter
    : public DiscreteUpdate<AugmentedKalmanFilter<Model>, typename Model::Dims, DiscreteSample> {
 public:
  ADAPTOBS_DISCRETE_UPDATE_INTERFACE(AugmentedKalmanFilter, DiscreteSample);
  /// No condition is checked per step: a covariance that turns indefinite is refused as `indefinite_covariance`.
  static constexpr CheckedAssumption checked_assumption{};
  using Covariances = AugmentedKalmanCovariances<Dims>;
  static constexpr int na = Covariances::na;
  using AugmentedVector = Eigen::Matrix<Scalar, na, 1>;
  using AugmentedMatrix = typename Covariances::AugmentedMatrix;

  AugmentedKalmanFilter(Model model, State x0, Parameters theta0, Covariances covariances)
      : model_(std::move(model)), x_(std::move(x0)), theta_(std::move(theta0)), cov_(std::move(covariances)) {
    constexpr std::string_view who = "AugmentedKalmanFilter";
    const Sizes s = model_.sizes();
    require_initial_estimates(x_, s.nx, theta_, s.np, who);
    cov_.validate(s, who);
    p_ = cov_.P0;
    this->output_error_.setZero(s.ny);
    work_.resize(s);
  }

  [[nodiscard]] const State& state() const noexcept { return x_; }
  /// Covariance of the augmented estimate [x̂; θ̂].
  [[nodiscard]] const AugmentedMatrix& covariance() const noexcept { return p_; }
  [[nodiscard]] const Covariances& covariances() const noexcept { return cov_; }

  /// Its fields for `snapshot` and `restore` (core/snapshot.hpp): the model,
  /// the covariances, the estimates and P.
  static constexpr std::string_view snapshot_type = "AugmentedKalmanFilter";
  static constexpr int snapshot_version = 1;
  template <class Self, class Archive>
    requires Snapshottable<Model>
  static void visit_state(Self& self, Archive& archive) {
    archive.object("model", self.model_);
    archive("P0", self.cov_.P0);
    archive("Q", self.cov_.Q);
    archive("R", self.cov_.R);
    archive("x", self.x_);
    archive("theta", self.theta_);
    archive("P", self.p_);
    AugmentedKalmanFilter::visit_update_state(self, archive);
  }

 private:
  // The rest of `reset`: the covariance back to P0.
  void restart(const State& x0, const Parameters& theta0) {
    x_ = x0;
    theta_ = theta0;
    p_ = cov_.P0;
  }

  // Kept between steps whatever the sizes: F_k's last rows [0 I] are written once.
  struct Workspace {
    AugmentedVector xi;
    AugmentedMatrix p, f, joseph, scratch;
    Eigen::Matrix<Scalar, na, Dims::ny> pht, gain;
    typename Dims::OutputMatrixSquare s, r_masked;
    typename Dims::OutputMatrix c_masked;
    detail::CholeskyFactor<typename Dims::OutputMatrixSquare> cholesky;
    typename Dims::Output innovation;
    State x;
    Parameters theta;
    void resize(const Sizes& sz) {
      const Index n = sz.nx + sz.np;
      xi.setZero(n);
      p.setZero(n, n);
      f.setZero(n, n);
      f.bottomRightCorner(sz.np, sz.np).setIdentity();
      joseph.setZero(n, n);
      scratch.setZero(n, n);
      pht.setZero(n, sz.ny);
      gain.setZero(n, sz.ny);
      s.setZero(sz.ny, sz.ny);
      r_masked.setZero(sz.ny, sz.ny);
      c_masked.setZero(sz.ny, sz.nx);
      innovation.setZero(sz.ny);
      x.setZero(sz.nx);
      theta.setZero(sz.np);
      cholesky = detail::CholeskyFactor<typename Dims::OutputMatrixSquare>(sz.ny);
    }
  };

  /// Correction with \f$y_k\f$, then prediction to step k + 1 with
  /// \f$(A_k, B_k, \Psi_k, u_k, f_k)\f$; `present` is null when every channel is. A step
  /// whose covariance would not be positive definite is rejected
  /// (`UpdateStatus::indefinite_covariance`) and changes nothing.
  UpdateStatus advance(const Sample& sample, const OutputMask<Dims>* present, Workspace& w) {
    const auto& system = model_.at(this->step());
    this->check_system_sizes(system);
    const Index nx = x_.rows();

    // C̄ = DC and R̄ = DRD + (I − D) with a mask; C and R without.
    if (present) {
      w.c_masked = system.C;
      detail::zero_absent_rows<Dims>(w.c_masked, present);
      detail::masked_covariance<Dims>(cov_.R, *present, w.r_masked);
    }
    const typename Dims::OutputMatrix& c = present ? w.c_masked : system.C;
    const typename Dims::OutputMatrixSquare& r = present ? w.r_masked : cov_.R;

    // Correction: S = C Pxx Cᵀ + R, L = P Hᵀ S⁻¹ with H = [C 0].
    detail::set_product(w.pht, p_.leftCols(nx), c.transpose());
    w.s = r;
    detail::add_product(w.s, c, w.pht.topRows(nx));
    if (!w.cholesky.compute(w.s)) return UpdateStatus::nonfinite_result;
    w.gain = w.pht;
    w.cholesky.solve_on_the_right_in_place(w.gain);  // L = P Hᵀ S⁻¹
    w.innovation = sample.y;
    detail::subtract_product(w.innovation, c, x_);
    detail::zero_absent_rows<Dims>(w.innovation, present);
    w.xi.head(nx) = x_;
    w.xi.tail(theta_.rows()) = theta_;
    detail::add_product(w.xi, w.gain, w.innovation);
    // Joseph form: P⁺ = (I − L H) P (I − L H)ᵀ + L R Lᵀ.
    w.joseph.setIdentity();
    detail::subtract_product(w.joseph.leftCols(nx), w.gain, c);
    detail::set_product(w.scratch, w.joseph, p_);
    detail::set_product(w.p, w.scratch, w.joseph.transpose());
    detail::set_product(w.pht, w.gain, r);  // reuse as L R
    detail::add_product(w.p, w.pht, w.gain.transpose());

    // Prediction with F_k = [A Ψ; 0 I]: x̂_{k+1|k} = A x̂_{k|k} + Ψ θ̂_{k|k} + B u_k + f_k.
    w.f.topLeftCorner(nx, nx) = system.A;
    w.f.topRightCorner(nx, theta_.rows()) = sample.Psi;
    detail::set_product(w.x, system.A, w.xi.head(nx));
    detail::add_product(w.x, sample.Psi, w.xi.tail(theta_.rows()));
    detail::add_product(w.x, system.B, sample.u);
    detail::add_known_input(w.x, sample.f);
    w.theta = w.xi.tail(theta_.rows());
    detail::set_product(w.scratch, w.f, w.p);
    detail::set_product(w.p, w.scratch, w.f.transpose());
    w.p += cov_.Q;
    w.scratch = Scalar(0.5) * (w.p + w.p.transpose());

    if (!detail::all_finite(w.x, w.theta, w.scratch)) return UpdateStatus::nonfinite_result;
    // A covariance that lost definiteness, e.g. to rounding under a regressor of 1e150
    // whose Ψ P Ψᵀ dwarfs the rest, would poison every later step: P⁺ must have a
    // Cholesky factor (about (n+p)³/6 flops, in the no longer needed Joseph workspace).
    w.joseph = w.scratch;
    if (!detail::cholesky_in_place(w.joseph)) return UpdateStatus::indefinite_covariance;
    detail::commit(x_, w.x);
    detail::commit(theta_, w.theta);
    detail::commit(p_, w.scratch);
    detail::commit(this->output_error_, w.innovation);
    return UpdateStatus::accepted;
  }

  Model model_;
  State x_;
  Parameters theta_;
  Covariances cov_;
  AugmentedMatrix p_;
  detail::UpdateWorkspace<Workspace, false> work_;
};

}  // namespace adaptobs
