#pragma once
/// \file
/// Time-varying Kalman–Bucy gains from the Riccati differential equation.
///
/// Algorithm 4 of Zhang (2005, §III-D) needs K(t) making \f$A(t) - K(t)C(t)\f$
/// exponentially stable; "typically such a K(t) is computed with the aid of a
/// dynamic Riccati equation like in the Kalman filter":
/// \f[ \dot P = A P + P A^T + Q - P C^T R^{-1} C P,\qquad K = P C^T R^{-1}, \f]
/// with Q ≥ 0, R > 0. For a uniformly completely observable (A(t), C(t)) (and
/// (A, Q^{1/2}) uniformly controllable) P stays bounded and positive definite and
/// \f$A - KC\f$ is exponentially stable (Kalman–Bucy 1961).
/// P is advanced with RK4 between samples and re-symmetrized after each step;
/// a fixed-size step allocates nothing.
///
/// Step length. Linearized about P, the equation is the Lyapunov flow
/// \f$\dot E = A_cE + EA_c^T\f$ with \f$A_c = A - KC\f$, whose eigenvalues
/// \f$\lambda_i + \lambda_j\f$ of \f$A_c\f$ are bounded by \f$2\|A_c\|_F\f$ in modulus. RK4 is
/// stable for \f$h|\lambda| \le 2.78\f$ on the negative real axis, so each step is at most
/// \f$2.5 / (2\|A_c\|_F)\f$, with \f$A_c\f$ taken at the step's start: a long interval
/// is crossed in as many steps as its stiffness needs, whatever the caller asks.

#include <adaptobs/core/continuous_model.hpp>
#include <adaptobs/core/detail/cholesky.hpp>
#include <adaptobs/core/dimensions.hpp>
#include <adaptobs/core/runge_kutta.hpp>
#include <adaptobs/core/validation.hpp>
#include <adaptobs/design/kalman_covariances.hpp>

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string_view>
#include <utility>

namespace adaptobs {

template <StateSpace D>
class RiccatiDifferentialEquation : public KalmanCovariances<D> {
  using Base = KalmanCovariances<D>;
  using Base::p_, Base::q_, Base::r_;

 public:
  using typename Base::Scalar, typename Base::StateMatrix, typename Base::GainMatrix, typename Base::OutputCovariance;

  /// \param P0 initial P (positive definite), \param Q ≥ 0, \param R > 0.
  RiccatiDifferentialEquation(StateMatrix P0, StateMatrix Q, OutputCovariance R)
      : Base(std::move(P0), std::move(Q), std::move(R), "RiccatiDifferentialEquation"), rk4_(p_) {
    (void)r_factor_.compute(r_);  // positive definite: checked above
    cp_.setZero(r_.rows(), p_.rows());
    r_inv_cp_.setZero(r_.rows(), p_.rows());
    gain_.setZero(p_.rows(), r_.rows());
    closed_loop_.setZero(p_.rows(), p_.rows());
    trial_.setZero(p_.rows(), p_.rows());
  }

