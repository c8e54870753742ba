#pragma once
/// \file
/// The covariances a Riccati equation of Kalman filtering carries — the error
/// covariance P it propagates and the noise covariances Q and R — checked and
/// kept once for the difference and the differential equation.

#include <adaptobs/core/dimensions.hpp>
#include <adaptobs/core/validation.hpp>

#include <string_view>
#include <utility>

namespace adaptobs {

/// Base of `KalmanGainRecursion` and `RiccatiDifferentialEquation`, not used on
/// its own: P (from P0, positive definite), Q (positive semidefinite, P's size)
/// and R (positive definite), with the accessor of P.
template <StateSpace D>
class KalmanCovariances : public D {
 public:
  using OutputCovariance = typename D::OutputMatrixSquare;

  /// The current P.
  [[nodiscard]] const typename D::StateMatrix& covariance() const noexcept { return p_; }

 protected:
  /// `who` names the equation in the errors.
  KalmanCovariances(typename D::StateMatrix P0, typename D::StateMatrix Q, OutputCovariance R, std::string_view who)
      : p_(std::move(P0)), q_(std::move(Q)), r_(std::move(R)) {
    require_positive_definite(p_, who, "P0");
    require_shape(q_, p_.rows(), p_.rows(), who, "Q");
    require_positive_semidefinite(q_, who, "Q");
    require_positive_definite(r_, who, "R");
  }

  typename D::StateMatrix p_;
  typename D::StateMatrix q_;
  OutputCovariance r_;
};

}  // namespace adaptobs
