#pragma once
/// \file
/// The exact test of strict positive realness of \f$G(s) = c(sI - A)^{-1}b\f$, alone:
/// what the Bastin–Gevers and Marino–Tomei observers check at construction,
/// without the sweep, the KYP certificate and the gain design of
/// `positive_real.hpp` (and the eigen-solvers they bring).
///
/// **Exact test.** With \f$G = N/D\f$, D monic of degree n: G is SPR iff D is
/// Hurwitz, the relative degree is 1 with a positive leading coefficient of N,
/// and the even polynomial \f$R(s) = \tfrac12[N(s)D(-s) + N(-s)D(s)]\f$, written
/// \f$q(w)\f$ with \f$w = \omega^2\f$ (\f$R(j\omega) = q(\omega^2) = \mathrm{Re}\,G(j\omega)|D(j\omega)|^2\f$),
/// has \f$q(0) > 0\f$, no real root in \f$[0, \infty)\f$, degree n − 1 and a positive
/// leading coefficient — the last two say \f$\lim\omega^2\mathrm{Re}\,G(j\omega) > 0\f$,
/// the strictness condition at infinity that \f$\mathrm{Re}\,G(j\omega) > 0\f$ alone misses.
/// D is tested by Routh–Hurwitz and the real roots of q are counted by a Sturm
/// sequence: exact in rational arithmetic, no root finding.

#include <adaptobs/core/precompiled.hpp>
#include <adaptobs/core/validation.hpp>
#include <adaptobs/design/polynomial.hpp>

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string_view>

namespace adaptobs {

/// The verdict of the exact SPR test and the figures it rests on.
template <typename Scalar>
struct SprConditions {
  bool strictly_positive_real = false;
  bool denominator_hurwitz = false;
  Index relative_degree = 0;
  Scalar high_frequency_gain = 0;  ///< leading coefficient of N (= cb when the relative degree is 1)
  bool q_positive_on_nonnegative_axis = false;
  bool strict_at_infinity = false;  ///< deg q = n − 1 with a positive leading coefficient
  explicit operator bool() const noexcept { return strictly_positive_real; }
};

/// Outcome of the exact SPR test, with the polynomial q.
template <typename Scalar>
struct SprTest : SprConditions<Scalar> {
  Polynomial<Scalar> q;  ///< \f$q(w) = \mathrm{Re}\,G(j\sqrt w)\,|D(j\sqrt w)|^2\f$, highest power first
};

/// Exact SPR test of \f$G = N/D\f$ (D monic of degree n, deg N < n), as in the
/// file comment: Routh–Hurwitz on D (`is_hurwitz_polynomial`), then the Sturm
/// count of the real roots of q on [0, ∞) (`count_real_roots_above`).
template <typename Scalar>
[[nodiscard]] SprTest<Scalar> strictly_positive_real(const Polynomial<Scalar>& numerator,
                                                     const Polynomial<Scalar>& denominator) {
  constexpr std::string_view who = "strictly_positive_real";
  require(denominator.size() >= 2 && denominator(0) == Scalar(1), who, "denominator",
          "must be monic of degree at least 1");
  const Index n = denominator.size() - 1;
  require(numerator.size() <= n, who, "numerator", "must have degree below the denominator's");
  require_finite(numerator, who, "numerator");
  require_finite(denominator, who, "denominator");
  // N padded to n coefficients (degree ≤ n − 1).
  Polynomial<Scalar> num = Polynomial<Scalar>::Zero(n);
  num.tail(numerator.size()) = numerator;
  const Scalar scale = std::max(detail::max_abs(num), std::numeric_limits<Scalar>::min());
  const Scalar zero_tol = Scalar(1e-10) * scale;

  SprTest<Scalar> r;
  r.denominator_hurwitz = is_hurwitz_polynomial(denominator);
  Index lead = 0;
  while (lead < n && std::abs(num(lead)) <= zero_tol) ++lead;
  if (lead == n) return r;  // G = 0
  r.relative_degree = n - (n - 1 - lead);
  r.high_frequency_gain = num(lead);

  // R(s) = ½[N(s)D(−s) + N(−s)D(s)], highest power first.
  const auto reflect = [](Polynomial<Scalar> p) {  // coefficients of p(−s)
    const Index d = p.size() - 1;
    for (Index i = 0; i <= d; ++i)
      if ((d - i) % 2 == 1) p(i) = -p(i);
    return p;
  };
  const Polynomial<Scalar> first = multiply_polynomials<Scalar>(num, reflect(denominator));
  const Polynomial<Scalar> second = multiply_polynomials<Scalar>(reflect(num), denominator);
  // q(w), ascending powers: q_k = (−1)^k R_{2k}, with R_{2k} the coefficient of s^{2k}.
  const Index last = first.size() - 1;
  const Index q_terms = (first.size() + 1) / 2;
  Polynomial<Scalar> q_asc(q_terms);
  for (Index k = 0; k < q_terms; ++k)
    q_asc(k) = (k % 2 == 0 ? Scalar(1) : Scalar(-1)) * (Scalar(0.5) * (first(last - 2 * k) + second(last - 2 * k)));
  const Scalar q_scale = std::max(detail::max_abs(q_asc), std::numeric_limits<Scalar>::min());
  Index degree = q_terms - 1;
  while (degree > 0 && std::abs(q_asc(degree)) <= Scalar(1e-10) * q_scale) --degree;
  r.q = q_asc.head(degree + 1).reverse();
  // The Sturm count below needs finite coefficients (its root scaling reads their exponents).
  require(r.q.allFinite(), who, "numerator",
          "times the denominator overflows the floating-point range (Re G(jw) |D(jw)|^2)");

  // q(0) > 0 is checked below, so a root on [0, ∞) is a root in (0, ∞) (Sturm count).
  const bool nonnegative_root = count_real_roots_above<Scalar>(r.q, Scalar(0), Scalar(1e-10)) > 0;
  r.q_positive_on_nonnegative_axis = q_asc(0) > 0 && !nonnegative_root;
  r.strict_at_infinity = degree == n - 1 && r.q(0) > 0;
  r.strictly_positive_real = r.denominator_hurwitz && r.relative_degree == 1 && r.high_frequency_gain > 0 &&
                             r.q_positive_on_nonnegative_axis && r.strict_at_infinity;
  return r;
}

#ifdef ADAPTOBS_PRECOMPILED
ADAPTOBS_INSTANTIATE SprTest<double> strictly_positive_real<double>(const Polynomial<double>&,
                                                                    const Polynomial<double>&);
#endif

/// Exact SPR test of \f$c(sI - A)^{-1}b\f$.
template <class DA, class DB, class DC>
[[nodiscard]] SprTest<typename DA::Scalar> strictly_positive_real(const Eigen::MatrixBase<DA>& A,
                                                                  const Eigen::MatrixBase<DB>& b,
                                                                  const Eigen::MatrixBase<DC>& c) {
  const auto g = transfer_function(A, b, c);
  return strictly_positive_real<typename DA::Scalar>(g.numerator, g.denominator);
}

}  // namespace adaptobs
