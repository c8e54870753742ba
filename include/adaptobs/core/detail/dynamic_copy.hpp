#pragma once
/// \file
/// Entry-by-entry copies into dynamic-size matrices for design-time routines.
///
/// Design routines (pole placement, gain design, stability certificates) work
/// on dynamic-size matrices, so that their decompositions are instantiated
/// once per scalar type rather than once per combination of fixed sizes. The
/// copy goes entry by entry: Eigen's vectorized copy of a fixed-size operand
/// smaller than one SIMD packet (a 1 × 1 gain, say) into run-time-sized
/// storage reads a whole packet, which compilers flag as an out-of-bounds read.

#include <adaptobs/core/dimensions.hpp>

#include <Eigen/Core>

#include <algorithm>
#include <complex>

namespace adaptobs {
/// Eigenvalues and poles: a column of complex numbers.
template <typename Scalar>
using ComplexVector = Eigen::Matrix<std::complex<Scalar>, Eigen::Dynamic, 1>;
}  // namespace adaptobs

namespace adaptobs::detail {

template <typename Scalar>
using DynamicMatrix = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;

/// `m` as a dynamic-size matrix.
template <class Derived>
[[nodiscard]] DynamicMatrix<typename Derived::Scalar> dynamic_copy(const Eigen::MatrixBase<Derived>& m) {
  DynamicMatrix<typename Derived::Scalar> out(m.rows(), m.cols());
  for (Index j = 0; j < m.cols(); ++j)
    for (Index i = 0; i < m.rows(); ++i) out(i, j) = m(i, j);
  return out;
}

/// `m.setZero(rows, cols)` without an expression: a constructor or a workspace sizes
/// many small matrices of distinct types, and `setZero` is costly to instantiate for each.
template <class Derived>
void zero_resize(Eigen::PlainObjectBase<Derived>& m, Index rows, Index cols) {
  m.resize(rows, cols);
  std::fill_n(m.data(), m.size(), typename Derived::Scalar(0));
}

/// The same for a vector of n entries.
template <class Derived>
void zero_resize(Eigen::PlainObjectBase<Derived>& m, Index n) {
  m.resize(n);
  std::fill_n(m.data(), n, typename Derived::Scalar(0));
}

}  // namespace adaptobs::detail
