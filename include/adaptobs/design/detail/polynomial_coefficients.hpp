#pragma once
/// \file
/// Polynomial arithmetic on plain coefficient vectors (`std::vector`, highest
/// power first): the Faddeev–LeVerrier recursion, the Routh–Hurwitz test, Sturm
/// counting, products and the SISO transfer function.
///
/// Why not Eigen's dynamic-size vectors: the continuous-time observers run this
/// arithmetic at construction (A22 Hurwitz, the error system SPR), so every
/// translation unit that builds one compiles it. On dynamic-size Eigen types it
/// cost about 1.4 s of g++ -O2 in each such unit (allocation, resizing and
/// assignment kernels for every operation); as loops on `std::vector` it is a
/// small fraction of that. `polynomial.hpp` and `spr_test.hpp` give it its
/// public, Eigen-typed form.

#include <adaptobs/core/dimensions.hpp>

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <iterator>
#include <limits>
#include <utility>
#include <vector>

namespace adaptobs::detail {

/// Coefficients \f$(p_0, \dots, p_d)\f$ of \f$p(s) = p_0s^d + \dots + p_d\f$.
template <typename Scalar>
using Coefficients = std::vector<Scalar>;

/// The entries of m in column-major order, read one by one (one small
/// instantiation per expression type, none of Eigen's assignment machinery).
template <class Derived>
[[nodiscard]] std::vector<typename Derived::Scalar> column_major_entries(const Eigen::MatrixBase<Derived>& m) {
  std::vector<typename Derived::Scalar> out;
  out.reserve(static_cast<std::size_t>(m.size()));
  for (Index j = 0; j < m.cols(); ++j)
    for (Index i = 0; i < m.rows(); ++i) out.push_back(m(i, j));
  return out;
}

template <typename Scalar>
[[nodiscard]] bool all_finite_coefficients(const std::vector<Scalar>& v) {
  return std::all_of(v.begin(), v.end(), [](Scalar x) { return std::isfinite(x); });
}

/// \f$\max_i|v_i|\f$, 0 for an empty v.
template <typename Scalar>
[[nodiscard]] Scalar max_abs_coefficient(const std::vector<Scalar>& v) {
  Scalar m = 0;
  for (Scalar x : v) m = std::max(m, std::abs(x));
  return m;
}

/// The coefficients of p from index `first` on.
template <typename Scalar>
[[nodiscard]] Coefficients<Scalar> without_leading(const Coefficients<Scalar>& p, Index first) {
  return Coefficients<Scalar>(p.begin() + first, p.end());
}

/// \f$ab\f$ for n × n matrices stored column-major, each entry an inner product
/// summed in ascending order.
template <typename Scalar>
[[nodiscard]] std::vector<Scalar> square_product(const std::vector<Scalar>& a, const std::vector<Scalar>& b, Index n) {
  std::vector<Scalar> c(static_cast<std::size_t>(n * n));
  for (Index j = 0; j < n; ++j)
    for (Index i = 0; i < n; ++i) {
      Scalar s = 0;
      for (Index k = 0; k < n; ++k) s += a[i + k * n] * b[k + j * n];
      c[i + j * n] = s;
    }
  return c;
}

/// The matrices \f$B_k\f$ of the Faddeev–LeVerrier recursion
/// \f$B_0 = I,\ a_k = -\mathrm{tr}(AB_{k-1})/k,\ B_k = AB_{k-1} + a_kI\f$ for an n × n
/// A (column-major), handed to `visit(k, B_k)` for k = 0, …, n − 1; returns
/// \f$\det(sI - A) = s^n + a_1s^{n-1} + \dots + a_n\f$.
template <typename Scalar, class Visit>
Coefficients<Scalar> faddeev_leverrier(const std::vector<Scalar>& a, Index n, Visit&& visit) {
  Coefficients<Scalar> p(static_cast<std::size_t>(n + 1));
  p[0] = Scalar(1);
  std::vector<Scalar> b(static_cast<std::size_t>(n * n), Scalar(0));
  for (Index i = 0; i < n; ++i) b[i * (n + 1)] = Scalar(1);
  for (Index k = 1; k <= n; ++k) {
    visit(k - 1, b);
    b = square_product(a, b, n);
    Scalar trace = 0;
    for (Index i = 0; i < n; ++i) trace += b[i * (n + 1)];
    p[k] = -trace / Scalar(k);
    for (Index i = 0; i < n; ++i) b[i * (n + 1)] += p[k];
  }
  return p;
}

/// \f$\det(sI - A)\f$ for an n × n A stored column-major.
template <typename Scalar>
[[nodiscard]] Coefficients<Scalar> characteristic_coefficients(const std::vector<Scalar>& a, Index n) {
  return faddeev_leverrier(a, n, [](Index, const std::vector<Scalar>&) {});
}

/// \f$G(s) = c(sI - A)^{-1}b = N(s)/D(s)\f$, D monic of degree n, N with n coefficients.
template <typename Scalar>
struct TransferCoefficients {
  Coefficients<Scalar> numerator;
  Coefficients<Scalar> denominator;
};

/// \f$N(s) = c\,\mathrm{adj}(sI - A)\,b = \sum_k (cB_kb)\,s^{n-1-k}\f$ with the
/// Faddeev–LeVerrier \f$B_k\f$; A n × n column-major, b and c n entries each.
template <typename Scalar>
[[nodiscard]] TransferCoefficients<Scalar> siso_transfer_coefficients(const std::vector<Scalar>& a,
                                                                      const std::vector<Scalar>& b,
                                                                      const std::vector<Scalar>& c, Index n) {
  TransferCoefficients<Scalar> g;
  g.numerator.assign(static_cast<std::size_t>(n), Scalar(0));
  g.denominator = faddeev_leverrier(a, n, [&](Index k, const std::vector<Scalar>& bk) {
    Scalar sum = 0;
    for (Index i = 0; i < n; ++i) {
      Scalar bk_b = 0;
      for (Index l = 0; l < n; ++l) bk_b += bk[i + l * n] * b[l];
      sum += c[i] * bk_b;
    }
    g.numerator[k] = sum;
  });
  return g;
}

/// The transfer function of the Eigen triple (A, b, c), whose shapes the caller guarantees.
template <class DA, class DB, class DC>
[[nodiscard]] TransferCoefficients<typename DA::Scalar> transfer_coefficients(const Eigen::MatrixBase<DA>& A,
                                                                            const Eigen::MatrixBase<DB>& b,
                                                                            const Eigen::MatrixBase<DC>& c) {
  return siso_transfer_coefficients(column_major_entries(A), column_major_entries(b), column_major_entries(c),
                                    A.rows());
}

/// The e with 2^e near the geometric mean magnitude of the nonzero roots of p
/// (p(0) ≠ 0): \f$|p_j/p_0|^{1/(d-j)}\f$ with \f$p_j\f$ the last nonzero coefficient.
template <typename Scalar>
[[nodiscard]] int root_scale_exponent(const Coefficients<Scalar>& p) {
  Index last = std::ssize(p) - 1;
  while (last > 0 && p[last] == Scalar(0)) --last;
  if (last == 0) return 0;
  return static_cast<int>(std::lround(static_cast<double>(std::ilogb(p[last]) - std::ilogb(p[0])) /
                                      static_cast<double>(last)));
}

/// \f$q(z) = p(2^e z)\f$ divided by a power of two that brings its largest
/// coefficient to [1, 2): both exact (short of underflow), with the roots of q
/// those of p divided by 2^e.
template <typename Scalar>
[[nodiscard]] Coefficients<Scalar> with_roots_scaled(const Coefficients<Scalar>& p, int e) {
  const Index d = std::ssize(p) - 1;
  int top = std::numeric_limits<int>::min();
  for (Index i = 0; i <= d; ++i)
    if (p[i] != Scalar(0)) top = std::max(top, std::ilogb(p[i]) + static_cast<int>(d - i) * e);
  Coefficients<Scalar> q(p.size());
  for (Index i = 0; i <= d; ++i) q[i] = p[i] == Scalar(0) ? Scalar(0) : std::ldexp(p[i], static_cast<int>(d - i) * e - top);
  return q;
}

/// Routh–Hurwitz test (see `is_hurwitz_polynomial`).
template <typename Scalar>
[[nodiscard]] bool is_hurwitz(const Coefficients<Scalar>& p) {
  if (p.empty() || p[0] == Scalar(0) || !all_finite_coefficients(p)) return false;
  const Index degree = std::ssize(p) - 1;
  if (degree == 0) return true;
  if (p[degree] == Scalar(0)) return false;  // a root at 0
  const Coefficients<Scalar> q = with_roots_scaled(p, root_scale_exponent(p));
  const Scalar sign = q[0] > 0 ? Scalar(1) : Scalar(-1);
  const Scalar tol = Scalar(64) * std::numeric_limits<Scalar>::epsilon() * max_abs_coefficient(q);
  const auto width = static_cast<std::size_t>(degree / 2 + 1);
  std::vector<Scalar> upper(width, Scalar(0)), lower(width, Scalar(0)), next(width);
  for (Index i = 0; i <= degree; ++i) (i % 2 == 0 ? upper : lower)[i / 2] = sign * q[i];
  for (Index row = 1; row <= degree; ++row) {
    if (!(lower[0] > tol)) return false;
    const Scalar ratio = upper[0] / lower[0];
    for (std::size_t j = 0; j + 1 < width; ++j) next[j] = upper[j + 1] - ratio * lower[j + 1];
    next[width - 1] = Scalar(0);
    std::swap(upper, lower);
    std::swap(lower, next);
  }
  return true;
}

/// Sturm count of the distinct real roots in (a, ∞) (see `count_real_roots_above`);
/// p and a finite.
template <typename Scalar>
[[nodiscard]] Index count_real_roots_above(const Coefficients<Scalar>& p, Scalar a, Scalar relative_tolerance) {
  const auto trimmed = [&](const Coefficients<Scalar>& q) {
    const Scalar scale = max_abs_coefficient(q);
    Index first = 0;
    while (first < std::ssize(q) && std::abs(q[first]) <= relative_tolerance * scale) ++first;
    return without_leading(q, first);
  };
  // Scale invariance: the roots (and a) divided by 2^e, near their geometric
  // mean magnitude, so that the relative trims see x² − 1e-12 as x² − 1.
  Index lead = 0;
  while (lead < std::ssize(p) && p[lead] == Scalar(0)) ++lead;
  if (std::ssize(p) - lead <= 1) return 0;
  const Coefficients<Scalar> exact = without_leading(p, lead);
  const int e = root_scale_exponent(exact);
  a = std::clamp(std::ldexp(a, -e), std::numeric_limits<Scalar>::lowest(), std::numeric_limits<Scalar>::max());
  std::vector<Coefficients<Scalar>> chain;
  chain.push_back(trimmed(with_roots_scaled(exact, e)));
  if (chain[0].size() <= 1) return 0;
  const Index d = std::ssize(chain[0]) - 1;
  Coefficients<Scalar> derivative(static_cast<std::size_t>(d));
  for (Index i = 0; i < d; ++i) derivative[i] = Scalar(d - i) * chain[0][i];
  chain.push_back(trimmed(derivative));
  while (chain.back().size() > 1) {
    // r = rem(p_{k−1}, p_k) by long division, in place on a copy of p_{k−1}.
    Coefficients<Scalar> r = chain[chain.size() - 2];
    const Coefficients<Scalar>& q = chain.back();
    const Index nq = std::ssize(q), nr = std::ssize(r);
    const Scalar keep = max_abs_coefficient(r);
    for (Index shift = 0; shift + nq <= nr; ++shift) {
      const Scalar factor = r[shift] / q[0];
      for (Index i = 0; i < nq; ++i) r[shift + i] -= factor * q[i];
      r[shift] = Scalar(0);
    }
    // The remainder is the last nq − 1 coefficients. Scale-aware trim:
    // compare with the dividend, not with the (small) remainder itself.
    Index first = nr - (nq - 1);
    while (first < nr && std::abs(r[first]) <= relative_tolerance * keep) ++first;
    if (first == nr) break;  // p has repeated roots: the chain ends at their gcd
    Coefficients<Scalar> next = without_leading(r, first);
    for (Scalar& x : next) x = -x;
    chain.push_back(std::move(next));
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
  const auto at_a = [&](const Coefficients<Scalar>& q) {
    Scalar v = 0;
    for (Scalar x : q) v = v * a + x;
    return v;
  };
  const auto at_infinity = [](const Coefficients<Scalar>& q) { return q[0]; };
  return sign_changes(at_a) - sign_changes(at_infinity);
}

/// Product of two polynomials (convolution of the coefficients).
template <typename Scalar>
[[nodiscard]] Coefficients<Scalar> multiply_coefficients(const Coefficients<Scalar>& a, const Coefficients<Scalar>& b) {
  if (a.empty() || b.empty()) return {};
  Coefficients<Scalar> c(a.size() + b.size() - 1, Scalar(0));
  for (std::size_t i = 0; i < a.size(); ++i)
    for (std::size_t j = 0; j < b.size(); ++j) c[i + j] += a[i] * b[j];
  return c;
}

}  // namespace adaptobs::detail
