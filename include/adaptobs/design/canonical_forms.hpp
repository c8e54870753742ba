#pragma once
/// \file
/// Static transformations (paper 001, eq. (2)) that bring a constant pair (A, C)
/// to the forms of Algorithms 1–3.
///
/// - `bastin_gevers_form` (Alg. 1, §III-A, form (5)): \f$c_o = e_1^T\f$,
///   \f$A_o = \begin{bmatrix} 0 & a_{12}\\ 0 & A_{22}\end{bmatrix}\f$ with chosen \f$\det(sI - A_{22})\f$.
///   With \f$v = T^{-1}e_1\f$, \f$c_o = e_1^T\f$ needs \f$Cv = 1\f$ and the other columns
///   of \f$T^{-1}\f$ in ker C; the eigenvalues of \f$A_{22}\f$ are then the zeros of
///   \f$C(sI - A)^{-1}v\f$, assigned by solving \f$C\,\mathrm{adj}(sI - A)\,v = \nu(s)\f$
///   (a regular linear system when (A, C) is observable). K is the first column
///   of \f$TAT^{-1}\f$, which the injection removes.
/// - `marino_tomei_form` (Alg. 2, §III-B, form (7)): \f$c_o = e_1^T\f$ and \f$A_o\f$
///   the shift matrix: \f$T = \mathcal O_{oc}^{-1}\mathcal O\f$ maps (A, C) to the
///   observer canonical pair \f$(S - ae_1^T, e_1^T)\f$ and \f$K = -a\f$ removes its first column.
/// - `besancon_form` (Alg. 3, §III-C, form (8)) for m outputs: \f$C_o = [I\ 0]\f$
///   with \f$A_{22}\f$ Hurwitz. From \f$T_0 = [C; N_0]\f$ (rows of \f$N_0\f$ span ker C),
///   \f$T = \begin{bmatrix} I & 0\\ -X & I\end{bmatrix}T_0\f$ turns the lower-right
///   block into \f$A_{22} - XA_{12}\f$; X is the Kalman–Bucy gain of the pair
///   \f$(A_{22} + \alpha I, A_{12})\f$, so every eigenvalue has real part below −α.
///   ((A, C) observable ⇔ \f$(A_{22}, A_{12})\f$ observable.) K removes the first m columns.

#include <adaptobs/core/dimensions.hpp>
#include <adaptobs/core/static_transform.hpp>
#include <adaptobs/core/validation.hpp>
#include <adaptobs/design/care.hpp>
#include <adaptobs/design/polynomial.hpp>

#include <Eigen/Core>
#include <Eigen/LU>
#include <Eigen/QR>

#include <cmath>
#include <optional>

