#pragma once
/// \file
/// Spectral norm (largest singular value) of a small matrix.

#include <Eigen/Core>
#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>

namespace adaptobs {

/// \f$\|M\|_2 = \sqrt{\lambda_{\max}(M^TM)}\f$, through the Gram matrix of the
/// smaller side (cheap for the m × p matrices observers monitor).
template <class Derived>
[[nodiscard]] typename Derived::Scalar spectral_norm(const Eigen::MatrixBase<Derived>& m) {
  using Scalar = typename Derived::Scalar;
  if (m.size() == 0) return Scalar(0);
  constexpr int R = Derived::RowsAtCompileTime;
  constexpr int C = Derived::ColsAtCompileTime;
  Scalar largest;
  if (m.cols() <= m.rows()) {
    const Eigen::Matrix<Scalar, C, C> gram = m.transpose() * m;
    largest = Eigen::SelfAdjointEigenSolver<Eigen::Matrix<Scalar, C, C>>(gram, Eigen::EigenvaluesOnly).eigenvalues()(m.cols() - 1);
  } else {
    const Eigen::Matrix<Scalar, R, R> gram = m * m.transpose();
    largest = Eigen::SelfAdjointEigenSolver<Eigen::Matrix<Scalar, R, R>>(gram, Eigen::EigenvaluesOnly).eigenvalues()(m.rows() - 1);
  }
  return std::sqrt(std::max(largest, Scalar(0)));
}

}  // namespace adaptobs
