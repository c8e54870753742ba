#pragma once
/// \file
/// Exponential bounds \f$\|U^k\|_2 \le M\lambda^k\f$ (k ≥ 0) for a Schur-stable matrix U.
///
/// For \f$\lambda \in (\rho(U), 1)\f$ the smallest such M is
/// \f$M(\lambda) = \sup_{k\ge0}\|S^k\|_2\f$ with \f$S = U/\lambda\f$, and it is
/// computed exactly: powers of S are formed until the first j with
/// \f$\|S^j\|_2 \le 1\f$; then every \f$k = qj + r\f$ has
/// \f$\|S^k\|_2 \le \|S^j\|_2^q\|S^r\|_2 \le \|S^r\|_2\f$, so
/// \f$M(\lambda) = \max_{0\le r<j}\|S^r\|_2\f$ (≥ 1, from k = 0). Such j exists
/// because \f$S^k \to 0\f$. A bound from a Lyapunov equation,
/// \f$M \le \sqrt{\operatorname{cond}P}\f$, is cheaper but can be several times larger.
///
/// Perturbation results such as proposition 2.1 of
/// Guiro et al. (2008) tolerate \f$\|W(k)\| < (1-\lambda)/M\f$;
/// `best_power_bound` picks the λ that maximizes that margin.

#include <adaptobs/core/detail/dynamic_copy.hpp>
#include <adaptobs/core/dimensions.hpp>
#include <adaptobs/core/precompiled.hpp>
#include <adaptobs/core/validation.hpp>
#include <adaptobs/design/stability.hpp>

#include <Eigen/Core>
#include <Eigen/SVD>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

namespace adaptobs {

namespace detail {
/// \f$\|M\|_2\f$ by a singular value decomposition (the one the design routines use anyway).
template <typename Scalar>
Scalar largest_singular_value(const DynamicMatrix<Scalar>& m) {
  if (m.size() == 0) return Scalar(0);
  return Eigen::JacobiSVD<DynamicMatrix<Scalar>>(m).singularValues()(0);
}
#ifdef ADAPTOBS_PRECOMPILED
ADAPTOBS_INSTANTIATE double largest_singular_value<double>(const DynamicMatrix<double>&);
#endif
}  // namespace detail

/// \f$\|U^k\|_2 \le M\lambda^k\f$ for every k ≥ 0.
template <typename Scalar>
struct PowerBound {
  Scalar lambda = 0;
  Scalar M = 0;
  /// \f$(1-\lambda)/M\f$: the size of perturbation \f$\|W(k)\|\f$ that \f$v_{k+1} = (U + W(k))v_k\f$ tolerates.
  [[nodiscard]] Scalar perturbation_margin() const noexcept { return (Scalar(1) - lambda) / M; }
};

/// The smallest M with \f$\|U^k\|_2 \le M\lambda^k\f$ for all k ≥ 0 (see file
/// comment); +∞ when \f$\lambda \le \rho(U)\f$ or when \f$\|(U/\lambda)^j\|_2\f$ has
/// not fallen to 1 by `max_power`.
template <class Derived>
[[nodiscard]] typename Derived::Scalar power_bound_constant(const Eigen::MatrixBase<Derived>& U,
                                                            typename Derived::Scalar lambda, Index max_power = 100000) {
  using Scalar = typename Derived::Scalar;
  using Matrix = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;
  require_square(U, "power_bound_constant", "U");
  require_finite(U, "power_bound_constant", "U");
  require_positive(lambda, "power_bound_constant", "lambda");
  const Index n = U.rows();
  if (n == 0) return Scalar(1);
  const Matrix s = detail::dynamic_copy(U) / lambda;
  Matrix power = Matrix::Identity(n, n);
  Scalar m = 1;
  for (Index j = 1; j <= max_power; ++j) {
    power = (power * s).eval();
    // λ ≤ ρ(U): the powers overflow. Stop before the SVD sees a non-finite matrix.
    if (!power.allFinite()) break;
    const Scalar norm = detail::largest_singular_value<Scalar>(power);
    if (!std::isfinite(norm)) break;
    if (norm <= Scalar(1)) return m;
    m = std::max(m, norm);
  }
  return std::numeric_limits<Scalar>::infinity();
}

/// The bound \f$(\lambda, M(\lambda))\f$ with the largest perturbation margin
/// \f$(1-\lambda)/M(\lambda)\f$ over \f$\lambda\in(\rho(U),1)\f$ (a scan of `grid`
/// points refined by golden-section search); empty when U is not Schur stable.
template <class Derived>
[[nodiscard]] std::optional<PowerBound<typename Derived::Scalar>> best_power_bound(const Eigen::MatrixBase<Derived>& U,
                                                                                   Index grid = 64) {
  using Scalar = typename Derived::Scalar;
  using Matrix = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;
  require(grid >= 2, "best_power_bound", "grid", "must be at least 2");
  require_square(U, "best_power_bound", "U");
  require_finite(U, "best_power_bound", "U");
  const Matrix u = detail::dynamic_copy(U);
  const Scalar rho = spectral_radius(u);
  if (!(rho < Scalar(1))) return std::nullopt;
  const auto margin = [&](Scalar lambda) {
    const Scalar m = power_bound_constant(u, lambda, 20000);
    return std::isfinite(m) ? (Scalar(1) - lambda) / m : Scalar(0);
  };
  const Scalar lo = std::max(rho, Scalar(0));
  const Scalar step = (Scalar(1) - lo) / Scalar(grid);
  Scalar best_lambda = lo + step;
  Scalar best = margin(best_lambda);
  for (Index i = 2; i < grid; ++i) {
    const Scalar lambda = lo + step * Scalar(i);
    const Scalar value = margin(lambda);
    if (value > best) {
      best = value;
      best_lambda = lambda;
    }
  }
  // Golden-section refinement within one grid step on either side.
  Scalar a = std::max(lo + step * Scalar(0.01), best_lambda - step);
  Scalar b = std::min(Scalar(1) - step * Scalar(0.01), best_lambda + step);
  const Scalar phi = (std::sqrt(Scalar(5)) - Scalar(1)) / Scalar(2);
  Scalar x1 = b - phi * (b - a), x2 = a + phi * (b - a);
  Scalar f1 = margin(x1), f2 = margin(x2);
  for (int it = 0; it < 30; ++it) {
    if (f1 < f2) {
      a = x1;
      x1 = x2;
      f1 = f2;
      x2 = a + phi * (b - a);
      f2 = margin(x2);
    } else {
      b = x2;
      x2 = x1;
      f2 = f1;
      x1 = b - phi * (b - a);
      f1 = margin(x1);
    }
  }
  if (f1 > best) {
    best = f1;
    best_lambda = x1;
  }
  if (f2 > best) {
    best = f2;
    best_lambda = x2;
  }
  if (!(best > Scalar(0))) return std::nullopt;
  return PowerBound<Scalar>{best_lambda, power_bound_constant(u, best_lambda)};
}

}  // namespace adaptobs
