#pragma once
/// \file
/// Matrix products of the update paths: `dst = lhs·rhs`, `dst += lhs·rhs` and
/// `dst −= lhs·rhs`, with the evaluation chosen from the sizes.
///
/// Three evaluations, by size:
/// - **tiny** (fixed, every dimension at most 3: the 3 × 3 times 3 × 1 and
///   1 × 2 times 2 × 2 products of the third-order and SISO observers): plain
///   loops over the coefficients, which the compiler unrolls. Eigen's lazy
///   product, costly to instantiate per pair of operand types, vectorizes
///   little at these sizes (docs/performance.md).
/// - **small** (fixed, every dimension at most 16): Eigen's lazy, coefficient-based
///   product, vectorized and unrolled. For fixed-size operands Eigen itself
///   switches to its cache-blocked GEMM kernel once rows + cols + depth reaches
///   20, e.g. for an 8 × 8 times 8 × 4 product, where the kernel's packing costs
///   more than it saves.
/// - dynamic or large: the GEMM kernel.
///
/// One function for the three forms keeps the choice, and the empty-product
/// case, in one place.
///
/// The operands must not alias the destination.

#include <adaptobs/core/dimensions.hpp>

#include <Eigen/Core>

namespace adaptobs::detail {

/// How `accumulate_product` combines the product with the destination.
enum class Combine { assign, add, subtract };

/// Every dimension of `lhs·rhs` fixed and at most `limit`.
template <class Lhs, class Rhs, int limit>
inline constexpr bool fixed_product_within =
    Lhs::RowsAtCompileTime != Eigen::Dynamic && Lhs::ColsAtCompileTime != Eigen::Dynamic &&
    Rhs::ColsAtCompileTime != Eigen::Dynamic && Lhs::RowsAtCompileTime <= limit && Lhs::ColsAtCompileTime <= limit &&
    Rhs::ColsAtCompileTime <= limit;

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
    if constexpr (fixed_product_within<Lhs, Rhs, 3>) {
      // Each entry an inner product summed in ascending order.
      for (Index j = 0; j < Rhs::ColsAtCompileTime; ++j)
        for (Index i = 0; i < Lhs::RowsAtCompileTime; ++i) {
          typename Dst::Scalar sum = lhs.coeff(i, 0) * rhs.coeff(0, j);
          for (Index k = 1; k < Lhs::ColsAtCompileTime; ++k) sum += lhs.coeff(i, k) * rhs.coeff(k, j);
          if constexpr (how == Combine::assign) {
            dst.coeffRef(i, j) = sum;
          } else if constexpr (how == Combine::add) {
            dst.coeffRef(i, j) += sum;
          } else {
            dst.coeffRef(i, j) -= sum;
          }
        }
    } else if constexpr (fixed_product_within<Lhs, Rhs, 16>) {
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
void subtract_product(Dst&& dst, const Eigen::MatrixBase<Lhs>& lhs, const Eigen::MatrixBase<Rhs>& rhs) {
  accumulate_product<Combine::subtract>(dst, lhs, rhs);
}

}  // namespace adaptobs::detail
