#pragma once
/// \file
/// Finiteness tests of the update paths and of argument checks.

#include <Eigen/Core>

#include <cmath>
#include <type_traits>

namespace adaptobs::detail {

/// True when every coefficient of every argument is finite.
///
/// Sums \f$0\cdot v_i\f$ over all coefficients: the sum is 0 when every
/// \f$v_i\f$ is finite and NaN as soon as one is NaN or ±Inf (0·Inf = NaN), so
/// one vectorized reduction replaces a compare-and-branch per coefficient.
/// (Like Eigen's `allFinite`, this relies on IEEE arithmetic: not valid under
/// `-ffast-math`.)
template <class First, class... Rest>
[[nodiscard]] bool all_finite(const Eigen::DenseBase<First>& first, const Eigen::DenseBase<Rest>&... rest) {
  using Scalar = typename First::Scalar;
  const auto zero_times = [](const auto& block) {
    using Block = std::remove_cvref_t<decltype(block.derived())>;
    if constexpr (Block::SizeAtCompileTime != Eigen::Dynamic && Block::SizeAtCompileTime <= 2) {
      // At most two coefficients (the inputs, outputs and parameters of small
      // models): their products directly, without instantiating Eigen's
      // reduction for the type; the same operations at run time.
      Scalar sum(0);
      for (Eigen::Index i = 0; i < Block::SizeAtCompileTime; ++i) sum += block.derived().coeff(i) * Scalar(0);
      return sum;
    } else {
      return block.size() == 0 ? Scalar(0) : (block.derived().array() * Scalar(0)).sum();
    }
  };
  const Scalar sum = (zero_times(first) + ... + zero_times(rest));
  return sum == sum;
}

/// True when the `size` entries from `data` are finite: 0·v is 0 for a finite v
/// and NaN for NaN or ±Inf, also for complex v.
template <typename Scalar>
[[nodiscard]] bool finite_storage(const Scalar* data, Eigen::Index size) {
  for (Eigen::Index i = 0; i < size; ++i)
    if (!(data[i] * Scalar(0) == Scalar(0))) return false;
  return true;
}

/// True when every coefficient of m is finite: the test of the argument checks.
/// Fixed sizes take a loop over the coefficients, which compiles in a fraction of
/// the time of Eigen's vectorized reduction (one per matrix type); a plain
/// matrix of fixed size is read through its storage, one loop per scalar type
/// for all of them (a constructor checks many small gains of distinct types).
/// Dynamic sizes, which can be large, take the reduction (`all_finite`).
template <class Derived>
[[nodiscard]] bool finite_entries(const Eigen::DenseBase<Derived>& m) {
  if constexpr (Derived::SizeAtCompileTime == Eigen::Dynamic) {
    return all_finite(m);
  } else if constexpr (std::is_base_of_v<Eigen::PlainObjectBase<Derived>, Derived>) {
    return finite_storage(m.derived().data(), m.size());
  } else {
    for (Eigen::Index j = 0; j < m.cols(); ++j)
      for (Eigen::Index i = 0; i < m.rows(); ++i)
        if (!std::isfinite(m.derived().coeff(i, j))) return false;
    return true;
  }
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
  if constexpr (sizeof...(Rest) > 0) return all_finite(rest...);
  return true;
}

}  // namespace adaptobs::detail
