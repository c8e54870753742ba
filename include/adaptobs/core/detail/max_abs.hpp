#pragma once
/// \file
/// The largest magnitude among a matrix's coefficients, the scale that relative
/// tolerances and trims are taken against.

#include <Eigen/Core>

namespace adaptobs::detail {

/// \f$\max_{ij}|m_{ij}|\f$, 0 for an empty m.
template <class Derived>
[[nodiscard]] typename Derived::Scalar max_abs(const Eigen::MatrixBase<Derived>& m) {
  return m.size() == 0 ? typename Derived::Scalar(0) : m.cwiseAbs().maxCoeff();
}

}  // namespace adaptobs::detail
