#pragma once
/// \file
/// Matrix products of the update paths: `dst = lhs·rhs`, `dst += lhs·rhs` and
/// `dst −= lhs·rhs`, with the evaluation chosen from the sizes.
///
/// For a product of fixed-size operands Eigen switches from the coefficient-based
/// (fully unrolled, register-resident) evaluation to its cache-blocked GEMM
/// kernel once rows + cols + depth reaches 20, e.g. for an 8 × 8 times 8 × 4
/// product. The GEMM kernel's packing costs more than it saves at these sizes,
/// so small fixed-size products (every dimension at most 16) are evaluated
/// lazily here; dynamic or large products keep the GEMM kernel. One function
/// for the three forms keeps the choice, and the empty-product case, in one place.
///
/// The operands must not alias the destination.

#include <Eigen/Core>

namespace adaptobs::detail {

/// How `accumulate_product` combines the product with the destination.
enum class Combine { assign, add, subtract };

template <class Lhs, class Rhs>
inline constexpr bool small_fixed_product =
    Lhs::RowsAtCompileTime != Eigen::Dynamic && Lhs::ColsAtCompileTime != Eigen::Dynamic &&
    Rhs::ColsAtCompileTime != Eigen::Dynamic && Lhs::RowsAtCompileTime <= 16 && Lhs::ColsAtCompileTime <= 16 &&
    Rhs::ColsAtCompileTime <= 16;

/// `dst (=, +=, −=) lhs·rhs`. An empty inner dimension (a model without inputs
/// or without parameters) gives the zero product without forming it: Eigen's
/// coefficient-based product would still form row views of `lhs`, which has no
/// storage, an offset applied to a null pointer.
template <Combine how, class Dst, class Lhs, class Rhs>
void accumulate_product(Eigen::MatrixBase<Dst>& dst, const Eigen::MatrixBase<Lhs>& lhs,
                        const Eigen::MatrixBase<Rhs>& rhs) {
  if (Lhs::ColsAtCompileTime == 0 || lhs.cols() == 0) {
    if constexpr (how == Combine::assign) dst.setZero();
  } else if constexpr (Lhs::ColsAtCompileTime != 0) {  // (an empty product type has no evaluator)
    if constexpr (small_fixed_product<Lhs, Rhs>) {
      if constexpr (how == Combine::assign) {
        dst.noalias() = lhs.derived().lazyProduct(rhs.derived());
      } else if constexpr (how == Combine::add) {
        dst.noalias() += lhs.derived().lazyProduct(rhs.derived());
      } else {
        dst.noalias() -= lhs.derived().lazyProduct(rhs.derived());
      }
    } else if constexpr (how == Combine::assign) {
      dst.noalias() = lhs.derived() * rhs.derived();
    } else if constexpr (how == Combine::add) {
      dst.noalias() += lhs.derived() * rhs.derived();
    } else {
      dst.noalias() -= lhs.derived() * rhs.derived();
    }
  }
}

/// `dst = lhs·rhs`; `dst` may be a block expression.
template <class Dst, class Lhs, class Rhs>
void set_product(Dst&& dst, const Eigen::MatrixBase<Lhs>& lhs, const Eigen::MatrixBase<Rhs>& rhs) {
  accumulate_product<Combine::assign>(dst, lhs, rhs);
}

/// `dst += lhs·rhs`.
template <class Dst, class Lhs, class Rhs>
void add_product(Dst&& dst, const Eigen::MatrixBase<Lhs>& lhs, const Eigen::MatrixBase<Rhs>& rhs) {
  accumulate_product<Combine::add>(dst, lhs, rhs);
}

/// `dst −= lhs·rhs`.
template <class Dst, class Lhs, class Rhs>
void subtract_product(Dst&& dst, const Eigen::MatrixBase<Lhs>& lhs,
                      const Eigen::MatrixBase<Rhs>& rhs) {
  accumulate_product<Combine::subtract>(dst, lhs, rhs);
}

}  // namespace adaptobs::detail