namespace adaptobs {

namespace detail {
// Columns spanning ker C (orthonormal), from a QR factorization of Cᵀ.
template <typename Scalar>
Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic> kernel_basis(
    const Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>& c, std::string_view who) {
  const Index n = c.cols(), m = c.rows();
  const Eigen::ColPivHouseholderQR<Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>> qr(c.transpose());
  require(qr.rank() == m, who, "C", "must have full row rank");
  const Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic> q =
      qr.householderQ() * Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>::Identity(n, n);
  return q.rightCols(n - m);
}

template <StateSpace D, class Matrix>
StaticTransform<D> transform_with_injection_of_first_columns(const Matrix& t, const Matrix& a, Index m) {
  const Eigen::FullPivLU<Matrix> lu(t);
  const Matrix tat = t * a * lu.inverse();
  return StaticTransform<D>(typename D::StateMatrix(t), typename D::GainMatrix(tat.leftCols(m)));
}
}  // namespace detail

/// Transform to the form (5) of Algorithm 1 with \f$\det(sI - A_{22}) = \nu(s)\f$
/// (`zeros`: monic, degree n − 1, Hurwitz). `kernel` (n × (n−1)), when given,
/// chooses the basis of ker c used for the last columns of \f$T^{-1}\f$.
template <StateSpace D, class DA, class DC>
[[nodiscard]] StaticTransform<D> bastin_gevers_form(
    const Eigen::MatrixBase<DA>& A, const Eigen::MatrixBase<DC>& c, const Polynomial<typename D::Scalar>& zeros,
    const std::optional<Eigen::Matrix<typename D::Scalar, Eigen::Dynamic, Eigen::Dynamic>>& kernel = std::nullopt) {
  using Scalar = typename D::Scalar;
  using Matrix = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;
  constexpr std::string_view who = "bastin_gevers_form";
  const Index n = detail::require_single_output_pair(A, c, who);
  detail::require(zeros.size() == n && zeros(0) == Scalar(1), who, "zeros", "must be monic of degree n - 1");
  detail::require(n == 1 || is_hurwitz_polynomial(zeros), who, "zeros", "must be Hurwitz (A22 is the zero dynamics)");
  const Matrix a = A, cc = c;
  // Rows c B_k of the Faddeev–LeVerrier adjugate: C adj(sI − A) v has coefficients M v.
  const Polynomial<Scalar> den = characteristic_polynomial(a);
  Matrix m(n, n), bk = Matrix::Identity(n, n);
  for (Index k = 0; k < n; ++k) {
    m.row(k) = cc * bk;
    bk = (a * bk).eval();
    bk.diagonal().array() += den(k + 1);
  }
  const Eigen::FullPivLU<Matrix> lu(m);
  detail::require(lu.isInvertible(), who, "A, c", "must be an observable pair");
  const Eigen::Matrix<Scalar, Eigen::Dynamic, 1> v = lu.solve(zeros);
  Matrix w = kernel ? *kernel : detail::kernel_basis<Scalar>(cc, who);
  detail::require_shape(w, n, n - 1, who, "kernel");
  detail::require((cc * w).cwiseAbs().maxCoeff() <= Scalar(1e-10) * std::max(Scalar(1), w.cwiseAbs().maxCoeff()), who,
                  "kernel", "must span the kernel of c");
  Matrix t_inv(n, n);
  t_inv << v, w;
  const Eigen::FullPivLU<Matrix> t_lu(t_inv);
  detail::require(t_lu.isInvertible(), who, "kernel", "must have independent columns");
  return detail::transform_with_injection_of_first_columns<D>(Matrix(t_lu.inverse()), a, 1);
}

/// Transform to the form (7) of Algorithm 2: \f$c_o = e_1^T\f$, \f$A_o = S\f$ (shift).
template <StateSpace D, class DA, class DC>
[[nodiscard]] StaticTransform<D> marino_tomei_form(const Eigen::MatrixBase<DA>& A, const Eigen::MatrixBase<DC>& c) {
  using Scalar = typename D::Scalar;
  using Matrix = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;
  constexpr std::string_view who = "marino_tomei_form";
  const Index n = detail::require_single_output_pair(A, c, who);
  const Polynomial<Scalar> a = characteristic_polynomial(A);
  Matrix canonical = Matrix::Zero(n, n);
  canonical.diagonal(1).setOnes();
  canonical.col(0) = -a.tail(n);
  Matrix e1 = Matrix::Zero(1, n);
  e1(0, 0) = Scalar(1);
  const Eigen::FullPivLU<Matrix> o(observability_matrix(A, c));
  detail::require(o.isInvertible(), who, "A, c", "must be an observable pair");
  const Matrix t = observability_matrix(canonical, e1).fullPivLu().solve(observability_matrix(A, c));
  return StaticTransform<D>(typename D::StateMatrix(t), typename D::GainMatrix(-a.tail(n)));
}

/// Transform to the form (8) of Algorithm 3 for a constant (A, C) with m outputs:
/// \f$C_o = [I\ 0]\f$, \f$A_o = \begin{bmatrix} 0 & A_{12}\\ 0 & A_{22}\end{bmatrix}\f$,
/// every eigenvalue of \f$A_{22}\f$ with real part below −`decay`.
template <StateSpace D, class DA, class DC>
[[nodiscard]] StaticTransform<D> besancon_form(const Eigen::MatrixBase<DA>& A, const Eigen::MatrixBase<DC>& C,
                                               typename D::Scalar decay = 1) {
  using Scalar = typename D::Scalar;
  using Matrix = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;
  constexpr std::string_view who = "besancon_form";
  detail::require_square(A, who, "A");
  const Index n = A.rows(), m = C.rows();
  detail::require_shape(C, m, n, who, "C");
  detail::require(decay >= 0 && std::isfinite(decay), who, "decay", "must be non-negative");
  const Matrix a = A, cc = C;
  Matrix t0(n, n);
  t0 << cc, detail::kernel_basis<Scalar>(cc, who).transpose();
  const Matrix at = t0 * a * t0.inverse();
  const Index r = n - m;
  Matrix t = t0;
  if (r > 0) {
    const Matrix a12 = at.topRightCorner(m, r);
    const Matrix a22 = at.bottomRightCorner(r, r) + decay * Matrix::Identity(r, r);
    const Eigen::FullPivLU<Matrix> obs(observability_matrix(a22, a12));
    detail::require(obs.rank() == r, who, "A, C", "must be an observable pair");
    const Matrix x = kalman_bucy_gain(a22, a12, Matrix::Identity(r, r), Matrix::Identity(m, m)).K;
    Matrix left = Matrix::Identity(n, n);
    left.bottomLeftCorner(r, m) = -x;
    t = left * t0;
  }
  return detail::transform_with_injection_of_first_columns<D>(t, a, m);
}

}  // namespace adaptobs
