#pragma once
/// \file
/// Continuous Lyapunov equation \f$A^TX + XA + Q = 0\f$ (Bartels–Stewart on the complex Schur form).
///
/// With \f$A = UTU^H\f$ (T upper triangular), \f$Y = U^HXU\f$ solves the
/// triangular equation \f$T^HY + YT = -U^HQU\f$, entry by entry:
/// \f[ (\bar t_{ii} + t_{jj})\,y_{ij} = -c_{ij} - \sum_{k<i}\bar t_{ki}y_{kj} - \sum_{l<j} y_{il}t_{lj}. \f]
/// A unique solution exists when no two eigenvalues of A sum to zero; for a
/// Hurwitz A and Q ≥ 0 it is the positive semidefinite \f$\int_0^\infty e^{A^Ts}Qe^{As}ds\f$.

#include <adaptobs/core/detail/dynamic_copy.hpp>
#include <adaptobs/core/precompiled.hpp>
#include <adaptobs/core/validation.hpp>

#include <Eigen/Core>
#include <Eigen/Eigenvalues>

#include <cmath>
#include <complex>
#include <limits>

namespace adaptobs {

namespace detail {
/// The Bartels–Stewart solve on dynamic-size matrices (checked arguments, n ≥ 1):
/// one instantiation per scalar type, compiled once for `double` where
/// `adaptobs::precompiled` is linked (core/precompiled.hpp).
template <typename Scalar>
[[nodiscard]] DynamicMatrix<Scalar> solve_continuous_lyapunov_dense(const DynamicMatrix<Scalar>& A,
                                                                    const DynamicMatrix<Scalar>& Q) {
  using Complex = std::complex<Scalar>;
  using ComplexMatrix = Eigen::Matrix<Complex, Eigen::Dynamic, Eigen::Dynamic>;
  const Index n = A.rows();
  const Eigen::ComplexSchur<ComplexMatrix> schur(ComplexMatrix(A.template cast<Complex>()));
  const ComplexMatrix& T = schur.matrixT();
  const ComplexMatrix& U = schur.matrixU();
  const ComplexMatrix C = U.adjoint() * Q.template cast<Complex>() * U;
  ComplexMatrix Y = ComplexMatrix::Zero(n, n);
  // Relative to A's own scale: a slow Hurwitz A (eigenvalues near 1e-20) is as
  // regular as a fast one; only a pivot small against the largest |t_ij| is singular.
  const Scalar scale = T.cwiseAbs().maxCoeff();
  for (Index j = 0; j < n; ++j) {
    for (Index i = 0; i < n; ++i) {
      Complex rhs = -C(i, j);
      for (Index k = 0; k < i; ++k) rhs -= std::conj(T(k, i)) * Y(k, j);
      for (Index l = 0; l < j; ++l) rhs -= Y(i, l) * T(l, j);
      const Complex pivot = std::conj(T(i, i)) + T(j, j);
      if (std::abs(pivot) <= Scalar(100) * std::numeric_limits<Scalar>::epsilon() * scale)
        fail_argument("solve_continuous_lyapunov", "A", "must not share an eigenvalue with -A (the equation is singular)");
      Y(i, j) = rhs / pivot;
    }
  }
  const DynamicMatrix<Scalar> x = (U * Y * U.adjoint()).real();
  return Scalar(0.5) * (x + x.transpose());
}
#ifdef ADAPTOBS_PRECOMPILED
ADAPTOBS_INSTANTIATE DynamicMatrix<double> solve_continuous_lyapunov_dense<double>(const DynamicMatrix<double>&,
                                                                                   const DynamicMatrix<double>&);
#endif
}  // namespace detail

/// Solution X of \f$A^TX + XA + Q = 0\f$ (Q symmetric). Throws when A and −A share an eigenvalue.
template <class DA, class DQ>
[[nodiscard]] Eigen::Matrix<typename DA::Scalar, DA::RowsAtCompileTime, DA::RowsAtCompileTime>
solve_continuous_lyapunov(const Eigen::MatrixBase<DA>& A, const Eigen::MatrixBase<DQ>& Q) {
  using Scalar = typename DA::Scalar;
  constexpr std::string_view who = "solve_continuous_lyapunov";
  detail::require_square(A, who, "A");
  detail::require_finite(A, who, "A");
  const Index n = A.rows();
  detail::require_finite_shape(Q, n, n, who, "Q");
  // The solution is symmetrized, which is only right for a symmetric Q.
  detail::require_symmetric(Q, who, "Q");
  Eigen::Matrix<Scalar, DA::RowsAtCompileTime, DA::RowsAtCompileTime> X(n, n);
  if (n == 0) return X;
  X = detail::solve_continuous_lyapunov_dense(detail::dynamic_copy(A), detail::dynamic_copy(Q));
  return X;
}

}  // namespace adaptobs
