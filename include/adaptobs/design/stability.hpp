#pragma once
/// \file
/// Eigenvalues and eigenvalue-based stability figures of closed-loop matrices such as A − KC.
/// (`is_schur_stable`, which needs no eigenvalues, is in schur_stability.hpp.)

#include <adaptobs/core/validation.hpp>
#include <adaptobs/design/dense_eigenvalues.hpp>
#include <adaptobs/design/schur_stability.hpp>

#include <Eigen/Core>

#include <complex>
#include <limits>

namespace adaptobs {

/// Eigenvalues of a real square matrix.
///
/// A design-time check, computed on a dynamic-size copy: the real Schur
/// decomposition behind it is costly to compile, and one instantiation per
/// scalar type serves every matrix size (see core/precompiled.hpp).
template <class Derived>
[[nodiscard]] ComplexVector<typename Derived::Scalar> eigenvalues(const Eigen::MatrixBase<Derived>& m) {
  detail::require_square(m, "eigenvalues", "M");
  detail::require_finite(m, "eigenvalues", "M");
  return detail::dense_eigenvalues(detail::dynamic_copy(m));
}

/// Spectral radius \f$\rho(M) = \max_i |\lambda_i(M)|\f$.
template <class Derived>
[[nodiscard]] typename Derived::Scalar spectral_radius(const Eigen::MatrixBase<Derived>& m) {
  if (m.size() == 0) return typename Derived::Scalar(0);
  return eigenvalues(m).cwiseAbs().maxCoeff();
}

/// Largest real part of the eigenvalues (the continuous-time stability abscissa).
template <class Derived>
[[nodiscard]] typename Derived::Scalar spectral_abscissa(const Eigen::MatrixBase<Derived>& m) {
  if (m.size() == 0) return -std::numeric_limits<typename Derived::Scalar>::infinity();
  return eigenvalues(m).real().maxCoeff();
}

/// Hurwitz stability: every eigenvalue has real part below −margin.
template <class Derived>
[[nodiscard]] bool is_hurwitz_stable(const Eigen::MatrixBase<Derived>& m, typename Derived::Scalar margin = 0) {
  return spectral_abscissa(m) < -margin;
}

}  // namespace adaptobs
