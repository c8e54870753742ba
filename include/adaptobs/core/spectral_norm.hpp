#pragma once
/// \file
/// Spectral norm (largest singular value) of a small matrix.

#include <adaptobs/core/detail/products.hpp>
#include <adaptobs/core/symmetric_eigenvalues.hpp>

#include <Eigen/Core>

#include <algorithm>
#include <cmath>

namespace adaptobs {

/// \f$\|M\|_2 = s\sqrt{\lambda_{\max}((M/s)^T(M/s))}\f$ with s = max |m_ij|, through
/// the Gram matrix of the smaller side (cheap for the m × p matrices observers
/// monitor), whose eigenvalues come from `symmetric_eigenvalues` (Jacobi).
/// Dividing by s first keeps the Gram matrix from overflowing (or underflowing)
/// for entries beyond about 10^154 (or below 10^−154): the norm of any finite M
/// is finite unless it exceeds the floating-point range itself. An M with a NaN
/// entry has norm NaN; one with ∞ and no NaN, ∞.
template <class Derived>
[[nodiscard]] typename Derived::Scalar spectral_norm(const Eigen::MatrixBase<Derived>& m) {
  using Scalar = typename Derived::Scalar;
  if (m.size() == 0) return Scalar(0);
  constexpr int R = Derived::RowsAtCompileTime;
  constexpr int C = Derived::ColsAtCompileTime;
  // NaN wins over ∞ (a plain maxCoeff keeps whichever its scan order meets).
  const Scalar scale = m.cwiseAbs().template maxCoeff<Eigen::PropagateNaN>();
  if (!(scale > Scalar(0)) || !std::isfinite(scale)) return scale;
  const typename Derived::PlainObject scaled = m / scale;
  // The Gram matrix of the smaller side; with fixed sizes the other branch is not compiled.
  constexpr bool fixed = R != Eigen::Dynamic && C != Eigen::Dynamic;
  Scalar largest;
  if (fixed ? C <= R : m.cols() <= m.rows()) {
    if constexpr (!fixed || C <= R) {
      Eigen::Matrix<Scalar, C, C> gram;
      detail::set_product(gram, scaled.transpose(), scaled);
      largest = symmetric_eigenvalues(gram)(m.cols() - 1);
    }
  } else {
    if constexpr (!fixed || C > R) {
      Eigen::Matrix<Scalar, R, R> gram;
      detail::set_product(gram, scaled, scaled.transpose());
      largest = symmetric_eigenvalues(gram)(m.rows() - 1);
    }
  }
  return scale * std::sqrt(std::max(largest, Scalar(0)));
}

}  // namespace adaptobs
