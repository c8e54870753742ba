#pragma once
/// \file
/// A continuous-time linear system observed at sampling instants, as a discrete model.
///
/// For \f$\dot x = Ax + Bu(t) + \varphi(t)\theta\f$, \f$y_k = Cx(kT)\f$, with u
/// held over each period (zero-order hold), the samples obey exactly
/// \f[ x_{k+1} = e^{AT}x_k + B_du_k + \Psi_k\theta,\qquad
///     B_d = \int_0^Te^{As}ds\,B,\qquad \Psi_k = e^{AT}H_k \f]
/// with \f$H_k\f$ from `RegressorIntegral` or `PolynomialRegressorIntegral`.
/// An input that is not held constant contributes
/// \f$\int_{kT}^{(k+1)T}e^{((k+1)T-s)A}Bu(s)ds\f$, the Ψ of the "regressor" \f$Bu(t)\f$
/// with θ = 1: pass it as the input of a model with \f$B_d = I\f$.

#include <adaptobs/core/dimensions.hpp>
#include <adaptobs/core/discrete_model.hpp>
#include <adaptobs/core/discretization.hpp>

#include <Eigen/Core>

namespace adaptobs {

/// The discrete model \f$(e^{AT}, B_d, C)\f$ of a continuous system sampled with period T (see file comment).
template <StateSpace D, class DA, class DB, class DC>
[[nodiscard]] DiscreteLtiModel<D> sampled_lti_model(const Eigen::MatrixBase<DA>& A, const Eigen::MatrixBase<DB>& B,
                                                    const Eigen::MatrixBase<DC>& C, typename D::Scalar period,
                                                    Index np = D::np) {
  require_finite(A, "sampled_lti_model", "A");
  const auto zoh = discretize_zoh(A, B, period);
  return DiscreteLtiModel<D>(typename D::StateMatrix(zoh.Ad), typename D::InputMatrix(zoh.Bd),
                             typename D::OutputMatrix(C), np);
}

}  // namespace adaptobs
