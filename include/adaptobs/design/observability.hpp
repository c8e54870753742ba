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
///
/// **Scale.** Observability is a property of the subspaces, not of the units:
/// (A, C) and \f$(\alpha A, EC)\f$ are observable together for every α ≠ 0
/// and invertible E (a change of the time unit or of the output units). A rank
/// decision against one fixed yardstick such as \f$\max(1, \|A\|_F, \|C\|_F)\f$
/// is not: with C in units \f$10^{12}\f$ times too large every singular value of
/// C falls below it. So the staircase first scales each row of C by a power of
/// two to its largest entry in [1, 2) (exact in binary floating point: the same
/// pair in other output units, without a rounding error), then decides each rank
/// against the scale of the block it examines: C's own norm for the first step
/// (the rank of C), and \f$\|A\|_F\f$ for the later ones, whose blocks are
/// parts of \f$Q^TA^TQ\f$. Both are relative, so the verdict does not change
/// when C, or A, is multiplied by a constant.
///
/// The units of the *states* are left as given. A diagonal similarity
/// \f$(D^{-1}AD, CD)\f$ could make any coupling count, down to one at the
/// rounding level of the data or of 1e-300: a state that reaches the output
/// only through such a coupling has a mode that only a gain of the coupling's
/// inverse size could move, and is reported unobservable. A model whose states
/// are in wildly different units (a coupling below the rank tolerance times \f$\|A\|_F\f$
/// that matters) should be brought to comparable units first.

#include <adaptobs/core/detail/dynamic_copy.hpp>
#include <adaptobs/core/dimensions.hpp>
#include <adaptobs/core/precompiled.hpp>
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
  Index observable_dimension = 0;                                             ///< dimension of the observable subspace
  Eigen::Matrix<std::complex<Scalar>, Eigen::Dynamic, 1> unobservable_modes;  ///< empty when observable
  [[nodiscard]] bool observable() const noexcept { return unobservable_modes.size() == 0; }
};

namespace detail {

/// The exponent \f$e_k\f$ of each row of c: row k times \f$2^{-e_k}\f$ has its
/// largest entry in [1, 2) (0 for a zero row). Taken from the largest entry, not
/// from the row's norm, so that it is finite for every finite row, subnormal
/// or near the overflow threshold.
template <typename Scalar>
[[nodiscard]] Eigen::Matrix<int, Eigen::Dynamic, 1> row_exponents(const DynamicMatrix<Scalar>& c) {
  Eigen::Matrix<int, Eigen::Dynamic, 1> e(c.rows());
  for (Index k = 0; k < c.rows(); ++k) {
    const Scalar largest = c.cols() == 0 ? Scalar(0) : c.row(k).cwiseAbs().maxCoeff();
    e(k) = largest > Scalar(0) ? std::ilogb(largest) : 0;
  }
  return e;
}

/// m with row k (`rows`) or column k (otherwise) multiplied by \f$2^{-e_k}\f$,
/// entry by entry through `ldexp`: exact unless an entry leaves the range of
/// the normal numbers (the factor itself never overflows).
template <typename Scalar>
[[nodiscard]] DynamicMatrix<Scalar> scaled_by_powers_of_two(DynamicMatrix<Scalar> m,
                                                            const Eigen::Matrix<int, Eigen::Dynamic, 1>& e, bool rows) {
  for (Index j = 0; j < m.cols(); ++j)
    for (Index i = 0; i < m.rows(); ++i) m(i, j) = std::ldexp(m(i, j), -e(rows ? i : j));
  return m;
}

/// The default relative rank tolerance of the staircase: \f$10^6\varepsilon\f$
/// (2.2e-10 in double), but at most \f$\sqrt\varepsilon\f$, which it exceeds in
/// float (\f$10^6\varepsilon\f$ is 0.12 there: any coupling below 12 % of
/// \f$\|A\|_F\f$ would count as zero).
template <typename Scalar>
[[nodiscard]] Scalar default_observability_tolerance() {
  const Scalar eps = std::numeric_limits<Scalar>::epsilon();
  return std::min(Scalar(1e6) * eps, std::sqrt(eps));
}

}  // namespace detail

