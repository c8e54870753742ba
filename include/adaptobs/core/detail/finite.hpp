#pragma once
/// \file
/// The finiteness test of the update paths and of the argument checks.

#include <Eigen/Core>

#include <cmath>

namespace adaptobs::detail {

/// True when every coefficient of every argument is finite (Eigen's `allFinite`,
/// which relies on IEEE arithmetic: not valid under `-ffast-math`).
template <class... Blocks>
[[nodiscard]] bool all_finite(const Eigen::DenseBase<Blocks>&... blocks) {
  return (blocks.derived().allFinite() && ...);
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
