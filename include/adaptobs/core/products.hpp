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

}  // namespace adaptobs::detail
