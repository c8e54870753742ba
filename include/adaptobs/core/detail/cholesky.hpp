#pragma once
/// \file
/// Cholesky factorization of a small symmetric positive definite matrix and the
/// triangular solves around it, as plain loops.
///
/// Every update that weighs an error by an inverse covariance factors one: the
/// innovation covariance of the Kalman filters and Riccati recursions, the
/// \f$R + \varphi^T\Gamma\varphi\f$ of the least-squares laws, a few rows each. The
/// loops below do the arithmetic of Eigen's `LLT` (left-looking Cholesky,
/// forward and back substitution) for any size, fixed or dynamic, without its
/// blocked kernels, which are costly to compile for every matrix type.

#include <adaptobs/core/dimensions.hpp>

#include <Eigen/Core>

#include <cmath>

namespace adaptobs::detail {

/// `cholesky_in_place` (below) for large matrices: column j of L from the
/// columns before it, \f$a_{j:n,j} \leftarrow a_{j:n,j} - L_{j:n,0:j}L_{j,0:j}^T\f$, as
/// axpys down the columns.
template <class Derived>
[[nodiscard]] bool cholesky_by_columns_in_place(Eigen::MatrixBase<Derived>& a) {
  using Scalar = typename Derived::Scalar;
  const Index n = a.rows();
  for (Index j = 0; j < n; ++j) {
    for (Index k = 0; k < j; ++k) {
      const Scalar ljk = a(j, k);
      for (Index i = j; i < n; ++i) a(i, j) -= a(i, k) * ljk;
    }
    const Scalar pivot = a(j, j);
    if (!(pivot > Scalar(0)) || !std::isfinite(pivot)) return false;
    const Scalar root = std::sqrt(pivot);
    a(j, j) = root;
    for (Index i = j + 1; i < n; ++i) a(i, j) /= root;
  }
  return true;
}

/// Cholesky factorization of the symmetric matrix held in `a` (lower triangle
/// read), in place, column by column (left-looking). Returns false at the first
/// pivot that is not positive and finite (NaN included), leaving `a` partly
/// overwritten; true means `a` was positive definite and its lower triangle now
/// holds L. No storage, so it also serves as a definiteness test on a workspace,
/// faster than `LLT` on the augmented Kalman update (docs/performance.md).
template <class Derived>
[[nodiscard]] bool cholesky_in_place(Eigen::MatrixBase<Derived>& a) {
  using Scalar = typename Derived::Scalar;
  const Index n = a.rows();
  // Two loop orders, with the same subtractions in the same order for every
  // entry, so the same factor to the bit. Up to a few dozen rows the row-by-row
  // dot products below keep each sum in a register, the faster order; beyond,
  // they read L's rows with a stride of n, and the column-by-column order, which
  // runs down contiguous columns, is faster (docs/performance.md).
  constexpr int large = 24;
  if constexpr (Derived::RowsAtCompileTime == Eigen::Dynamic || Derived::RowsAtCompileTime > large) {
    if (n > large) return cholesky_by_columns_in_place(a);
  }
  for (Index j = 0; j < n; ++j) {
    Scalar pivot = a(j, j);
    for (Index k = 0; k < j; ++k) pivot -= a(j, k) * a(j, k);
    if (!(pivot > Scalar(0)) || !std::isfinite(pivot)) return false;
    const Scalar root = std::sqrt(pivot);
    a(j, j) = root;
    for (Index i = j + 1; i < n; ++i) {
      Scalar v = a(i, j);
      for (Index k = 0; k < j; ++k) v -= a(i, k) * a(j, k);
      a(i, j) = v / root;
    }
  }
  return true;
}

/// The factor L of \f$A = LL^T\f$ (`Square` is A's matrix type), with the solves
/// the updates need. Solving before a successful `compute` is a logic error.
template <class Square>
class CholeskyFactor {
 public:
  CholeskyFactor() = default;
  /// Storage for an n × n factor (run-time sizes: allocated here, never in `compute`).
  explicit CholeskyFactor(Index n) { l_.setZero(n, n); }

  /// Factors the symmetric `a` (lower triangle read). False when `a` is not
  /// positive definite or not finite; then no solve may follow.
  template <class Derived>
  [[nodiscard]] bool compute(const Eigen::MatrixBase<Derived>& a) {
    l_ = a;
    return cholesky_in_place(l_);
  }

  /// \f$B \leftarrow L^{-1}B\f$ (forward substitution).
  template <class Derived>
  void solve_lower_in_place(Eigen::MatrixBase<Derived>& b) const {
    const Index n = l_.rows();
    for (Index j = 0; j < b.cols(); ++j)
      for (Index k = 0; k < n; ++k) {
        b(k, j) /= l_(k, k);
        for (Index i = k + 1; i < n; ++i) b(i, j) -= l_(i, k) * b(k, j);
      }
  }

  /// \f$B \leftarrow A^{-1}B = L^{-T}L^{-1}B\f$.
  template <class Derived>
  void solve_in_place(Eigen::MatrixBase<Derived>& b) const {
    solve_lower_in_place(b);
    const Index n = l_.rows();
    for (Index j = 0; j < b.cols(); ++j)
      for (Index k = n - 1; k >= 0; --k) {  // Lᵀx = z: row k of Lᵀ is column k of L
        for (Index i = k + 1; i < n; ++i) b(k, j) -= l_(i, k) * b(i, j);
        b(k, j) /= l_(k, k);
      }
  }

  /// \f$B \leftarrow BL^{-T}\f$, i.e. \f$(L^{-1}B^T)^T\f$. Each row of B is solved
  /// independently; the loops run over whole columns so that the rows go
  /// together (vectorized), each entry seeing the same operations in the same
  /// order as a row-by-row substitution.
  template <class Derived>
  void solve_lower_transposed_on_the_right(Eigen::MatrixBase<Derived>& b) const {
    const Index n = l_.rows();
    for (Index k = 0; k < n; ++k) {
      b.col(k) /= l_(k, k);
      for (Index i = k + 1; i < n; ++i) b.col(i) -= l_(i, k) * b.col(k);
    }
  }

  /// \f$B \leftarrow BA^{-1} = BL^{-T}L^{-1}\f$ (A is symmetric: the transpose of
  /// \f$A^{-1}B^T\f$), by columns as above.
  template <class Derived>
  void solve_on_the_right_in_place(Eigen::MatrixBase<Derived>& b) const {
    solve_lower_transposed_on_the_right(b);
    const Index n = l_.rows();
    for (Index k = n - 1; k >= 0; --k) {
      for (Index i = k + 1; i < n; ++i) b.col(k) -= l_(i, k) * b.col(i);
      b.col(k) /= l_(k, k);
    }
  }

  /// L in the lower triangle (the strict upper triangle holds what `compute` was given).
  [[nodiscard]] const Square& factor() const noexcept { return l_; }

 private:
  Square l_;
};

}  // namespace adaptobs::detail