  /// Advances P from t0 to t1 along the model's (A(t), C(t)) with at least
  /// `min_steps` RK4 steps, more where the stability bound of the file comment
  /// asks for shorter ones. Returns the number of steps taken.
  /// A model giving non-finite matrices anywhere on the way (at a step's start
  /// or at an RK4 stage), or a P that leaves the floating-point range, throws a
  /// `ConfigurationError` naming `model` and leaves P as it was.
  template <ContinuousModel Model>
  int advance(const Model& model, Scalar t0, Scalar t1, int min_steps = 1) {
    constexpr std::string_view who = "RiccatiDifferentialEquation::advance";
    require(min_steps >= 1, who, "min_steps", "must be at least 1");
    require(std::isfinite(t0) && std::isfinite(t1) && t1 >= t0, who, "t1", "must be finite and not before t0");
    const auto field = [&](const StateMatrix& p, StateMatrix& dp, Scalar t) {
      decltype(auto) s = model.at(t);
      derivative(s.A, s.C, p, dp, cp_, r_inv_cp_);
    };
    const Scalar nominal = (t1 - t0) / Scalar(min_steps);
    trial_ = p_;  // P moves only once the whole interval is crossed
    int steps = 0;
    for (Scalar t = t0; t < t1; ++steps) {
      decltype(auto) s = model.at(t);
      closed_loop_ = s.A;
      closed_loop_.noalias() -= gain_of(s.C, trial_) * s.C;
      const Scalar rate = Scalar(2) * closed_loop_.norm();
      if (!std::isfinite(rate)) fail_argument(who, "model", "gives a non-finite A - KC (or P is not finite)");
      Scalar h = std::min(nominal, t1 - t);
      if (rate * h > Scalar(2.5)) h = Scalar(2.5) / rate;
      // The last step lands on t1 exactly: a remainder within the rounding that
      // the sum of the steps accumulates joins it instead of making a step of its own.
      const Scalar slack = std::max(Scalar(1e-6), Scalar(1000) * std::numeric_limits<Scalar>::epsilon()) * h;
      const Scalar next = t1 - t <= h + slack ? t1 : t + h;
      if (!(next > t)) fail_argument(who, "model", "gives a Riccati equation too stiff for a step to advance t");
      rk4_.integrate(field, trial_, t, next, 1);
      trial_ = Scalar(0.5) * (trial_ + trial_.transpose()).eval();
      if (!trial_.allFinite()) {
        fail_argument(who, "model", "gives a non-finite A or C within the step, or P leaves the floating-point range");
      }
      t = next;
    }
    p_.swap(trial_);
    return steps;
  }

  /// \f$\dot P = AP + PA^T + Q - PC^TR^{-1}CP\f$. It writes only `dp`, so that
  /// threads may share one equation; with run-time sizes its scratch CP and
  /// \f$R^{-1}CP\f$ is allocated at each call (`advance` keeps its own).
  template <class DA, class DC>
  void derivative(const Eigen::MatrixBase<DA>& A, const Eigen::MatrixBase<DC>& C, const StateMatrix& p,
                  StateMatrix& dp) const {
    typename D::OutputMatrix cp(r_.rows(), p_.rows()), r_inv_cp(r_.rows(), p_.rows());
    derivative(A, C, p, dp, cp, r_inv_cp);
  }

  /// \f$K = PC^TR^{-1}\f$ for the output matrix C of the current instant.
  template <class DC>
  const GainMatrix& gain(const Eigen::MatrixBase<DC>& C) {
    return gain_of(C, p_);
  }

 private:
  // The right-hand side with the caller's scratch for CP and R⁻¹CP.
  template <class DA, class DC>
  void derivative(const Eigen::MatrixBase<DA>& A, const Eigen::MatrixBase<DC>& C, const StateMatrix& p, StateMatrix& dp,
                  typename D::OutputMatrix& cp, typename D::OutputMatrix& r_inv_cp) const {
    cp.noalias() = C * p;
    r_inv_cp = cp;
    r_factor_.solve_in_place(r_inv_cp);
    dp = q_;
    dp.noalias() += A * p;
    dp.noalias() += p * A.transpose();
    dp.noalias() -= cp.transpose() * r_inv_cp;
  }

  template <class DC>
  const GainMatrix& gain_of(const Eigen::MatrixBase<DC>& C, const StateMatrix& p) {
    cp_.noalias() = C * p;
    gain_ = cp_.transpose();
    r_factor_.solve_on_the_right_in_place(gain_);  // K = P Cᵀ R⁻¹
    return gain_;
  }

  detail::CholeskyFactor<OutputCovariance> r_factor_;  // of R
  RungeKutta4<StateMatrix> rk4_;
  typename D::OutputMatrix cp_, r_inv_cp_;  // the scratch of `advance`
  GainMatrix gain_;
  StateMatrix trial_;        ///< P along the interval being crossed
  StateMatrix closed_loop_;  ///< A − KC at the start of a step
};

}  // namespace adaptobs
