#pragma once
/// \file
/// Matrix products of the update paths: `dst = lhs·rhs`, `dst += lhs·rhs` and
/// `dst −= lhs·rhs`, with the evaluation chosen from the sizes.
///
/// Small fixed-size products (every dimension at most 16) are plain loops over
/// the coefficients. Eigen's own coefficient-based product would unroll them
/// too, but through a recursive template per coefficient and per term: on the
/// observers' 2 × 2 … 8 × 8 products that template work was the largest part
/// of a user program's compile time, and the loops, unrolled by the optimizer,
/// run as fast. Each sum is taken in the order k = 0, 1, …, as Eigen's
/// vectorized product does. Dynamic or larger products use Eigen's product
/// (its cache-blocked kernel for large sizes).
///
/// The operands are matrices, blocks or transposes of them (whose coefficients
/// are read directly), and must not alias the destination.

#include <Eigen/Core>

namespace adaptobs::detail {

/// How `accumulate_product` combines the product with the destination.
enum class Combine { assign, add, subtract };

template <class Lhs, class Rhs>
inline constexpr bool small_fixed_product =
    Lhs::RowsAtCompileTime != Eigen::Dynamic && Lhs::ColsAtCompileTime != Eigen::Dynamic &&
    Rhs::ColsAtCompileTime != Eigen::Dynamic && Lhs::RowsAtCompileTime <= 16 && Lhs::ColsAtCompileTime <= 16 &&
    Rhs::ColsAtCompileTime <= 16;

/// `dst (=, +=, −=) lhs·rhs`; an empty inner dimension gives the zero product.
template <Combine how, class Dst, class Lhs, class Rhs>
void accumulate_product(Eigen::MatrixBase<Dst>& dst, const Eigen::MatrixBase<Lhs>& lhs,
                        const Eigen::MatrixBase<Rhs>& rhs) {
  using Scalar = typename Dst::Scalar;
  if constexpr (small_fixed_product<Lhs, Rhs>) {
    constexpr int rows = Lhs::RowsAtCompileTime, depth = Lhs::ColsAtCompileTime, cols = Rhs::ColsAtCompileTime;
    // Column j of the product as a sum of columns of lhs (contiguous, so the
    // inner loop vectorizes); each coefficient is summed in the order k = 0, 1, ….
    for (int j = 0; j < cols; ++j) {
      Scalar column[rows > 0 ? rows : 1] = {};
      for (int k = 0; k < depth; ++k) {
        const Scalar factor = rhs.coeff(k, j);
        for (int i = 0; i < rows; ++i) column[i] += lhs.coeff(i, k) * factor;
      }
      for (int i = 0; i < rows; ++i) {
        if constexpr (how == Combine::assign) {
          dst.coeffRef(i, j) = column[i];
        } else if constexpr (how == Combine::add) {
          dst.coeffRef(i, j) += column[i];
        } else {
          dst.coeffRef(i, j) -= column[i];
        }
      }
    }
  } else if (Lhs::ColsAtCompileTime == 0 || lhs.cols() == 0) {
    if constexpr (how == Combine::assign) dst.setZero();
  } else if constexpr (Lhs::ColsAtCompileTime != 0) {  // (an empty product type has no evaluator)
    if constexpr (how == Combine::assign) {
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
