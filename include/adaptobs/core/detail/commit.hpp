#pragma once
/// \file
/// Building blocks of the compute-then-commit update used by every observer:
/// a step is computed into workspace, checked for finiteness, and only then
/// moved into the observer's state, so a rejected step changes nothing.

#include <Eigen/Core>

#include <cmath>
#include <type_traits>

namespace adaptobs::detail {

/// \f$\sum_i 0\cdot v_i\f$ over the coefficients of m: 0 when every \f$v_i\f$ is
/// finite, NaN as soon as one is NaN or ±Inf (0·Inf = NaN). A fixed-size matrix
/// takes a plain loop over its storage, which the optimizer unrolls and which
/// costs little to compile; anything else Eigen's vectorized reduction.
template <class Derived>
[[nodiscard]] typename Derived::Scalar zero_times(const Eigen::DenseBase<Derived>& m) {
  using Scalar = typename Derived::Scalar;
  if constexpr (std::is_base_of_v<Eigen::PlainObjectBase<Derived>, Derived> &&
                Derived::SizeAtCompileTime != Eigen::Dynamic) {
    Scalar sum(0);
    const Scalar* data = m.derived().data();
    for (int i = 0; i < Derived::SizeAtCompileTime; ++i) sum += data[i] * Scalar(0);
    return sum;
  } else {
    return m.size() == 0 ? Scalar(0) : (m.derived().array() * Scalar(0)).sum();
  }
}

/// True when every coefficient of every argument is finite: one sum of
/// `zero_times` replaces a compare-and-branch per coefficient. (Like Eigen's
/// `allFinite`, this relies on IEEE arithmetic: not valid under `-ffast-math`.)
template <class First, class... Rest>
[[nodiscard]] bool all_finite(const Eigen::DenseBase<First>& first, const Eigen::DenseBase<Rest>&... rest) {
  const typename First::Scalar sum = (zero_times(first) + ... + zero_times(rest));
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
  if constexpr (sizeof...(Rest) > 0) return all_finite(rest...);
  return true;
}

/// Moves a computed value into place: a pointer swap for heap storage, a copy
/// for fixed-size storage (where a swap would cost three copies).
template <class Derived>
void commit(Eigen::PlainObjectBase<Derived>& destination, Eigen::PlainObjectBase<Derived>& computed) {
  if constexpr (Derived::SizeAtCompileTime == Eigen::Dynamic) {
    destination.swap(computed);
  } else {
    destination = computed;
  }
}

}  // namespace adaptobs::detail
