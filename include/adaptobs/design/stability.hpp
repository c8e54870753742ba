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
#include <string_view>

namespace adaptobs {

namespace detail {
/// The eigenvalues of a square finite M, refused otherwise under the caller's name `who`.
template <class Derived>
[[nodiscard]] ComplexVector<typename Derived::Scalar> checked_eigenvalues(const Eigen::MatrixBase<Derived>& m,
                                                                          std::string_view who) {
  require_square(m, who, "M");
  require_finite(m, who, "M");
  if (m.size() == 0) return {};
  return dense_eigenvalues(dynamic_copy(m));
}

template <class Derived>
[[nodiscard]] typename Derived::Scalar checked_spectral_abscissa(const Eigen::MatrixBase<Derived>& m,
                                                                 std::string_view who) {
  const auto lambda = checked_eigenvalues(m, who);
  if (lambda.size() == 0) return -std::numeric_limits<typename Derived::Scalar>::infinity();
  return lambda.real().maxCoeff();
}
}  // namespace detail

/// Eigenvalues of a real square matrix.
///
/// A design-time check, computed on a dynamic-size copy: the real Schur
/// decomposition behind it is costly to compile, and one instantiation per
/// scalar type serves every matrix size (see core/precompiled.hpp).
template <class Derived>
[[nodiscard]] ComplexVector<typename Derived::Scalar> eigenvalues(const Eigen::MatrixBase<Derived>& m) {
  return detail::checked_eigenvalues(m, "eigenvalues");
}

/// Spectral radius \f$\rho(M) = \max_i |\lambda_i(M)|\f$.
template <class Derived>
[[nodiscard]] typename Derived::Scalar spectral_radius(const Eigen::MatrixBase<Derived>& m) {
  const auto lambda = detail::checked_eigenvalues(m, "spectral_radius");
  return lambda.size() == 0 ? typename Derived::Scalar(0) : lambda.cwiseAbs().maxCoeff();
}

/// Largest real part of the eigenvalues (the continuous-time stability abscissa).
template <class Derived>
[[nodiscard]] typename Derived::Scalar spectral_abscissa(const Eigen::MatrixBase<Derived>& m) {
  return detail::checked_spectral_abscissa(m, "spectral_abscissa");
}

/// Hurwitz stability: every eigenvalue has real part below −margin.
template <class Derived>
[[nodiscard]] bool is_hurwitz_stable(const Eigen::MatrixBase<Derived>& m, typename Derived::Scalar margin = 0) {
  return detail::checked_spectral_abscissa(m, "is_hurwitz_stable") < -margin;
}

}  // namespace adaptobs
