#pragma once
/// \file
/// The correction step shared by the recursive-least-squares laws, in a form
/// that keeps the covariance exactly symmetric and never inverts a matrix.
///
/// With \f$M = W + \varphi^T\Gamma\varphi\f$ (\f$W = R\f$ for RLS, \f$\lambda R\f$
/// with forgetting) factored as \f$M = LL^T\f$ and \f$U = \Gamma\varphi L^{-T}\f$,
/// \f[ \hat p^+ = \hat p + \Gamma\varphi M^{-1}(z - \varphi^T\hat p) = \hat p + U\,L^{-1}(z - \varphi^T\hat p),
///     \qquad \bar\Gamma = \Gamma - \Gamma\varphi M^{-1}\varphi^T\Gamma = \Gamma - UU^T. \f]
/// Cost: \f$n_p^2 n_z\f$ for \f$\Gamma\varphi\f$, \f$n_p^2 n_z\f$ for \f$UU^T\f$, a
/// \f$n_z \times n_z\f$ Cholesky factorization and two triangular solves; the
/// lower triangle of \f$\bar\Gamma\f$ is mirrored into the upper one, so the
/// stored covariance is symmetric to the last bit.

#include <adaptobs/adaptation/adaptation_law.hpp>
#include <adaptobs/core/detail/cholesky.hpp>
#include <adaptobs/core/detail/products.hpp>

#include <Eigen/Core>

#include <limits>

namespace adaptobs::detail {

/// Copies the strictly lower triangle of a square matrix into its strictly upper one.
template <class Derived>
void mirror_lower_triangle(Eigen::MatrixBase<Derived>& m) {
  for (Index j = 1; j < m.cols(); ++j)
    for (Index i = 0; i < j; ++i) m(i, j) = m(j, i);
}

/// Workspace and arithmetic of one RLS correction (see the file comment).
template <typename S, int NP, int NZ>
class RlsCorrection {
 public:
  using Types = RegressionTypes<S, NP, NZ>;
  using Parameters = typename Types::Parameters;
  using Regressor = typename Types::Regressor;
  using Measurement = typename Types::Measurement;
  using Covariance = typename Types::Covariance;
  using MeasurementWeight = typename Types::MeasurementWeight;

  RlsCorrection(Index np, Index nz) : cholesky_(nz) {
    gain_.setZero(np, nz);
    innovation_weight_.setZero(nz, nz);
    innovation_.setZero(nz);
  }

  /// \f$p^+ = p + \Gamma\varphi M^{-1}(z - \varphi^Tp)\f$ and
  /// \f$\Gamma^+ = s\,(\Gamma - \Gamma\varphi M^{-1}\varphi^T\Gamma)\f$ with \f$M = W + \varphi^T\Gamma\varphi\f$.
  ///
  /// Returns false, with NaN in both outputs, when M is not positive definite
  /// (Γ has lost its definiteness in floating point); the outputs may still
  /// hold non-finite numbers when it returns true (overflow).
  bool apply(const Covariance& gamma, const MeasurementWeight& weight, const Regressor& phi, const Measurement& z,
             const Parameters& p, S scale, Parameters& p_out, Covariance& gamma_out) {
    set_product(gain_, gamma, phi);
    innovation_weight_ = weight;
    add_product(innovation_weight_, phi.transpose(), gain_);
    if (!cholesky_.compute(innovation_weight_)) {
      p_out.setConstant(std::numeric_limits<S>::quiet_NaN());
      gamma_out.setConstant(std::numeric_limits<S>::quiet_NaN());
      return false;
    }
    // U = Γφ L⁻ᵀ (in place), then L⁻¹(z − φᵀp).
    cholesky_.solve_lower_transposed_on_the_right(gain_);
    innovation_ = z;
    subtract_product(innovation_, phi.transpose(), p);
    cholesky_.solve_lower_in_place(innovation_);
    p_out = p;
    add_product(p_out, gain_, innovation_);
    gamma_out = gamma;
    subtract_product(gamma_out, gain_, gain_.transpose());
    if (scale != S(1)) gamma_out *= scale;
    mirror_lower_triangle(gamma_out);
    return true;
  }

  /// \f$U = \Gamma\varphi L^{-T}\f$ of the last successful `apply`.
  [[nodiscard]] const typename Types::Gain& factor() const noexcept { return gain_; }

 private:
  typename Types::Gain gain_;
  MeasurementWeight innovation_weight_;
  CholeskyFactor<MeasurementWeight> cholesky_;
  Measurement innovation_;
};

}  // namespace adaptobs::detail
