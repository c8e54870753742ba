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
#include <adaptobs/core/detail/max_abs.hpp>
#include <adaptobs/core/precompiled.hpp>
#include <adaptobs/core/validation.hpp>

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string_view>
#include <utility>
#include <vector>

namespace adaptobs {

template <typename Scalar>
using Polynomial = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;

namespace detail {

/// The Faddeev–LeVerrier recursion (file comment) for a square A: hands
/// \f$B_k\f$ to `visit(k, B_k)` for k = 0, …, n − 1 and returns \f$\det(sI - A)\f$.
template <typename Scalar, class Visit>
Polynomial<Scalar> faddeev_leverrier(const DynamicMatrix<Scalar>& A, Visit&& visit) {
  const Index n = A.rows();
  Polynomial<Scalar> p(n + 1);
  p(0) = Scalar(1);
  DynamicMatrix<Scalar> b = DynamicMatrix<Scalar>::Identity(n, n);
  for (Index k = 1; k <= n; ++k) {
    visit(k - 1, b);
    b = A.lazyProduct(b).eval();
    p(k) = -b.trace() / Scalar(k);
    b.diagonal().array() += p(k);
  }
  return p;
}

/// The e with 2^e near the geometric mean magnitude of the nonzero roots of p
/// (p(0) ≠ 0): \f$|p_j/p_0|^{1/(d-j)}\f$ with \f$p_j\f$ the last nonzero coefficient.
template <typename Scalar>
[[nodiscard]] int root_scale_exponent(const Polynomial<Scalar>& p) {
  Index last = p.size() - 1;
  while (last > 0 && p(last) == Scalar(0)) --last;
  if (last == 0) return 0;
  return static_cast<int>(
      std::lround(static_cast<double>(std::ilogb(p(last)) - std::ilogb(p(0))) / static_cast<double>(last)));
}

/// \f$q(z) = p(2^e z)\f$ divided by a power of two that brings its largest
/// coefficient to [1, 2): both exact (short of underflow), with the roots of q
/// those of p divided by 2^e.
template <typename Scalar>
[[nodiscard]] Polynomial<Scalar> with_roots_scaled(const Polynomial<Scalar>& p, int e) {
  const Index d = p.size() - 1;
  int top = std::numeric_limits<int>::min();
  for (Index i = 0; i <= d; ++i)
    if (p(i) != Scalar(0)) top = std::max(top, std::ilogb(p(i)) + static_cast<int>(d - i) * e);
  Polynomial<Scalar> q(p.size());
  for (Index i = 0; i <= d; ++i)
    q(i) = p(i) == Scalar(0) ? Scalar(0) : std::ldexp(p(i), static_cast<int>(d - i) * e - top);
  return q;
}

}  // namespace detail

/// Coefficients of \f$\det(sI - A)\f$ (monic, degree n) by the Faddeev–LeVerrier
/// recursion (file comment), on a dynamic-size A.
template <typename Scalar>
[[nodiscard]] Polynomial<Scalar> characteristic_polynomial(const detail::DynamicMatrix<Scalar>& A) {
  require_square(A, "characteristic_polynomial", "A");
  require_finite(A, "characteristic_polynomial", "A");
  return detail::faddeev_leverrier(A, [](Index, const detail::DynamicMatrix<Scalar>&) {});
}

/// Coefficients of \f$\det(sI - A)\f$ (monic, degree n), for any A (the overload above).
template <class Derived>
[[nodiscard]] Polynomial<typename Derived::Scalar> characteristic_polynomial(const Eigen::MatrixBase<Derived>& A) {
  return characteristic_polynomial(detail::dynamic_copy(A));
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
  if (p.size() == 0 || p(0) == Scalar(0) || !p.allFinite()) return false;
  const Index degree = p.size() - 1;
  if (degree == 0) return true;
  if (p(degree) == Scalar(0)) return false;  // a root at 0
  const Polynomial<Scalar> q = detail::with_roots_scaled(p, detail::root_scale_exponent(p));
  const Scalar sign = q(0) > 0 ? Scalar(1) : Scalar(-1);
  const Scalar tol = Scalar(64) * std::numeric_limits<Scalar>::epsilon() * detail::max_abs(q);
  const Index width = degree / 2 + 1;
  Polynomial<Scalar> upper = Polynomial<Scalar>::Zero(width), lower = Polynomial<Scalar>::Zero(width), next(width);
  for (Index i = 0; i <= degree; ++i) (i % 2 == 0 ? upper : lower)(i / 2) = sign * q(i);
  for (Index row = 1; row <= degree; ++row) {
    if (!(lower(0) > tol)) return false;
    const Scalar ratio = upper(0) / lower(0);
    for (Index j = 0; j + 1 < width; ++j) next(j) = upper(j + 1) - ratio * lower(j + 1);
    next(width - 1) = Scalar(0);
    std::swap(upper, lower);
    std::swap(lower, next);
  }
  return true;
}

/// Hurwitz test of a small square matrix without an eigen-decomposition:
/// Routh–Hurwitz on its Faddeev–LeVerrier characteristic polynomial (orders n ≲ 10,
/// the construction-time checks of small observer blocks).
template <class Derived>
[[nodiscard]] bool has_hurwitz_characteristic_polynomial(const Eigen::MatrixBase<Derived>& m) {
  constexpr std::string_view who = "has_hurwitz_characteristic_polynomial";
  if (m.size() == 0) return true;
  if (m.rows() != m.cols()) detail::fail_not_square(m.rows(), m.cols(), who, "m");
  const detail::DynamicMatrix<typename Derived::Scalar> a = detail::dynamic_copy(m);
  require_finite(a, who, "m");
  return is_hurwitz_polynomial(characteristic_polynomial(a));
}

/// Number of distinct real roots of p in the half-open interval (a, ∞), by a
/// Sturm sequence (signs of \f$p_0 = p,\ p_1 = p',\ p_{k+1} = -\mathrm{rem}(p_{k-1}, p_k)\f$
/// at a and at +∞); `relative_tolerance` treats remainder coefficients that small
/// against the largest as zero, after the roots are scaled to magnitudes near 1
/// (as in `is_hurwitz_polynomial`). No root finding.
template <typename Scalar>
[[nodiscard]] Index count_real_roots_above(const Polynomial<Scalar>& p, Scalar a,
                                           Scalar relative_tolerance = Scalar(1e-10)) {
  require_finite(p, "count_real_roots_above", "p");
  require(std::isfinite(a), "count_real_roots_above", "a", "must be finite");
  using detail::max_abs;
  // The coefficients from the first whose magnitude exceeds `relative_tolerance`
  // times `scale` on.
  const auto trimmed = [&](const Polynomial<Scalar>& q, Index first, Scalar scale) {
    while (first < q.size() && std::abs(q(first)) <= relative_tolerance * scale) ++first;
    return Polynomial<Scalar>(q.tail(q.size() - first));
  };
  // Scale invariance: the roots (and a) divided by 2^e, near their geometric
  // mean magnitude, so that the relative trims see x² − 1e-12 as x² − 1.
  Index lead = 0;
  while (lead < p.size() && p(lead) == Scalar(0)) ++lead;
  if (p.size() - lead <= 1) return 0;
  const Polynomial<Scalar> exact = p.tail(p.size() - lead);
  const int e = detail::root_scale_exponent(exact);
  a = std::clamp(std::ldexp(a, -e), std::numeric_limits<Scalar>::lowest(), std::numeric_limits<Scalar>::max());
  const Polynomial<Scalar> scaled = detail::with_roots_scaled(exact, e);
  std::vector<Polynomial<Scalar>> chain{trimmed(scaled, 0, max_abs(scaled))};
  if (chain[0].size() <= 1) return 0;
  const Index d = chain[0].size() - 1;
  Polynomial<Scalar> derivative(d);
  for (Index i = 0; i < d; ++i) derivative(i) = Scalar(d - i) * chain[0](i);
  chain.push_back(trimmed(derivative, 0, max_abs(derivative)));
  while (chain.back().size() > 1) {
    // r = rem(p_{k−1}, p_k) by long division, in place on a copy of p_{k−1}.
    Polynomial<Scalar> r = chain[chain.size() - 2];
    const Polynomial<Scalar>& q = chain.back();
    const Index nq = q.size(), nr = r.size();
    const Scalar keep = max_abs(r);
    for (Index shift = 0; shift + nq <= nr; ++shift) {
      const Scalar factor = r(shift) / q(0);
      for (Index i = 0; i < nq; ++i) r(shift + i) -= factor * q(i);
      r(shift) = Scalar(0);
    }
    // The remainder is the last nq − 1 coefficients. Scale-aware trim:
    // compare with the dividend, not with the (small) remainder itself.
    Polynomial<Scalar> next = trimmed(r, nr - (nq - 1), keep);
    if (next.size() == 0) break;  // p has repeated roots: the chain ends at their gcd
    chain.push_back(Polynomial<Scalar>(-next));
  }
  const auto sign_changes = [&](auto value_of) {
    Index changes = 0;
    int previous = 0;
    for (const auto& q : chain) {
      const Scalar v = value_of(q);
      const int s = v > 0 ? 1 : (v < 0 ? -1 : 0);
      if (s != 0) {
        if (previous != 0 && s != previous) ++changes;
        previous = s;
      }
    }
    return changes;
  };
  const auto at_a = [&](const Polynomial<Scalar>& q) {
    Scalar v = 0;
    for (Index i = 0; i < q.size(); ++i) v = v * a + q(i);
    return v;
  };
  const auto at_infinity = [](const Polynomial<Scalar>& q) { return q(0); };
  return sign_changes(at_a) - sign_changes(at_infinity);
}

/// Product of two polynomials (convolution of the coefficients).
template <typename Scalar>
[[nodiscard]] Polynomial<Scalar> multiply_polynomials(const Polynomial<Scalar>& a, const Polynomial<Scalar>& b) {
  if (a.size() == 0 || b.size() == 0) return {};
  Polynomial<Scalar> c = Polynomial<Scalar>::Zero(a.size() + b.size() - 1);
  for (Index i = 0; i < a.size(); ++i) c.segment(i, b.size()) += a(i) * b;
  return c;
}

/// \f$p(M) = p_0M^d + \dots + p_dI\f$ by Horner's rule.
template <class Derived>
[[nodiscard]] Eigen::Matrix<typename Derived::Scalar, Eigen::Dynamic, Eigen::Dynamic> evaluate_polynomial(
    const Polynomial<typename Derived::Scalar>& p, const Eigen::MatrixBase<Derived>& m) {
  using Matrix = Eigen::Matrix<typename Derived::Scalar, Eigen::Dynamic, Eigen::Dynamic>;
  require_finite(p, "evaluate_polynomial", "p");
  require_square(m, "evaluate_polynomial", "m");
  require_finite(m, "evaluate_polynomial", "m");
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

/// The transfer function of a SISO triple on dynamic-size matrices (shapes
/// unchecked): \f$N(s) = c\,\mathrm{adj}(sI - A)\,b = \sum_k (cB_kb)\,s^{n-1-k}\f$ with the
/// Faddeev–LeVerrier \f$B_k\f$ (file comment).
template <typename Scalar>
[[nodiscard]] SisoTransferFunction<Scalar> transfer_function(const detail::DynamicMatrix<Scalar>& A,
                                                             const Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& b,
                                                             const Eigen::Matrix<Scalar, 1, Eigen::Dynamic>& c) {
  SisoTransferFunction<Scalar> g;
  g.numerator = Polynomial<Scalar>::Zero(A.rows());
  g.denominator = detail::faddeev_leverrier(
      A, [&](Index k, const detail::DynamicMatrix<Scalar>& bk) { g.numerator(k) = c.dot(bk * b); });
  return g;
}

/// \f$G(s) = c(sI - A)^{-1}b\f$ of any SISO triple: its shapes and finiteness
/// checked, then the overload above.
template <class DA, class DB, class DC>
[[nodiscard]] SisoTransferFunction<typename DA::Scalar> transfer_function(const Eigen::MatrixBase<DA>& A,
                                                                          const Eigen::MatrixBase<DB>& b,
                                                                          const Eigen::MatrixBase<DC>& c) {
  using Scalar = typename DA::Scalar;
  detail::require_siso_triple(A, b, c, "transfer_function");
  return transfer_function(detail::dynamic_copy(A), Eigen::Matrix<Scalar, Eigen::Dynamic, 1>(detail::dynamic_copy(b)),
                           Eigen::Matrix<Scalar, 1, Eigen::Dynamic>(detail::dynamic_copy(c)));
}

#ifdef ADAPTOBS_PRECOMPILED
ADAPTOBS_INSTANTIATE Polynomial<double> characteristic_polynomial<double>(const detail::DynamicMatrix<double>&);
ADAPTOBS_INSTANTIATE bool is_hurwitz_polynomial<double>(const Polynomial<double>&);
ADAPTOBS_INSTANTIATE Index count_real_roots_above<double>(const Polynomial<double>&, double, double);
ADAPTOBS_INSTANTIATE Polynomial<double> multiply_polynomials<double>(const Polynomial<double>&,
                                                                     const Polynomial<double>&);
ADAPTOBS_INSTANTIATE SisoTransferFunction<double> transfer_function<double>(
    const detail::DynamicMatrix<double>&, const Eigen::Matrix<double, Eigen::Dynamic, 1>&,
    const Eigen::Matrix<double, 1, Eigen::Dynamic>&);
#endif

}  // namespace adaptobs
