#pragma once
/// \file
/// Static transformations (Zhang 2005, eq. (2)) that bring a constant pair (A, C)
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

#include <adaptobs/core/detail/dynamic_copy.hpp>
#include <adaptobs/core/dimensions.hpp>
#include <adaptobs/core/precompiled.hpp>
#include <adaptobs/core/static_transform.hpp>
#include <adaptobs/core/validation.hpp>
#include <adaptobs/design/care.hpp>
#include <adaptobs/design/observability.hpp>
#include <adaptobs/design/polynomial.hpp>

#include <Eigen/Core>
#include <Eigen/LU>
#include <Eigen/QR>

#include <cmath>
#include <optional>
#include <string>
#include <string_view>

namespace adaptobs {

/// A static transformation (Zhang 2005, eq. (2)) on run-time sizes: T and the
/// injection K (n × m) that removes the first m columns of \f$TAT^{-1}\f$.
/// `StaticTransform` is the same at the sizes of a `StateSpace`, with T's inverse.
template <typename Scalar>
struct CanonicalTransformation {
  Eigen::MatrixX<Scalar> T, K;
};

namespace detail {

/// A quantity of a form that grows like a power of A (the characteristic
/// polynomial's coefficients, the rows of an observability or adjugate
/// matrix, the transformation built from them), checked to be finite: one that
/// overflowed is refused naming `A`, whose scale is the cause.
template <class Matrix>
void require_within_range(const Matrix& m, std::string_view who, std::string_view what) {
  if (!m.allFinite())
    fail_argument(who, "A",
                  std::string("is too large in scale for the canonical form: ")
                      .append(what)
                      .append(", which grows like the powers of A, overflows; rescale the states or the time unit"));
}

/// The transformation in the types of `D`; refused, naming `A` or the output
/// matrix, when the pair's sizes are not the fixed sizes of `D`.
template <StateSpace D>
[[nodiscard]] StaticTransform<D> to_static_transform(const CanonicalTransformation<typename D::Scalar>& t,
                                                     std::string_view who, std::string_view output_matrix) {
  if constexpr (D::nx != Eigen::Dynamic) require_shape(t.T, D::nx, D::nx, who, "A");
  if constexpr (D::ny != Eigen::Dynamic)
    require(t.K.cols() == D::ny, who, output_matrix, "must have as many rows as the outputs of the dimensions D");
  require_within_range(t.T, who, "the transformation T");
  require_within_range(t.K, who, "the injection K");
  try {
    return StaticTransform<D>(typename D::StateMatrix(t.T), typename D::GainMatrix(t.K));
  } catch (const ConfigurationError&) {  // T (finite, square) not invertible to working accuracy
    fail_argument(who, "A, " + std::string(output_matrix),
                  "is too ill-conditioned for the canonical form: its transformation T has a condition number "
                  "beyond 1/(n eps)");
  }
}

// Columns spanning ker C (orthonormal), from a QR factorization of Cᵀ.
template <typename Scalar>
DynamicMatrix<Scalar> kernel_basis(const DynamicMatrix<Scalar>& c, std::string_view who) {
  const Index n = c.cols(), m = c.rows();
  const Eigen::ColPivHouseholderQR<DynamicMatrix<Scalar>> qr(c.transpose());
  require(qr.rank() == m, who, "C", "must have full row rank");
  const DynamicMatrix<Scalar> q = qr.householderQ() * DynamicMatrix<Scalar>::Identity(n, n);
  return q.rightCols(n - m);
}

template <typename Scalar>
CanonicalTransformation<Scalar> transform_with_injection_of_first_columns(const DynamicMatrix<Scalar>& t,
                                                                          const DynamicMatrix<Scalar>& a, Index m) {
  const Eigen::FullPivLU<DynamicMatrix<Scalar>> lu(t);
  const DynamicMatrix<Scalar> tat = t * a * lu.inverse();
  return {t, tat.leftCols(m)};
}

}  // namespace detail

/// The transformation to the form (5) of Algorithm 1 (Zhang 2005, §III-A) on
/// run-time sizes, with \f$\det(sI - A_{22}) = \nu(s)\f$ (`zeros`: monic,
/// degree n − 1, Hurwitz): \f$T^{-1} = [v, W]\f$ with W a basis of ker c
/// (`kernel`, or orthonormal from a QR factorization of \f$c^T\f$) and v
/// solving \f$C\,\mathrm{adj}(sI - A)\,v = \nu(s)\f$, i.e. \f$Mv = \nu\f$ with
/// the rows \f$cB_k\f$ of the Faddeev–LeVerrier adjugate
/// \f$B_{k+1} = AB_k + a_{k+1}I\f$; K is the first column of \f$TAT^{-1}\f$.
/// One instance per scalar type (compiled once in `adaptobs::precompiled`);
/// `bastin_gevers_form` is the same at the sizes of a `StateSpace`.
///
/// Refusals (`ConfigurationError` naming `bastin_gevers_form`): not a
/// single-output pair, `zeros` not monic of degree n − 1, not finite or not
/// Hurwitz, (A, c) not observable, a `kernel` that is not n × (n − 1), does not
/// span ker c or has dependent columns, a characteristic polynomial or adjugate
/// rows beyond the floating-point range, and a v that cannot be computed to
/// working accuracy.
template <typename Scalar>
[[nodiscard]] CanonicalTransformation<Scalar> bastin_gevers_form_dynamic(
    const Eigen::MatrixX<Scalar>& a, const Eigen::MatrixX<Scalar>& cc, const Polynomial<Scalar>& zeros,
    const std::optional<Eigen::MatrixX<Scalar>>& kernel = std::nullopt) {
  using Matrix = Eigen::MatrixX<Scalar>;
  constexpr std::string_view who = "bastin_gevers_form";
  const Index n = detail::require_single_output_pair(a, cc, who);
  require(zeros.size() == n && zeros(0) == Scalar(1), who, "zeros", "must be monic of degree n - 1");
  require_finite(zeros, who, "zeros");
  require(n == 1 || is_hurwitz_polynomial(zeros), who, "zeros", "must be Hurwitz (A22 is the zero dynamics)");
  // Rows c B_k of the Faddeev–LeVerrier adjugate: C adj(sI − A) v has coefficients M v.
  const Polynomial<Scalar> den = characteristic_polynomial(a);
  detail::require_within_range(den, who, "the characteristic polynomial of A");
  Matrix m(n, n), bk = Matrix::Identity(n, n);
  for (Index k = 0; k < n; ++k) {
    m.row(k) = cc * bk;
    bk = (a * bk).eval();
    bk.diagonal().array() += den(k + 1);
  }
  detail::require_within_range(m, who, "the adjugate rows c B_k of (A, c)");
  // M is a unit lower triangular Toeplitz matrix times the observability matrix:
  // invertible exactly when (A, c) is observable, which the staircase decides
  // in any output or time units; M, whose rows grow like the powers of A, is
  // what v needs.
  require(observability(a, cc).observable(), who, "A, c", "must be an observable pair");
  const Eigen::FullPivLU<Matrix> lu(m);
  constexpr std::string_view ill_conditioned =
      "is too ill-conditioned for the canonical form: the vector v of T^-1 = [v, W] (C adj(sI - A) v = zeros) "
      "cannot be computed to working accuracy";
  require(lu.isInvertible(), who, "A, c", ill_conditioned);
  const Eigen::Matrix<Scalar, Eigen::Dynamic, 1> v = lu.solve(zeros);
  Matrix w = kernel ? *kernel : detail::kernel_basis<Scalar>(cc, who);
  require_shape(w, n, n - 1, who, "kernel");
  // Relative to the sizes of c and W: c in other units has the same kernel.
  require((cc * w).cwiseAbs().maxCoeff() <= Scalar(1e-10) * cc.cwiseAbs().sum() * w.cwiseAbs().maxCoeff(), who,
          "kernel", "must span the kernel of c");
  require(w.fullPivLu().rank() == n - 1, who, "kernel", "must have independent columns");
  Matrix t_inv(n, n);
  t_inv << v, w;
  // With c v = 1 and W a basis of ker c, [v, W] is invertible: a singular one
  // means that v was not computed accurately.
  const Eigen::FullPivLU<Matrix> t_lu(t_inv);
  require(t_lu.isInvertible(), who, "A, c", ill_conditioned);
  return detail::transform_with_injection_of_first_columns<Scalar>(Matrix(t_lu.inverse()), a, 1);
}

/// The transformation to the form (7) of Algorithm 2 (Zhang 2005, §III-B) on
/// run-time sizes: \f$T = \mathcal O_{oc}^{-1}\mathcal O\f$, with \f$\mathcal O\f$ the
/// observability matrix of (A, c) and \f$\mathcal O_{oc}\f$ that of the observer
/// canonical pair \f$(S - ae_1^T, e_1^T)\f$ (a the coefficients of
/// \f$\det(sI - A)\f$), and \f$K = -a\f$. One instance per scalar type
/// (compiled once in `adaptobs::precompiled`); `marino_tomei_form` is the same
/// at the sizes of a `StateSpace`. Refuses (naming `marino_tomei_form`) a pair
/// that is not single-output or not observable, and one whose characteristic
/// polynomial or observability matrices leave the floating-point range.
template <typename Scalar>
[[nodiscard]] CanonicalTransformation<Scalar> marino_tomei_form_dynamic(const Eigen::MatrixX<Scalar>& A,
                                                                        const Eigen::MatrixX<Scalar>& c) {
  using Matrix = Eigen::MatrixX<Scalar>;
  constexpr std::string_view who = "marino_tomei_form";
  const Index n = detail::require_single_output_pair(A, c, who);
  const Polynomial<Scalar> a = characteristic_polynomial(A);
  detail::require_within_range(a, who, "the characteristic polynomial of A");
  Matrix canonical = Matrix::Zero(n, n);
  canonical.diagonal(1).setOnes();
  canonical.col(0) = -a.tail(n);
  Matrix e1 = Matrix::Zero(1, n);
  e1(0, 0) = Scalar(1);
  require(observability(A, c).observable(), who, "A, c", "must be an observable pair");
  const Matrix o = observability_matrix(A, c), o_canonical = observability_matrix(canonical, e1);
  detail::require_within_range(o, who, "the observability matrix of (A, c)");
  detail::require_within_range(o_canonical, who, "the observability matrix of the canonical pair");
  return {o_canonical.fullPivLu().solve(o), -a.tail(n)};
}

/// The transformation to the form (8) of Algorithm 3 (Zhang 2005, §III-C) on
/// run-time sizes: \f$T = \begin{bmatrix} I & 0\\ -X & I\end{bmatrix}T_0\f$ with
/// \f$T_0 = [C; N_0]\f$ (rows of \f$N_0\f$ an orthonormal basis of ker C) and X
/// the Kalman–Bucy gain (`kalman_bucy_gain`, unit weights) of
/// \f$(A_{22} + \text{decay}\,I, A_{12})\f$, so that every eigenvalue of
/// \f$A_{22} - XA_{12}\f$ has real part below −decay; K removes the first m
/// columns of \f$TAT^{-1}\f$. One instance per scalar type (compiled once in
/// `adaptobs::precompiled`); `besancon_form` is the same at the sizes of a `StateSpace`.
///
/// Refusals (naming `besancon_form`): C without full row rank or A's columns,
/// a negative or infinite decay, (A, C) not observable, a Riccati equation
/// that cannot be solved to working accuracy (naming `decay` when the
/// unshifted one can, `A` otherwise), and a T whose condition number the
/// decay drives beyond 1/(n ε).
template <typename Scalar>
[[nodiscard]] CanonicalTransformation<Scalar> besancon_form_dynamic(const Eigen::MatrixX<Scalar>& a,
                                                                    const Eigen::MatrixX<Scalar>& cc,
                                                                    Scalar decay = 1) {
  using Matrix = Eigen::MatrixX<Scalar>;
  constexpr std::string_view who = "besancon_form";
  const Index n = detail::require_output_pair(a, cc, who), m = cc.rows();
  require(decay >= 0 && std::isfinite(decay), who, "decay", "must be non-negative");
  // The kernel first: it may refuse C, which must not happen inside an open
  // comma initializer (its destructor would then assert on the missing rows).
  const Matrix kernel = detail::kernel_basis<Scalar>(cc, who);
  Matrix t0(n, n);
  t0 << cc, kernel.transpose();
  const Matrix at = t0 * a * t0.inverse();
  const Index r = n - m;
  Matrix t = t0;
  if (r > 0) {
    const Matrix a12 = at.topRightCorner(m, r);
    // (A22 + decay I, A12) is observable with (A22, A12); the staircase judges the
    // unshifted pair, whose scale does not grow with `decay`.
    require(observability(Matrix(at.bottomRightCorner(r, r)), a12).observable(), who, "A, C",
            "must be an observable pair");
    const Matrix a22 = at.bottomRightCorner(r, r) + decay * Matrix::Identity(r, r);
    // The unshifted pair is observable, and a shift keeps it so: a refusal of
    // the Riccati solver is numerical. It comes from the decay asked for when
    // the unshifted equation can be solved (the gain X, and with it
    // cond(T) ~ ||X||^2, grows with the decay), from the scale of A otherwise.
    const auto refuse_decay = [&](std::string_view reason) {
      fail_argument(
          who, "decay",
          std::string("is too large for the scale of A: ").append(reason).append("; ask for a smaller decay"));
    };
    const auto gain = [&](const Matrix& shifted) {
      return kalman_bucy_gain(shifted, a12, Matrix::Identity(r, r), Matrix::Identity(m, m)).K;
    };
    const auto solvable = [&](const Matrix& shifted) {
      try {
        (void)gain(shifted);
        return true;
      } catch (const ConfigurationError&) {
        return false;
      }
    };
    Matrix x;
    try {
      x = gain(a22);
    } catch (const ConfigurationError&) {
      if (decay > Scalar(0) && solvable(Matrix(at.bottomRightCorner(r, r))))
        refuse_decay(
            "the Riccati equation of the shifted pair (A22 + decay I, A12), whose gain moves the eigenvalues "
            "of A22 left of -decay, cannot be solved to working accuracy");
      fail_argument(who, "A",
                    "is beyond the range of the canonical form: the Riccati equation of the observable pair (A22, A12) "
                    "cannot be solved to working accuracy at its scale; rescale the states or the time unit");
    }
    Matrix left = Matrix::Identity(n, n);
    left.bottomLeftCorner(r, m) = -x;
    t = left * t0;
    if (decay > Scalar(0) && !detail::well_conditioned_inverse(t) && detail::well_conditioned_inverse(t0))
      refuse_decay(
          "the transformation T = [I 0; -X I] T0 that moves the eigenvalues of A22 left of -decay has a "
          "condition number beyond 1/(n eps)");
  }
  return detail::transform_with_injection_of_first_columns<Scalar>(t, a, m);
}

#ifdef ADAPTOBS_PRECOMPILED
ADAPTOBS_INSTANTIATE CanonicalTransformation<double> bastin_gevers_form_dynamic<double>(
    const Eigen::MatrixXd&, const Eigen::MatrixXd&, const Polynomial<double>&, const std::optional<Eigen::MatrixXd>&);
ADAPTOBS_INSTANTIATE CanonicalTransformation<double> marino_tomei_form_dynamic<double>(const Eigen::MatrixXd&,
                                                                                       const Eigen::MatrixXd&);
ADAPTOBS_INSTANTIATE CanonicalTransformation<double> besancon_form_dynamic<double>(const Eigen::MatrixXd&,
                                                                                   const Eigen::MatrixXd&, double);
#endif

/// Transform to the form (5) of Algorithm 1 with \f$\det(sI - A_{22}) = \nu(s)\f$
/// (`zeros`: monic, degree n − 1, Hurwitz). `kernel` (n × (n−1)), when given,
/// chooses the basis of ker c used for the last columns of \f$T^{-1}\f$.
template <StateSpace D, class DA, class DC>
[[nodiscard]] StaticTransform<D> bastin_gevers_form(
    const Eigen::MatrixBase<DA>& A, const Eigen::MatrixBase<DC>& c, const Polynomial<typename D::Scalar>& zeros,
    const std::optional<Eigen::Matrix<typename D::Scalar, Eigen::Dynamic, Eigen::Dynamic>>& kernel = std::nullopt) {
  return detail::to_static_transform<D>(
      bastin_gevers_form_dynamic<typename D::Scalar>(detail::dynamic_copy(A), detail::dynamic_copy(c), zeros, kernel),
      "bastin_gevers_form", "c");
}

/// Transform to the form (7) of Algorithm 2: \f$c_o = e_1^T\f$, \f$A_o = S\f$ (shift).
template <StateSpace D, class DA, class DC>
[[nodiscard]] StaticTransform<D> marino_tomei_form(const Eigen::MatrixBase<DA>& A, const Eigen::MatrixBase<DC>& c) {
  return detail::to_static_transform<D>(
      marino_tomei_form_dynamic<typename D::Scalar>(detail::dynamic_copy(A), detail::dynamic_copy(c)),
      "marino_tomei_form", "c");
}

/// Transform to the form (8) of Algorithm 3 for a constant (A, C) with m outputs:
/// \f$C_o = [I\ 0]\f$, \f$A_o = \begin{bmatrix} 0 & A_{12}\\ 0 & A_{22}\end{bmatrix}\f$,
/// every eigenvalue of \f$A_{22}\f$ with real part below −`decay`.
template <StateSpace D, class DA, class DC>
[[nodiscard]] StaticTransform<D> besancon_form(const Eigen::MatrixBase<DA>& A, const Eigen::MatrixBase<DC>& C,
                                               typename D::Scalar decay = 1) {
  return detail::to_static_transform<D>(
      besancon_form_dynamic<typename D::Scalar>(detail::dynamic_copy(A), detail::dynamic_copy(C), decay),
      "besancon_form", "C");
}

}  // namespace adaptobs
