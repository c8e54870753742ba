#pragma once
/// \file
/// Time-varying Kalman–Bucy gains from the Riccati differential equation.
///
/// Algorithm 4 of paper 001 (§III-D) needs K(t) making \f$A(t) - K(t)C(t)\f$
/// exponentially stable; "typically such a K(t) is computed with the aid of a
/// dynamic Riccati equation like in the Kalman filter":
/// \f[ \dot P = A P + P A^T + Q - P C^T R^{-1} C P,\qquad K = P C^T R^{-1}, \f]
/// with Q ≥ 0, R > 0. For a uniformly completely observable (A(t), C(t)) (and
/// (A, Q^{1/2}) uniformly controllable) P stays bounded and positive definite and
/// \f$A - KC\f$ is exponentially stable (Kalman–Bucy 1961).
/// P is advanced with RK4 between samples and re-symmetrized after each step;
/// a fixed-size step allocates nothing.

#include <adaptobs/core/continuous_model.hpp>
#include <adaptobs/core/dimensions.hpp>
#include <adaptobs/core/runge_kutta.hpp>
#include <adaptobs/core/validation.hpp>

#include <Eigen/Cholesky>
#include <Eigen/Core>

#include <utility>

namespace adaptobs {

template <StateSpace D>
class RiccatiDifferentialEquation : public SizedBy<D> {
 public:
  using Scalar = typename D::Scalar;
  using StateMatrix = typename D::StateMatrix;
  using OutputCovariance = typename D::OutputMatrixSquare;
  using GainMatrix = typename D::GainMatrix;

  /// \param P0 initial P (positive definite), \param Q ≥ 0, \param R > 0.
  RiccatiDifferentialEquation(StateMatrix P0, StateMatrix Q, OutputCovariance R)
      : p_(std::move(P0)), q_(std::move(Q)), r_(std::move(R)), rk4_(p_) {
    constexpr std::string_view who = "RiccatiDifferentialEquation";
    detail::require_positive_definite(p_, who, "P0");
    detail::require_shape(q_, p_.rows(), p_.rows(), who, "Q");
    detail::require_positive_semidefinite(q_, who, "Q");
    detail::require_positive_definite(r_, who, "R");
    llt_.compute(r_);
    cp_.setZero(r_.rows(), p_.rows());
    r_inv_cp_.setZero(r_.rows(), p_.rows());
    gain_.setZero(p_.rows(), r_.rows());
  }

  /// Advances P from t0 to t1 along the model's (A(t), C(t)) with `steps` RK4 steps.
  template <ContinuousModel Model>
  void advance(const Model& model, Scalar t0, Scalar t1, int steps = 1) {
    rk4_.integrate(
        [&](const StateMatrix& p, StateMatrix& dp, Scalar t) {
          decltype(auto) s = model.at(t);
          derivative(s.A, s.C, p, dp);
        },
        p_, t0, t1, steps);
    p_ = Scalar(0.5) * (p_ + p_.transpose()).eval();
  }

  /// \f$\dot P = AP + PA^T + Q - PC^TR^{-1}CP\f$.
  template <class DA, class DC>
  void derivative(const Eigen::MatrixBase<DA>& A, const Eigen::MatrixBase<DC>& C, const StateMatrix& p,
                  StateMatrix& dp) const {
    cp_.noalias() = C * p;
    r_inv_cp_ = llt_.solve(cp_);
    dp = q_;
    dp.noalias() += A * p;
    dp.noalias() += p * A.transpose();
    dp.noalias() -= cp_.transpose() * r_inv_cp_;
  }

  /// \f$K = PC^TR^{-1}\f$ for the output matrix C of the current instant.
  template <class DC>
  const GainMatrix& gain(const Eigen::MatrixBase<DC>& C) {
    cp_.noalias() = C * p_;
    gain_.transpose() = llt_.solve(cp_);
    return gain_;
  }

  [[nodiscard]] const StateMatrix& covariance() const noexcept { return p_; }

 private:
  StateMatrix p_;
  StateMatrix q_;
  OutputCovariance r_;
  Eigen::LLT<OutputCovariance> llt_;
  RungeKutta4<StateMatrix> rk4_;
  mutable typename D::OutputMatrix cp_, r_inv_cp_;
  GainMatrix gain_;
};

}  // namespace adaptobs
