#pragma once
/// \file
/// Time-varying Kalman gains \f$K_k\f$ from the Riccati difference equation.
///
/// Assumption 1 of Guyader & Zhang (2003) asks for a bounded \f$K_k\f$ making
/// \f$\eta_{k+1} = (A_k - K_k C_k)\eta_k\f$ exponentially stable; for a
/// uniformly completely observable pair \f$(A_k, C_k)\f$ the Kalman predictor
/// gain does it (Jazwinski 1970, quoted in Guyader & Zhang (2003) §2):
/// \f[ K_k = A_k P_k C_k^T (C_k P_k C_k^T + R)^{-1},\qquad
///     P_{k+1} = (A_k - K_k C_k) P_k (A_k - K_k C_k)^T + K_k R K_k^T + Q. \f]
/// The covariance is propagated in this Joseph-like form, a sum of positive
/// semidefinite terms, so it stays symmetric positive definite in floating point.

#include <adaptobs/core/detail/cholesky.hpp>
#include <adaptobs/core/dimensions.hpp>
#include <adaptobs/core/discrete_model.hpp>
#include <adaptobs/core/validation.hpp>
#include <adaptobs/design/kalman_covariances.hpp>

#include <Eigen/Core>

namespace adaptobs {

/// Runs the Riccati difference equation alongside a time-varying system and
/// hands out the predictor gain of each step.
template <StateSpace D>
class KalmanGainRecursion : public KalmanCovariances<D> {
  using Base = KalmanCovariances<D>;
  using Base::p_, Base::q_, Base::r_;

 public:
  using typename Base::Scalar, typename Base::StateMatrix, typename Base::GainMatrix, typename Base::OutputCovariance;

  /// \param P0 initial covariance (positive definite), \param Q state noise
  /// covariance (positive semidefinite), \param R output noise covariance (positive definite).
  KalmanGainRecursion(StateMatrix P0, StateMatrix Q, OutputCovariance R)
      : Base(std::move(P0), std::move(Q), std::move(R), "KalmanGainRecursion") {
    gain_.setZero(p_.rows(), r_.rows());
    s_.setZero(r_.rows(), r_.rows());
    closed_loop_.setZero(p_.rows(), p_.rows());
    next_.setZero(p_.rows(), p_.rows());
    scratch_.setZero(p_.rows(), p_.rows());
    cp_.setZero(r_.rows(), p_.rows());
    cpa_.setZero(r_.rows(), p_.rows());
    gain_r_.setZero(p_.rows(), r_.rows());
    s_factor_ = detail::CholeskyFactor<OutputCovariance>(r_.rows());
  }

  /// Gain \f$K_k\f$ for the matrices of step k; advances the covariance to \f$P_{k+1}\f$.
  /// A non-finite A or C throws `ConfigurationError` naming it, with nothing
  /// changed: a NaN would otherwise stay in P for every later step.
  const GainMatrix& next_gain(const DiscreteSystem<D>& system) {
    const auto& A = system.A;
    const auto& C = system.C;
    require_finite_shape(A, p_.rows(), p_.rows(), "KalmanGainRecursion::next_gain", "system.A");
    require_finite_shape(C, r_.rows(), p_.rows(), "KalmanGainRecursion::next_gain", "system.C");
    cp_.noalias() = C * p_;
    s_ = r_;
    s_.noalias() += cp_ * C.transpose();
    (void)s_factor_.compute(s_);  // R + CPCᵀ with R positive definite
    cpa_.noalias() = cp_ * A.transpose();
    gain_ = cpa_.transpose();
    s_factor_.solve_on_the_right_in_place(gain_);  // K = A P Cᵀ S⁻¹
    closed_loop_ = A;
    closed_loop_.noalias() -= gain_ * C;
    next_ = q_;
    scratch_.noalias() = closed_loop_ * p_;
    next_.noalias() += scratch_ * closed_loop_.transpose();
    gain_r_.noalias() = gain_ * r_;
    next_.noalias() += gain_r_ * gain_.transpose();
    p_ = Scalar(0.5) * (next_ + next_.transpose());
    return gain_;
  }

  [[nodiscard]] const GainMatrix& gain() const noexcept { return gain_; }

 private:
  GainMatrix gain_;
  // Workspace, sized once so that a step allocates nothing.
  OutputCovariance s_;
  detail::CholeskyFactor<OutputCovariance> s_factor_;
  StateMatrix closed_loop_;
  StateMatrix next_;
  StateMatrix scratch_;
  typename D::OutputMatrix cp_;
  typename D::OutputMatrix cpa_;
  GainMatrix gain_r_;
};

}  // namespace adaptobs
