#pragma once
/// \file
/// Continuous Lyapunov equation \f$A^TX + XA + Q = 0\f$ (Bartels–Stewart on the complex Schur form).
///
/// With \f$A = UTU^H\f$ (T upper triangular), \f$Y = U^HXU\f$ solves the
/// triangular equation \f$T^HY + YT = -U^HQU = -C\f$ column by column: column j reads
/// \f[ (T^H + t_{jj}I)\,y_j = -c_j - \sum_{l<j} y_l\,t_{lj}, \f]
/// a lower triangular system with the diagonal \f$\bar t_{ii} + t_{jj}\f$
/// (R. H. Bartels, G. W. Stewart, "Solution of the matrix equation AX + XB = C",
/// Comm. ACM 15(9), 1972). A unique solution exists when no two eigenvalues of
/// A sum to zero; for a Hurwitz A and Q ≥ 0 it is the positive semidefinite
/// \f$\int_0^\infty e^{A^Ts}Qe^{As}ds\f$.

#include <adaptobs/core/detail/dynamic_copy.hpp>
#include <adaptobs/core/precompiled.hpp>
#include <adaptobs/core/validation.hpp>

#include <Eigen/Core>
#include <Eigen/Eigenvalues>

#include <cmath>
#include <complex>
#include <limits>
#include <string_view>

namespace adaptobs {

/// Solution X of \f$A^TX + XA + Q = 0\f$ on run-time sizes, by the column
/// recursion of the file comment, symmetrized: for a Q symmetric only to
/// rounding (a residual), the solution for its symmetric part. One instance
/// per scalar type serves every order (compiled once for `double` where
/// `adaptobs::precompiled` is linked, core/precompiled.hpp);
/// `solve_continuous_lyapunov` is the same for fixed-size arguments.
///
/// Refusals (`ConfigurationError` naming `solve_continuous_lyapunov`): A not
/// square or not finite, Q not of A's order, and A sharing an eigenvalue with
/// −A, i.e. a diagonal entry \f$\bar t_{ii} + t_{jj}\f$ at most
/// \f$100\varepsilon\max|t_{kl}|\f$ (relative to A's own scale: a slow Hurwitz
/// A, eigenvalues near 1e-20, is as regular as a fast one).
template <typename Scalar>
[[nodiscard]] Eigen::MatrixX<Scalar> solve_continuous_lyapunov_dynamic(const Eigen::MatrixX<Scalar>& A,
                                                                       const Eigen::MatrixX<Scalar>& Q) {
  using Complex = std::complex<Scalar>;
  using ComplexMatrix = Eigen::MatrixX<Complex>;
  constexpr std::string_view who = "solve_continuous_lyapunov";
  require_square(A, who, "A");
  require_finite(A, who, "A");
  const Index n = A.rows();
  require_shape(Q, n, n, who, "Q");
  if (n == 0) return Eigen::MatrixX<Scalar>(0, 0);
  const Eigen::ComplexSchur<ComplexMatrix> schur(ComplexMatrix(A.template cast<Complex>()));
  const ComplexMatrix& T = schur.matrixT();
  const ComplexMatrix& U = schur.matrixU();
  const ComplexMatrix C = U.adjoint() * Q.template cast<Complex>() * U;
  const Scalar singular = Scalar(100) * std::numeric_limits<Scalar>::epsilon() * T.cwiseAbs().maxCoeff();
  ComplexMatrix Y(n, n);
  for (Index j = 0; j < n; ++j) {
    // The diagonal of T^H + t_jj I: the pivots of column j.
    if ((T.diagonal().conjugate().array() + T(j, j)).abs().minCoeff() <= singular)
      fail_argument(who, "A", "must not share an eigenvalue with -A (the equation is singular)");
    const ComplexMatrix shifted = T.adjoint() + T(j, j) * ComplexMatrix::Identity(n, n);
    Y.col(j) = shifted.template triangularView<Eigen::Lower>().solve(-C.col(j) - Y.leftCols(j) * T.col(j).head(j));
  }
  const Eigen::MatrixX<Scalar> x = (U * Y * U.adjoint()).real();
  return Scalar(0.5) * (x + x.transpose());
}
#ifdef ADAPTOBS_PRECOMPILED
ADAPTOBS_INSTANTIATE Eigen::MatrixXd solve_continuous_lyapunov_dynamic<double>(const Eigen::MatrixXd&,
                                                                               const Eigen::MatrixXd&);
#endif

namespace detail {
/// The solve for the Newton steps of care.hpp, whose right-hand sides are
/// residuals, symmetric only to rounding.
template <typename Scalar>
[[nodiscard]] DynamicMatrix<Scalar> solve_continuous_lyapunov_dense(const DynamicMatrix<Scalar>& A,
                                                                    const DynamicMatrix<Scalar>& Q) {
  return solve_continuous_lyapunov_dynamic<Scalar>(A, Q);
}
}  // namespace detail

/// Solution X of \f$A^TX + XA + Q = 0\f$ (Q symmetric): `solve_continuous_lyapunov_dynamic`
/// on copies, sized as A. Throws when A and −A share an eigenvalue, or when A
/// or Q is not finite, Q not symmetric or not of A's order.
template <class DA, class DQ>
[[nodiscard]] Eigen::Matrix<typename DA::Scalar, DA::RowsAtCompileTime, DA::RowsAtCompileTime>
solve_continuous_lyapunov(const Eigen::MatrixBase<DA>& A, const Eigen::MatrixBase<DQ>& Q) {
  using Scalar = typename DA::Scalar;
  constexpr std::string_view who = "solve_continuous_lyapunov";
  require_square(A, who, "A");
  require_finite(A, who, "A");
  require_finite_shape(Q, A.rows(), A.rows(), who, "Q");
  // The solution is symmetrized, which is only right for a symmetric Q.
  require_symmetric(Q, who, "Q");
  return Eigen::Matrix<Scalar, DA::RowsAtCompileTime, DA::RowsAtCompileTime>(
      solve_continuous_lyapunov_dynamic<Scalar>(detail::dynamic_copy(A), detail::dynamic_copy(Q)));
}

}  // namespace adaptobs
