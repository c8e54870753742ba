#pragma once
/// \file
/// Polynomials and SISO transfer functions of small state-space systems.
///
/// Coefficients are stored highest power first: \f$p(s) = p_0 s^d + p_1 s^{d-1} + \dots + p_d\f$
/// is the vector \f$(p_0, \dots, p_d)\f$. Characteristic polynomials and
/// adjugates come from the Faddeev–LeVerrier recursion
/// \f$B_0 = I,\ a_k = -\mathrm{tr}(AB_{k-1})/k,\ B_k = AB_{k-1} + a_kI\f$, giving
/// \f$\det(sI - A) = s^n + a_1s^{n-1} + \dots + a_n\f$ and
/// \f$\mathrm{adj}(sI - A) = \sum_{k=0}^{n-1} B_k s^{n-1-k}\f$ — exact in rational
/// arithmetic, and accurate in floating point for the small orders (n ≲ 10)
/// of the design problems it serves.
///
/// `ackermann_observer_gain` is in positive_real.hpp: it decides observability
/// by the staircase of observability.hpp, whose SVD and eigenvalue solver this
/// header, which the observers include, does without.

#include <adaptobs/core/detail/dynamic_copy.hpp>
#include <adaptobs/core/validation.hpp>
#include <adaptobs/design/detail/polynomial_coefficients.hpp>

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <string_view>
#include <vector>

