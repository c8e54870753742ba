#pragma once
/// \file
/// Observability of a pair (A, C) by the orthogonal staircase algorithm.
///
/// Rank tests on the observability matrix \f$[C; CA; \dots; CA^{n-1}]\f$ lose
/// accuracy with the powers of A, and Popov–Belevitch–Hautus tests at computed
/// eigenvalues miss defective ones (a k-fold eigenvalue is computed only to
/// \f$\varepsilon^{1/k}\f$). The staircase works with orthogonal similarity
/// transformations and one rank decision per step instead: it reduces the dual
/// pair \f$(A^T, C^T)\f$ to
/// \f[ Q^TA^TQ = \begin{bmatrix} \tilde A_{11} & \tilde A_{12} \\ 0 & \tilde A_{22}\end{bmatrix},\qquad
///     Q^TC^T = \begin{bmatrix} \tilde B_1 \\ 0 \end{bmatrix}, \f]
/// with \f$(\tilde A_{11}, \tilde B_1)\f$ controllable; the eigenvalues of
/// \f$\tilde A_{22}\f$ are the unobservable modes of (A, C) (P. Van Dooren, "The
/// generalized eigenstructure problem in linear system theory", IEEE TAC 26(1), 1981).

#include <adaptobs/core/dimensions.hpp>
#include <adaptobs/core/detail/dynamic_copy.hpp>
#include <adaptobs/core/validation.hpp>
#include <adaptobs/design/dense_eigenvalues.hpp>

#include <Eigen/Core>
#include <Eigen/SVD>

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <string_view>

namespace adaptobs {

/// Outcome of the observability staircase.
template <typename Scalar>
struct ObservabilityReport {
  Index observable_dimension = 0;  ///< dimension of the observable subspace
  Eigen::Matrix<std::complex<Scalar>, Eigen::Dynamic, 1> unobservable_modes;  ///< empty when observable
  [[nodiscard]] bool observable() const noexcept { return unobservable_modes.size() == 0; }
};

/// Staircase observability analysis of (A, C) (see file comment). A singular
/// value counts as zero below `relative_tolerance` × max(1, ‖A‖_F, ‖C‖_F);
/// 0 selects \f$10^6\varepsilon\f$.
template <class DA, class DC>
[[nodiscard]] ObservabilityReport<typename DA::Scalar> observability(const Eigen::MatrixBase<DA>& A,
                                                                     const Eigen::MatrixBase<DC>& C,
                                                                     typename DA::Scalar relative_tolerance = 0) {
  using Scalar = typename DA::Scalar;
  using Matrix = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;
  constexpr std::string_view who = "observability";
  detail::require_output_pair(A, C, who);
  const Index n = A.rows();
  const Scalar rel = relative_tolerance > 0 ? relative_tolerance
                                            : Scalar(1e6) * std::numeric_limits<Scalar>::epsilon();
  const Scalar tol = rel * std::max({Scalar(1), Scalar(A.norm()), Scalar(C.norm())});

  Matrix a = detail::dynamic_copy(A.transpose());
  Matrix block = detail::dynamic_copy(C.transpose());  // the part of the input matrix not yet reached
  Index offset = 0;
  while (offset < n && block.cols() > 0) {
    const Index rows = n - offset;
    const Eigen::JacobiSVD<Matrix> svd(block, Eigen::ComputeFullU);
    const auto& sigma = svd.singularValues();
    Index rank = 0;
    while (rank < sigma.size() && sigma(rank) > tol) ++rank;
    if (rank == 0) break;
    const Matrix& u = svd.matrixU();
    a.bottomRows(rows) = (u.transpose() * a.bottomRows(rows)).eval();
    a.rightCols(rows) = (a.rightCols(rows) * u).eval();
    const Index next = offset + rank;
    if (next < n) block = a.block(next, offset, n - next, rank);
    offset = next;
  }
  ObservabilityReport<Scalar> report;
  report.observable_dimension = offset;
  if (offset < n) {
    const Matrix rest = a.bottomRightCorner(n - offset, n - offset);
    report.unobservable_modes = detail::dense_eigenvalues(rest);
  }
  return report;
}

/// Popov–Belevitch–Hautus margin at a real μ:
/// \f$\sigma_{\min}\!\left(\begin{bmatrix} A - \mu I \\ C\end{bmatrix}\right) / \max(1, \|A\|_F, \|C\|_F)\f$,
/// 0 exactly when μ is an unobservable eigenvalue of A. Use it at eigenvalues
/// known in closed form (such as the eigenvalue 1 of an integrator), where a
/// computed eigenvalue would be inexact.
template <class DA, class DC>
[[nodiscard]] typename DA::Scalar pbh_margin(const Eigen::MatrixBase<DA>& A, const Eigen::MatrixBase<DC>& C,
                                             typename DA::Scalar mu) {
  using Scalar = typename DA::Scalar;
  using Matrix = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;
  constexpr std::string_view who = "pbh_margin";
  detail::require_output_pair(A, C, who);
  detail::require(std::isfinite(mu), who, "mu", "must be finite");
  const Index n = A.rows();
  if (n == 0) return Scalar(1);
  Matrix stacked(n + C.rows(), n);
  stacked.topRows(n) = detail::dynamic_copy(A);
  stacked.topRows(n).diagonal().array() -= mu;
  stacked.bottomRows(C.rows()) = detail::dynamic_copy(C);
  const Scalar smallest = Eigen::JacobiSVD<Matrix>(stacked).singularValues()(n - 1);
  return smallest / std::max({Scalar(1), Scalar(A.norm()), Scalar(C.norm())});
}

}  // namespace adaptobs
