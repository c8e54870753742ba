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

#include <adaptobs/core/detail/cholesky.hpp>
#include <adaptobs/core/detail/dynamic_copy.hpp>
#include <adaptobs/core/validation.hpp>

#include <Eigen/Core>

#include <cmath>
#include <utility>

namespace adaptobs::detail {

// The loops index the column-major storage directly: besides being the
// natural form of these kernels, it keeps them fast in an unoptimized
// (sanitizer) build, where every Eigen coefficient access is a function call.

/// \f$ab\f$.
template <typename Scalar>
[[nodiscard]] DynamicMatrix<Scalar> multiply(const DynamicMatrix<Scalar>& a, const DynamicMatrix<Scalar>& b) {
  const Index m = a.rows(), n = b.cols(), depth = a.cols();
  eigen_assert(b.rows() == depth && "multiply: inner dimensions differ");
  DynamicMatrix<Scalar> c = DynamicMatrix<Scalar>::Zero(m, n);
  const Scalar* pa = a.data();
  for (Index j = 0; j < n; ++j) {
    Scalar* cj = c.data() + j * m;
    const Scalar* bj = b.data() + j * depth;
    for (Index k = 0; k < depth; ++k) {
      const Scalar bkj = bj[k];
      const Scalar* ak = pa + k * m;
      for (Index i = 0; i < m; ++i) cj[i] += ak[i] * bkj;
    }
  }
  return c;
}

/// \f$a^Tb\f$: inner products of columns, so both operands are read contiguously.
template <typename Scalar>
[[nodiscard]] DynamicMatrix<Scalar> multiply_transposed(const DynamicMatrix<Scalar>& a,
                                                        const DynamicMatrix<Scalar>& b) {
  const Index m = a.cols(), n = b.cols(), depth = a.rows();
  eigen_assert(b.rows() == depth && "multiply_transposed: inner dimensions differ");
  DynamicMatrix<Scalar> c(m, n);
  for (Index j = 0; j < n; ++j) {
    const Scalar* bj = b.data() + j * depth;
    for (Index i = 0; i < m; ++i) {
      const Scalar* ai = a.data() + i * depth;
      Scalar s = 0;
      for (Index k = 0; k < depth; ++k) s += ai[k] * bj[k];
      c.data()[i + j * m] = s;
    }
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
  bool singular = false;  ///< a zero (or non-finite) pivot: the factors are incomplete and must not be solved with

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
      Scalar* lk = lu.data() + k * n;  // column k: the multipliers below the pivot
      for (Index i = k + 1; i < n; ++i) lk[i] /= lk[k];
      for (Index j = k + 1; j < n; ++j) {
        Scalar* uj = lu.data() + j * n;
        const Scalar ukj = uj[k];
        for (Index i = k + 1; i < n; ++i) uj[i] -= lk[i] * ukj;
      }
    }
  }

  /// \f$A^{-1}b\f$ by forward and back substitution.
  [[nodiscard]] DynamicMatrix<Scalar> solve(const DynamicMatrix<Scalar>& b) const {
    const Index n = lu.rows();
    eigen_assert(!singular && b.rows() == n && "LuFactorization::solve: singular factors or wrong row count");
    DynamicMatrix<Scalar> x(n, b.cols());
    for (Index i = 0; i < n; ++i) x.row(i) = b.row(rows(i));
    for (Index j = 0; j < x.cols(); ++j) {
      Scalar* xj = x.data() + j * n;
      for (Index k = 0; k < n; ++k) {
        const Scalar* lk = lu.data() + k * n;
        for (Index i = k + 1; i < n; ++i) xj[i] -= lk[i] * xj[k];
      }
      for (Index k = n - 1; k >= 0; --k) {
        const Scalar* uk = lu.data() + k * n;
        xj[k] /= uk[k];
        for (Index i = 0; i < k; ++i) xj[i] -= uk[i] * xj[k];
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
  CholeskyFactor<DynamicMatrix<Scalar>> factor;
  bool positive_definite;  ///< false when a pivot is not positive and finite: then the factor must not be solved with

  explicit CholeskyFactorization(const DynamicMatrix<Scalar>& a) : positive_definite(factor.compute(a)) {}

  /// \f$A^{-1}b\f$ by forward and back substitution.
  [[nodiscard]] DynamicMatrix<Scalar> solve(DynamicMatrix<Scalar> x) const {
    eigen_assert(positive_definite && x.rows() == factor.factor().rows() &&
                 "CholeskyFactorization::solve: no factor or wrong row count");
    factor.solve_in_place(x);
    return x;
  }
};

}  // namespace adaptobs::detail
