#pragma once
/// \file
/// The Sylvester equation \f$AX + XB = C\f$, by the Bartels–Stewart method on
/// complex Schur forms.
///
/// With \f$A = Q_AT_AQ_A^H\f$ and \f$B = Q_BT_BQ_B^H\f$ (complex Schur forms,
/// \f$T\f$ upper triangular, \f$Q\f$ unitary), \f$Y = Q_A^HXQ_B\f$ solves
/// \f$T_AY + YT_B = Q_A^HCQ_B =: R\f$ one column at a time:
/// \f[ (T_A + t^B_{jj}I)\,y_j = r_j - \sum_{i<j} t^B_{ij}\,y_i, \f]
/// each an upper-triangular solve (R. H. Bartels, G. W. Stewart, "Solution of
/// the matrix equation AX + XB = C", Comm. ACM 15(9), 1972). The solution is
/// unique exactly when A and −B have no eigenvalue in common; `separation()`
/// measures how far they are from sharing one. The Schur forms are computed
/// once, so many right-hand sides cost \f$O(n^3)\f$ each.

#include <adaptobs/core/dimensions.hpp>
#include <adaptobs/core/validation.hpp>

#include <Eigen/Core>
#include <Eigen/Eigenvalues>

#include <algorithm>
#include <complex>
#include <limits>

namespace adaptobs {

/// Solver of \f$AX + XB = C\f$ for fixed A (n × n) and B (m × m) and any C (n × m).
/// Works on dynamic-size matrices: it is a design-time tool.
template <typename Scalar>
class SylvesterSolver {
 public:
  using Matrix = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;
  using Complex = std::complex<Scalar>;
  using ComplexMatrix = Eigen::Matrix<Complex, Eigen::Dynamic, Eigen::Dynamic>;

  SylvesterSolver(const Matrix& A, const Matrix& B) {
    constexpr std::string_view who = "SylvesterSolver";
    require_square(A, who, "A");
    require_finite(A, who, "A");
    require_square(B, who, "B");
    require_finite(B, who, "B");
    n_ = A.rows();
    m_ = B.rows();
    if (n_ > 0) {
      const Eigen::ComplexSchur<Matrix> schur_a(A);
      ta_ = schur_a.matrixT();
      qa_ = schur_a.matrixU();
    }
    if (m_ > 0) {
      const Eigen::ComplexSchur<Matrix> schur_b(B);
      tb_ = schur_b.matrixT();
      qb_ = schur_b.matrixU();
    }
    Scalar gap = std::numeric_limits<Scalar>::infinity();
    for (Index i = 0; i < n_; ++i)
      for (Index j = 0; j < m_; ++j) gap = std::min(gap, std::abs(ta_(i, i) + tb_(j, j)));
    // Relative to the data's own scale, so that an equation scaled by any power
    // of ten keeps its separation. stableNorm: the plain norm sums squares,
    // which overflow beyond about 10^154 and underflow below 10^-154.
    const Scalar scale = std::max(A.stableNorm(), B.stableNorm());
    separation_ = n_ == 0 || m_ == 0  ? std::numeric_limits<Scalar>::infinity()
                  : scale > Scalar(0) ? gap / scale
                                      : Scalar(0);
  }

  /// \f$\min_{i,j}|\lambda_i(A) + \mu_j(B)| / \max(\|A\|_F, \|B\|_F)\f$ (∞ when A
  /// or B is empty, 0 when both are zero): 0 when the solution is not unique,
  /// small when it is ill conditioned. Unchanged when A and B are scaled together.
  [[nodiscard]] Scalar separation() const noexcept { return separation_; }

  /// X with \f$AX + XB = C\f$ (real part of the complex computation; exact for
  /// real data up to round-off). Non-finite when `separation()` is 0.
  [[nodiscard]] Matrix solve(const Matrix& C) const {
    require_shape(C, n_, m_, "SylvesterSolver::solve", "C");
    if (n_ == 0 || m_ == 0) return Matrix::Zero(n_, m_);
    const ComplexMatrix r = qa_.adjoint() * C.template cast<Complex>() * qb_;
    ComplexMatrix y(n_, m_);
    ComplexMatrix shifted = ta_;
    for (Index j = 0; j < m_; ++j) {
      Eigen::Matrix<Complex, Eigen::Dynamic, 1> rhs = r.col(j);
      if (j > 0) rhs.noalias() -= y.leftCols(j) * tb_.col(j).head(j);
      shifted.diagonal() = ta_.diagonal().array() + tb_(j, j);
      y.col(j) = shifted.template triangularView<Eigen::Upper>().solve(rhs);
    }
    return (qa_ * y * qb_.adjoint()).real();
  }

 private:
  Index n_ = 0;
  Index m_ = 0;
  ComplexMatrix ta_, qa_, tb_, qb_;
  Scalar separation_ = 0;
};

/// X with \f$AX + XB = C\f$. Throws `ConfigurationError` when A and −B share an
/// eigenvalue (no unique solution).
template <class DA, class DB, class DC>
[[nodiscard]] Eigen::Matrix<typename DA::Scalar, DA::RowsAtCompileTime, DB::ColsAtCompileTime> solve_sylvester(
    const Eigen::MatrixBase<DA>& A, const Eigen::MatrixBase<DB>& B, const Eigen::MatrixBase<DC>& C) {
  using Scalar = typename DA::Scalar;
  using Matrix = typename SylvesterSolver<Scalar>::Matrix;
  require_finite(C, "solve_sylvester", "C");
  const SylvesterSolver<Scalar> solver{Matrix(A), Matrix(B)};
  if (!(solver.separation() > Scalar(10) * std::numeric_limits<Scalar>::epsilon()))
    fail_argument("solve_sylvester", "A, B", "share an eigenvalue of A and -B: no unique solution");
  return solver.solve(Matrix(C));
}

}  // namespace adaptobs
