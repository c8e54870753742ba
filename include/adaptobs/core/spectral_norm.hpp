#pragma once
/// \file
/// Spectral norm (largest singular value) of a small matrix.

#include <adaptobs/core/symmetric_eigenvalues.hpp>

#include <Eigen/Core>

#include <algorithm>
#include <cmath>

namespace adaptobs {

/// \f$\|M\|_2 = \sqrt{\lambda_{\max}(M^TM)}\f$, through the Gram matrix of the
/// smaller side (cheap for the m × p matrices observers monitor), whose
/// eigenvalues come from `symmetric_eigenvalues` (Jacobi).
template <class Derived>
[[nodiscard]] typename Derived::Scalar spectral_norm(const Eigen::MatrixBase<Derived>& m) {
  using Scalar = typename Derived::Scalar;
  if (m.size() == 0) return Scalar(0);
  constexpr int R = Derived::RowsAtCompileTime;
  constexpr int C = Derived::ColsAtCompileTime;
  Scalar largest;
  if (m.cols() <= m.rows()) {
    const Eigen::Matrix<Scalar, C, C> gram = m.transpose() * m;
    largest = symmetric_eigenvalues(gram)(m.cols() - 1);
  } else {
    const Eigen::Matrix<Scalar, R, R> gram = m * m.transpose();
    largest = symmetric_eigenvalues(gram)(m.rows() - 1);
  }
  return std::sqrt(std::max(largest, Scalar(0)));
}

}  // namespace adaptobs