/// The orthogonal staircase of the file comment on run-time sizes: the
/// dimension of the observable subspace of (A, C) and the unobservable modes,
/// the eigenvalues of the block \f$\tilde A_{22}\f$ it leaves unreached
/// (Van Dooren 1981). Each step takes the SVD of the block of \f$Q^TA^TQ\f$
/// (first: of \f$C_s^T\f$, C with its rows scaled by powers of two to their
/// largest entry in [1, 2)) not yet reached, counts the singular values above
/// `relative_tolerance` times \f$\|C_s\|_F\f$ (first step) or \f$\|A\|_F\f$
/// (later steps), and rotates the state by its left singular vectors; 0 selects
/// \f$\min(10^6\varepsilon, \sqrt\varepsilon)\f$. `observability` is the same
/// for fixed-size or expression arguments; one instance per scalar type serves
/// every size (compiled once in `adaptobs::precompiled`). Refuses, naming
/// `observability`, an A that is not square or a C without A's columns.
template <typename Scalar>
[[nodiscard]] ObservabilityReport<Scalar> observability_staircase(const Eigen::MatrixX<Scalar>& A,
                                                                  const Eigen::MatrixX<Scalar>& C,
                                                                  Scalar relative_tolerance = 0) {
  using Matrix = Eigen::MatrixX<Scalar>;
  detail::require_output_pair(A, C, "observability");
  const Index n = A.rows();
  const Scalar rel = relative_tolerance > 0 ? relative_tolerance : detail::default_observability_tolerance<Scalar>();
  const Matrix scaled_c = detail::scaled_by_powers_of_two<Scalar>(C, detail::row_exponents<Scalar>(C), true);
  const Scalar c_tol = rel * scaled_c.stableNorm(), a_tol = rel * A.stableNorm();

  Matrix a = A.transpose();
  Matrix block = scaled_c.transpose();  // the part of the input matrix not yet reached
  Index offset = 0;
  while (offset < n && block.cols() > 0) {
    const Index rows = n - offset;
    const Eigen::JacobiSVD<Matrix> svd(block, Eigen::ComputeFullU);
    const auto& sigma = svd.singularValues();
    const Scalar tol = offset == 0 ? c_tol : a_tol;  // the scale of the block: C, then a part of A
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
#ifdef ADAPTOBS_PRECOMPILED
ADAPTOBS_INSTANTIATE ObservabilityReport<double> observability_staircase<double>(const Eigen::MatrixXd&,
                                                                                 const Eigen::MatrixXd&, double);
#endif

/// Staircase observability analysis of (A, C) (see file comment). A singular
/// value of C counts as zero below `relative_tolerance` × ‖C‖_F (each row of C
/// scaled by a power of two to its largest entry in [1, 2)), and one of a later
/// block below `relative_tolerance` × ‖A‖_F; 0 selects
/// \f$\min(10^6\varepsilon, \sqrt\varepsilon)\f$. The unobservable modes are the
/// eigenvalues of the unreached block.
template <class DA, class DC>
[[nodiscard]] ObservabilityReport<typename DA::Scalar> observability(const Eigen::MatrixBase<DA>& A,
                                                                     const Eigen::MatrixBase<DC>& C,
                                                                     typename DA::Scalar relative_tolerance = 0) {
  using Scalar = typename DA::Scalar;
  constexpr std::string_view who = "observability";
  detail::require_output_pair(A, C, who);
  return observability_staircase<Scalar>(detail::dynamic_copy(A), detail::dynamic_copy(C), relative_tolerance);
}

/// Popov–Belevitch–Hautus margin at a real μ:
/// \f$\sigma_{\min}\!\left(\begin{bmatrix} A - \mu I \\ C_s\end{bmatrix}\right) / \max(1, \|A\|_F, \|C_s\|_F)\f$,
/// 0 exactly when μ is an unobservable eigenvalue of A. \f$C_s\f$ is C with each
/// row scaled by a power of two to its largest entry in [1, 2), as in
/// `observability`: the outputs' units change C by a row scaling, which leaves
/// the pair's observability as it is, and so must leave the margin. Use it at
/// eigenvalues known in closed form (such as the eigenvalue 1 of an
/// integrator), where a computed eigenvalue would be inexact.
template <class DA, class DC>
[[nodiscard]] typename DA::Scalar pbh_margin(const Eigen::MatrixBase<DA>& A, const Eigen::MatrixBase<DC>& C,
                                             typename DA::Scalar mu) {
  using Scalar = typename DA::Scalar;
  using Matrix = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;
  constexpr std::string_view who = "pbh_margin";
  detail::require_output_pair(A, C, who);
  require(std::isfinite(mu), who, "mu", "must be finite");
  const Index n = A.rows();
  if (n == 0) return Scalar(1);
  Matrix stacked(n + C.rows(), n);
  stacked.topRows(n) = detail::dynamic_copy(A);
  stacked.topRows(n).diagonal().array() -= mu;
  const Matrix c = detail::dynamic_copy(C);
  const Matrix scaled_c = detail::scaled_by_powers_of_two<Scalar>(c, detail::row_exponents<Scalar>(c), true);
  stacked.bottomRows(C.rows()) = scaled_c;
  const Scalar smallest = Eigen::JacobiSVD<Matrix>(stacked).singularValues()(n - 1);
  return smallest / std::max({Scalar(1), Scalar(A.norm()), scaled_c.norm()});
}

}  // namespace adaptobs
