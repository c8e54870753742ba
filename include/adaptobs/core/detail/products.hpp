#pragma once
/// \file
/// Matrix products that pick Eigen's evaluation strategy from the sizes.
///
/// For a product of fixed-size operands Eigen switches from the coefficient-based
/// (fully unrolled, register-resident) evaluation to its cache-blocked GEMM
/// kernel once rows + cols + depth reaches 20, e.g. for an 8 × 8 times 8 × 4
/// product. The GEMM kernel's packing costs more than it saves at these sizes,
/// so small fixed-size products are evaluated lazily here; dynamic or large
/// products keep the GEMM kernel.

#include <Eigen/Core>

namespace adaptobs::detail {

template <class Lhs, class Rhs>
inline constexpr bool use_lazy_product =
    Lhs::RowsAtCompileTime != Eigen::Dynamic && Lhs::ColsAtCompileTime != Eigen::Dynamic &&
    Rhs::ColsAtCompileTime != Eigen::Dynamic && Lhs::RowsAtCompileTime <= 16 && Lhs::ColsAtCompileTime <= 16 &&
    Rhs::ColsAtCompileTime <= 16;

/// `lhs * rhs`, evaluated coefficient-wise when both operands are small and fixed.
template <class Lhs, class Rhs>
[[nodiscard]] auto product(const Eigen::MatrixBase<Lhs>& lhs, const Eigen::MatrixBase<Rhs>& rhs) {
  if constexpr (use_lazy_product<Lhs, Rhs>) {
    return lhs.derived().lazyProduct(rhs.derived());
  } else {
    return lhs.derived() * rhs.derived();
  }
}

/// True when `lhs * rhs` has an empty inner dimension (a model without inputs or
/// without parameters). Eigen's coefficient-based product would then still form
/// row views of `lhs`, which has no storage: an offset applied to a null pointer.
template <class Lhs>
[[nodiscard]] bool empty_inner_dimension(const Eigen::MatrixBase<Lhs>& lhs) {
  return Lhs::ColsAtCompileTime == 0 || lhs.cols() == 0;
}

/// `dst = lhs * rhs`, zero when the inner dimension is empty.
template <class Dst, class Lhs, class Rhs>
void set_product(Eigen::MatrixBase<Dst>& dst, const Eigen::MatrixBase<Lhs>& lhs, const Eigen::MatrixBase<Rhs>& rhs) {
  if (empty_inner_dimension(lhs)) {
    dst.setZero();
  } else if constexpr (Lhs::ColsAtCompileTime != 0) {
    dst.noalias() = lhs.derived() * rhs.derived();
  }
}

/// `dst += lhs * rhs`, nothing when the inner dimension is empty.
template <class Dst, class Lhs, class Rhs>
void add_product(Eigen::MatrixBase<Dst>& dst, const Eigen::MatrixBase<Lhs>& lhs, const Eigen::MatrixBase<Rhs>& rhs) {
  if constexpr (Lhs::ColsAtCompileTime != 0) {
    if (!empty_inner_dimension(lhs)) dst.noalias() += lhs.derived() * rhs.derived();
  }
}

}  // namespace adaptobs::detail
