#pragma once
/// \file
/// Continuous-time gradient adaptation \f$\dot{\hat\theta} = \Gamma R^T\varepsilon\f$.
///
/// The parameter update of the four observers of Zhang (2005): with
/// \f$\varepsilon = y - C_o\hat x\f$ the output error and R the regressor of the
/// algorithm (m × p), \f$R = \xi^T\f$ for Alg. 1–2, \f$R = A_{12}\Xi + \Psi_1\f$ for
/// Alg. 3, \f$R = C\Omega\f$ for Alg. 4 (eq. (12b)). Γ is symmetric positive definite.
///
/// An update law is any type with `derivative(R, epsilon, theta, dtheta)`;
/// this one is the default of `UnifiedAdaptiveObserver`.

#include <adaptobs/core/dimensions.hpp>
#include <adaptobs/core/validation.hpp>

#include <Eigen/Core>

#include <concepts>
#include <utility>

namespace adaptobs {

/// A parameter update law: `law.derivative(R, epsilon, theta, dtheta)` writes \f$\dot{\hat\theta}\f$.
template <class L, class D>
concept ContinuousAdaptationLaw = requires(
    const L& law, const typename D::OutputRegressor& R, const typename D::Output& epsilon,
    const typename D::Parameters& theta, typename D::Parameters& dtheta) { law.derivative(R, epsilon, theta, dtheta); };

/// \f$\dot{\hat\theta} = \Gamma R^T\varepsilon\f$.
template <StateSpace D>
class GradientLaw {
 public:
  using Scalar = typename D::Scalar;
  using ParameterMatrix = typename D::ParameterMatrix;

  explicit GradientLaw(ParameterMatrix gamma) : gamma_(std::move(gamma)) {
    require_positive_definite(gamma_, "GradientLaw", "gamma");
  }

  /// \f$\dot{\hat\theta} = \Gamma R^T\varepsilon = \sum_j \Gamma_{:,j}\,(r_j^T\varepsilon)\f$, with
  /// \f$r_j\f$ the j-th column of R: summed column by column, so that no
  /// intermediate vector \f$R^T\varepsilon\f$ is stored (none allocated with
  /// run-time sizes) and the law writes only `dtheta`, safe to call from
  /// several threads at once.
  template <class DR, class DE, class DT, class DOut>
  void derivative(const Eigen::MatrixBase<DR>& R, const Eigen::MatrixBase<DE>& epsilon,
                  const Eigen::MatrixBase<DT>& /*theta*/, Eigen::MatrixBase<DOut>& dtheta) const {
    dtheta.setZero();
    for (Index j = 0; j < R.cols(); ++j) dtheta += gamma_.col(j) * R.col(j).dot(epsilon);
  }

  [[nodiscard]] const ParameterMatrix& gamma() const noexcept { return gamma_; }

  /// Its fields for `snapshot` and `restore` (core/snapshot.hpp): Γ.
  template <class Self, class Archive>
  static void visit_state(Self& self, Archive& archive) {
    archive("gamma", self.gamma_);
  }

 private:
  ParameterMatrix gamma_;
};

}  // namespace adaptobs
