#pragma once
/// \file
/// Schur stability of a square matrix from repeated squaring, without eigenvalues.
///
/// Closed-loop checks such as "A − KC is Schur" only need to know on which
/// side of 1 the spectral radius lies. For any submultiplicative norm,
/// \f$\rho(M) \le \|M^{m}\|^{1/m}\f$ for every m, and the bound tends to
/// \f$\rho(M)\f$ as m grows (Gelfand's formula). Squaring gives m = 2^k with
/// k matrix products, and rescaling each square to unit norm keeps the powers
/// representable. This needs nothing beyond matrix products, so it is cheap
/// to compile, unlike a real Schur decomposition.

#include <adaptobs/core/precompiled.hpp>
#include <adaptobs/core/validation.hpp>

#include <Eigen/Core>

#include <cmath>
#include <limits>

namespace adaptobs {

/// An upper bound on the spectral radius, \f$\|M^{2^k}\|_F^{2^{-k}}\f$, tightened by
/// squaring until it falls below `target` (then `ρ(M) < target` is proven) or
/// stops decreasing (then it equals ρ(M) to within rounding). At most 64 squarings.
template <class Derived>
[[nodiscard]] typename Derived::Scalar spectral_radius_bound(const Eigen::MatrixBase<Derived>& m,
                                                             typename Derived::Scalar target = 0) {
  using Scalar = typename Derived::Scalar;
  require_square(m, "spectral_radius_bound", "M");
  if (m.size() == 0) return Scalar(0);
  if (!m.derived().allFinite()) return std::numeric_limits<Scalar>::infinity();
  const Scalar largest = m.cwiseAbs().maxCoeff();
  if (largest == Scalar(0)) return Scalar(0);
  // M^(2^k) = exp(log_scale) · power with ‖power‖ = norm, so the bound is
  // exp((log_scale + log norm) / 2^k). Starting from M / max|m_ij| keeps the
  // Frobenius norm itself from overflowing.
  Eigen::Matrix<Scalar, Derived::RowsAtCompileTime, Derived::ColsAtCompileTime> power = m / largest;
  Scalar norm = power.norm();
  Scalar log_scale = std::log(largest), exponent = 1, bound = std::exp(log_scale + std::log(norm));
  constexpr Scalar eps = std::numeric_limits<Scalar>::epsilon();
  for (int k = 1; k <= 64 && !(bound < target); ++k) {
    power /= norm;
    power = power.lazyProduct(power).eval();
    log_scale = Scalar(2) * (log_scale + std::log(norm));
    exponent *= Scalar(2);
    norm = power.norm();
    if (norm == Scalar(0)) return Scalar(0);  // nilpotent
    const Scalar next = std::exp((log_scale + std::log(norm)) / exponent);
    const bool settled = std::abs(next - bound) <= Scalar(4) * eps * bound;
    bound = std::min(bound, next);
    if (settled) break;
  }
  return bound;
}

/// Schur stability: every eigenvalue strictly inside the circle of radius 1 − margin.
template <class Derived>
[[nodiscard]] bool is_schur_stable(const Eigen::MatrixBase<Derived>& m, typename Derived::Scalar margin = 0) {
  using Scalar = typename Derived::Scalar;
  const Scalar radius = Scalar(1) - margin;
  return spectral_radius_bound(m, radius) < radius;
}

#ifdef ADAPTOBS_PRECOMPILED
ADAPTOBS_INSTANTIATE double spectral_radius_bound<Eigen::MatrixXd>(const Eigen::MatrixBase<Eigen::MatrixXd>&, double);
#endif

}  // namespace adaptobs
