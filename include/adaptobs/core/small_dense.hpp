#pragma once
/// \file
/// Products, LU and Cholesky solves on dynamic-size matrices, written as plain loops.
///
/// Design routines (Riccati, Stein and Lyapunov solvers, stability checks) work
/// on matrices of a few to a few dozen rows, once, before the real-time loop.
/// Eigen's dynamic-size product and its blocked LU and Cholesky pull in the
/// cache-blocked GEMM and triangular-solve kernels: each instantiation costs
/// about a second of compilation at -O2, in every translation unit that calls a
/// design routine, for a speed that matters only above a hundred rows. The loops
/// here compute the same quantities with the same algorithms (inner products,
/// Gaussian elimination with partial pivoting, Cholesky), and compile in a
/// fraction of that time.

#include <adaptobs/core/dynamic_copy.hpp>
#include <adaptobs/core/validation.hpp>

#include <Eigen/Core>

#include <cmath>
#include <utility>

namespace adaptobs::detail {

/// \f$ab\f$.
template <typename Scalar>
[[nodiscard]] DynamicMatrix<Scalar> multiply(const DynamicMatrix<Scalar>& a, const DynamicMatrix<Scalar>& b) {
  DynamicMatrix<Scalar> c = DynamicMatrix<Scalar>::Zero(a.rows(), b.cols());
  for (Index j = 0; j < b.cols(); ++j)
    for (Index k = 0; k < a.cols(); ++k) {
      const Scalar bkj = b(k, j);
      for (Index i = 0; i < a.rows(); ++i) c(i, j) += a(i, k) * bkj;
    }
  return c;
}

/// \f$a^Tb\f$: inner products of columns, so both operands are read contiguously.
template <typename Scalar>
[[nodiscard]] DynamicMatrix<Scalar> multiply_transposed(const DynamicMatrix<Scalar>& a,
                                                        const DynamicMatrix<Scalar>& b) {
  DynamicMatrix<Scalar> c(a.cols(), b.cols());
  for (Index j = 0; j < b.cols(); ++j)
    for (Index i = 0; i < a.cols(); ++i) {
      Scalar s = 0;
      for (Index k = 0; k < a.rows(); ++k) s += a(k, i) * b(k, j);
      c(i, j) = s;
    }
  return c;
}

/// \f$ab^T\f$.
template <typename Scalar>
[[nodiscard]] DynamicMatrix<Scalar> multiply_by_transpose(const DynamicMatrix<Scalar>& a,
                                                          const DynamicMatrix<Scalar>& b) {
  DynamicMatrix<Scalar> c = DynamicMatrix<Scalar>::Zero(a.rows(), b.rows());
  for (Index j = 0; j < b.rows(); ++j)
    for (Index k = 0; k < a.cols(); ++k) {
      const Scalar bjk = b(j, k);
      for (Index i = 0; i < a.rows(); ++i) c(i, j) += a(i, k) * bjk;
    }
  return c;
}

/// \f$a^Txa\f$ for a symmetric x, symmetrized so that rounding leaves it exactly symmetric.
template <typename Scalar>
[[nodiscard]] DynamicMatrix<Scalar> congruence(const DynamicMatrix<Scalar>& a, const DynamicMatrix<Scalar>& x) {
  const DynamicMatrix<Scalar> c = multiply_transposed(a, multiply(x, a));
  return Scalar(0.5) * (c + c.transpose());
}

/// \f$PA = LU\f$ by Gaussian elimination with partial pivoting: L (unit lower,
/// below the diagonal) and U share `lu`; row i of PA is row `rows(i)` of A.
template <typename Scalar>
struct LuFactorization {
  DynamicMatrix<Scalar> lu;
  Eigen::Matrix<Index, Eigen::Dynamic, 1> rows;
  bool singular = false;  ///< a zero (or non-finite) pivot: no solve is attempted

  explicit LuFactorization(DynamicMatrix<Scalar> a) : lu(std::move(a)), rows(lu.rows()) {
    const Index n = lu.rows();
    for (Index i = 0; i < n; ++i) rows(i) = i;
    for (Index k = 0; k < n; ++k) {
      Index p = k;
      for (Index i = k + 1; i < n; ++i)
        if (std::abs(lu(i, k)) > std::abs(lu(p, k))) p = i;
      if (!(lu(p, k) != Scalar(0)) || !std::isfinite(lu(p, k))) {
        singular = true;
        return;
      }
      if (p != k) {
        lu.row(k).swap(lu.row(p));
        std::swap(rows(k), rows(p));
      }
      const Scalar pivot = lu(k, k);
      for (Index i = k + 1; i < n; ++i) lu(i, k) /= pivot;
      for (Index j = k + 1; j < n; ++j) {
        const Scalar ukj = lu(k, j);
        for (Index i = k + 1; i < n; ++i) lu(i, j) -= lu(i, k) * ukj;
      }
    }
  }

  /// \f$A^{-1}b\f$ by forward and back substitution.
  [[nodiscard]] DynamicMatrix<Scalar> solve(const DynamicMatrix<Scalar>& b) const {
    const Index n = lu.rows();
    DynamicMatrix<Scalar> x(n, b.cols());
    for (Index i = 0; i < n; ++i) x.row(i) = b.row(rows(i));
    for (Index j = 0; j < x.cols(); ++j) {
      for (Index k = 0; k < n; ++k)
        for (Index i = k + 1; i < n; ++i) x(i, j) -= lu(i, k) * x(k, j);
      for (Index k = n - 1; k >= 0; --k) {
        x(k, j) /= lu(k, k);
        for (Index i = 0; i < k; ++i) x(i, j) -= lu(i, k) * x(k, j);
      }
    }
    return x;
  }

  /// \f$\log|\det A|\f$ (the sum of the pivots' logarithms, which cannot overflow).
  [[nodiscard]] Scalar log_abs_determinant() const {
    Scalar s = 0;
    for (Index i = 0; i < lu.rows(); ++i) s += std::log(std::abs(lu(i, i)));
    return s;
  }
};

/// \f$A = LL^T\f$ for a symmetric positive definite A (lower triangle read).
template <typename Scalar>
struct CholeskyFactorization {
  DynamicMatrix<Scalar> l;
  bool positive_definite;  ///< false when a pivot is not positive and finite: no solve is attempted

  explicit CholeskyFactorization(DynamicMatrix<Scalar> a) : l(std::move(a)), positive_definite(cholesky_in_place(l)) {}

  /// \f$A^{-1}b\f$ by forward and back substitution.
  [[nodiscard]] DynamicMatrix<Scalar> solve(DynamicMatrix<Scalar> x) const {
    const Index n = l.rows();
    for (Index j = 0; j < x.cols(); ++j) {
      for (Index k = 0; k < n; ++k) {
        x(k, j) /= l(k, k);
        for (Index i = k + 1; i < n; ++i) x(i, j) -= l(i, k) * x(k, j);
      }
      for (Index k = n - 1; k >= 0; --k) {
        for (Index i = k + 1; i < n; ++i) x(k, j) -= l(i, k) * x(i, j);
        x(k, j) /= l(k, k);
      }
    }
    return x;
  }
};

}  // namespace adaptobs::detail
