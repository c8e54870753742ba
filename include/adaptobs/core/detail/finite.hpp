#pragma once
/// \file
/// The finiteness test of the update paths and of the argument checks.

#include <Eigen/Core>

#include <cmath>

namespace adaptobs::detail {

/// True when every coefficient of every argument is finite. The sum of
/// \f$0\cdot v_i\f$ over all of them is 0 when every \f$v_i\f$ is finite and NaN as
/// soon as one is NaN or ±Inf (0·Inf = NaN): one vectorized reduction instead of
/// a compare and a branch per coefficient, on every update path. Like Eigen's
/// `allFinite`, it relies on IEEE arithmetic: not valid under `-ffast-math`.
template <class First, class... Rest>
[[nodiscard]] bool all_finite(const Eigen::DenseBase<First>& first, const Eigen::DenseBase<Rest>&... rest) {
  using Scalar = typename First::Scalar;
  const Scalar sum = ((first.derived().array() * Scalar(0)).sum() + ... + (rest.derived().array() * Scalar(0)).sum());
  return sum == sum;
}

/// True when the entries of y whose channel is present (all of them for a null
/// mask) and every entry of `rest` (the input, a regressor) are finite: the
/// check of a sample with some output channels absent, whose other entries may be NaN.
template <class Y, class Mask, class... Rest>
[[nodiscard]] bool finite_measured(const Eigen::MatrixBase<Y>& y, const Mask* present,
                                   const Eigen::DenseBase<Rest>&... rest) {
  if (!present) return all_finite(y, rest...);
  for (Eigen::Index i = 0; i < y.size(); ++i)
    if ((*present)(i) && !std::isfinite(y(i))) return false;
  return all_finite(rest...);
}

}  // namespace adaptobs::detail