namespace adaptobs {

template <typename Scalar>
using Polynomial = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;

namespace detail {
template <typename Scalar>
[[nodiscard]] Coefficients<Scalar> coefficients_of(const Polynomial<Scalar>& p) {
  return Coefficients<Scalar>(p.data(), p.data() + p.size());
}

template <typename Scalar>
[[nodiscard]] Polynomial<Scalar> polynomial_of(const Coefficients<Scalar>& c) {
  Polynomial<Scalar> p(std::ssize(c));
  std::copy(c.begin(), c.end(), p.data());
  return p;
}
}  // namespace detail

/// Coefficients of \f$\det(sI - A)\f$ (monic, degree n).
template <class Derived>
[[nodiscard]] Polynomial<typename Derived::Scalar> characteristic_polynomial(const Eigen::MatrixBase<Derived>& A) {
  const detail::DynamicMatrix<typename Derived::Scalar> a = detail::dynamic_copy(A);
  detail::require_square(a, "characteristic_polynomial", "A");
  detail::require_finite(a, "characteristic_polynomial", "A");
  return detail::polynomial_of(
      detail::characteristic_coefficients(std::vector<typename Derived::Scalar>(a.data(), a.data() + a.size()), a.rows()));
}

/// Every root in the open left half-plane (and a non-zero leading coefficient).
///
/// Routh–Hurwitz test, no root finding: the first column of the Routh array
/// must keep one sign. Each row is \f$r_{k+1,j} = r_{k-1,j+1} - (r_{k-1,0}/r_{k,0})\,r_{k,j+1}\f$;
/// a zero (relative to the coefficients) in the first column means a root on
/// or to the right of the imaginary axis, so the polynomial is not Hurwitz.
/// The test is scale invariant: p(s) is first written as q(z) = p(2^e z)
/// scaled by a power of two (both exact), with 2^e near the geometric mean
/// \f$|p_d/p_0|^{1/d}\f$ of the roots' magnitudes, so that (s + 10⁻¹⁰)² or
/// s² + 10¹⁰s + 10³⁰ is judged as (z + 1)² or z² + 10⁻⁵z + 1.
template <typename Scalar>
[[nodiscard]] bool is_hurwitz_polynomial(const Polynomial<Scalar>& p) {
  return detail::is_hurwitz(detail::coefficients_of(p));
}

/// Hurwitz test of a small square matrix without an eigen-decomposition:
/// Routh–Hurwitz on its Faddeev–LeVerrier characteristic polynomial (orders n ≲ 10,
/// the construction-time checks of small observer blocks, which is why it
/// reads the entries one by one rather than copying m into a dynamic-size matrix).
template <class Derived>
[[nodiscard]] bool has_hurwitz_characteristic_polynomial(const Eigen::MatrixBase<Derived>& m) {
  constexpr std::string_view who = "has_hurwitz_characteristic_polynomial";
  if (m.size() == 0) return true;
  if (m.rows() != m.cols()) detail::fail_not_square(m.rows(), m.cols(), who, "m");
  const std::vector<typename Derived::Scalar> a = detail::column_major_entries(m);
  detail::require(detail::all_finite_coefficients(a), who, "m", "must contain only finite numbers");
  return detail::is_hurwitz(detail::characteristic_coefficients(a, m.rows()));
}

/// Number of distinct real roots of p in the half-open interval (a, ∞), by a
/// Sturm sequence (signs of \f$p_0 = p,\ p_1 = p',\ p_{k+1} = -\mathrm{rem}(p_{k-1}, p_k)\f$
/// at a and at +∞); `relative_tolerance` treats remainder coefficients that small
/// against the largest as zero, after the roots are scaled to magnitudes near 1
/// (as in `is_hurwitz_polynomial`). No root finding.
template <typename Scalar>
[[nodiscard]] Index count_real_roots_above(const Polynomial<Scalar>& p, Scalar a,
                                           Scalar relative_tolerance = Scalar(1e-10)) {
  detail::require_finite(p, "count_real_roots_above", "p");
  detail::require(std::isfinite(a), "count_real_roots_above", "a", "must be finite");
  return detail::count_real_roots_above(detail::coefficients_of(p), a, relative_tolerance);
}

/// Product of two polynomials (convolution of the coefficients).
template <typename Scalar>
[[nodiscard]] Polynomial<Scalar> multiply_polynomials(const Polynomial<Scalar>& a, const Polynomial<Scalar>& b) {
  return detail::polynomial_of(detail::multiply_coefficients(detail::coefficients_of(a), detail::coefficients_of(b)));
}

/// \f$p(M) = p_0M^d + \dots + p_dI\f$ by Horner's rule.
template <class Derived>
[[nodiscard]] Eigen::Matrix<typename Derived::Scalar, Eigen::Dynamic, Eigen::Dynamic> evaluate_polynomial(
    const Polynomial<typename Derived::Scalar>& p, const Eigen::MatrixBase<Derived>& m) {
  using Matrix = Eigen::Matrix<typename Derived::Scalar, Eigen::Dynamic, Eigen::Dynamic>;
  detail::require_finite(p, "evaluate_polynomial", "p");
  detail::require_square(m, "evaluate_polynomial", "m");
  detail::require_finite(m, "evaluate_polynomial", "m");
  const Index n = m.rows();
  Matrix result = Matrix::Zero(n, n);
  for (Index i = 0; i < p.size(); ++i) {
    result = (result * m).eval();
    result.diagonal().array() += p(i);
  }
  return result;
}

/// Observability matrix \f$[C; CA; \dots; CA^{n-1}]\f$.
template <class DA, class DC>
[[nodiscard]] Eigen::Matrix<typename DA::Scalar, Eigen::Dynamic, Eigen::Dynamic> observability_matrix(
    const Eigen::MatrixBase<DA>& A, const Eigen::MatrixBase<DC>& C) {
  using Matrix = Eigen::Matrix<typename DA::Scalar, Eigen::Dynamic, Eigen::Dynamic>;
  const Index n = detail::require_output_pair(A, C, "observability_matrix"), m = C.rows();
  Matrix o(n * m, n);
  Matrix row = C;
  for (Index k = 0; k < n; ++k) {
    o.middleRows(k * m, m) = row;
    row = (row * A).eval();
  }
  return o;
}

/// \f$G(s) = c(sI - A)^{-1}b = N(s)/D(s)\f$ with D monic of degree n and N of degree ≤ n − 1.
template <typename Scalar>
struct SisoTransferFunction {
  Polynomial<Scalar> numerator;    ///< \f$N(s) = c\,\mathrm{adj}(sI - A)\,b\f$, n coefficients
  Polynomial<Scalar> denominator;  ///< \f$D(s) = \det(sI - A)\f$, n + 1 coefficients
};

template <class DA, class DB, class DC>
[[nodiscard]] SisoTransferFunction<typename DA::Scalar> transfer_function(const Eigen::MatrixBase<DA>& A,
                                                                          const Eigen::MatrixBase<DB>& b,
                                                                          const Eigen::MatrixBase<DC>& c) {
  detail::require_siso_triple(A, b, c, "transfer_function");
  const auto g = detail::transfer_coefficients(A, b, c);
  return {detail::polynomial_of(g.numerator), detail::polynomial_of(g.denominator)};
}

}  // namespace adaptobs
