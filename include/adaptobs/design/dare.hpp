#pragma once
/// \file
/// Discrete algebraic Riccati equation and the steady-state Kalman gain.
///
/// The DARE
/// \f[ X = A^T X A - A^T X B (R + B^T X B)^{-1} B^T X A + Q \f]
/// is solved by the structure-preserving doubling algorithm (SDA; E. K.-W. Chu,
/// H.-Y. Fan, W.-W. Lin, "A structure-preserving doubling algorithm for
/// discrete-time algebraic Riccati equations", Linear Algebra Appl. 396, 2005):
/// with \f$A_0 = A,\ G_0 = B R^{-1} B^T,\ H_0 = Q\f$,
/// \f[ A_{j+1} = A_j W_j^{-1} A_j,\quad G_{j+1} = G_j + A_j W_j^{-1} G_j A_j^T,\quad
///     H_{j+1} = H_j + A_j^T H_j W_j^{-1} A_j,\quad W_j = I + G_j H_j, \f]
/// and \f$H_j \to X\f$ quadratically when (A, B) is stabilizable and (A, Q) detectable.
/// Only n × n linear solves are needed, no eigenvalue reordering.

#include <adaptobs/core/dimensions.hpp>
#include <adaptobs/core/dynamic_copy.hpp>
#include <adaptobs/core/precompiled.hpp>
#include <adaptobs/core/validation.hpp>
#include <adaptobs/design/schur_stability.hpp>

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <Eigen/LU>

#include <cmath>
#include <limits>

namespace adaptobs {

/// Stabilizing solution of a DARE, with the figures that certify it.
template <typename Scalar, int N>
struct DareSolution {
  Eigen::Matrix<Scalar, N, N> X;  ///< symmetric positive semidefinite solution
  int iterations = 0;             ///< doubling steps taken
  Scalar relative_residual = 0;   ///< ‖X − Ric(X)‖_F / max(1, ‖X‖_F)
};

struct DareOptions {
  int max_iterations = 100;
  double tolerance = 0;  ///< relative change that stops the doubling; 0 selects 100 ε
};

namespace detail {

// Design-time computations run on dynamic-size matrices (DynamicMatrix, from
// core/dynamic_copy.hpp) whatever the caller's sizes: the factorizations they
// use are costly to compile, and one instantiation per scalar type then serves
// every size.

template <typename Scalar>
Scalar dare_relative_residual(const DynamicMatrix<Scalar>& X, const DynamicMatrix<Scalar>& A,
                              const DynamicMatrix<Scalar>& B, const DynamicMatrix<Scalar>& Q,
                              const DynamicMatrix<Scalar>& R) {
  const DynamicMatrix<Scalar> btxa = B.transpose() * X * A;
  const DynamicMatrix<Scalar> s = R + B.transpose() * X * B;
  const DynamicMatrix<Scalar> ric = A.transpose() * X * A - btxa.transpose() * s.llt().solve(btxa) + Q;
  return (X - ric).norm() / std::max(Scalar(1), X.norm());
}

template <typename Scalar>
DareSolution<Scalar, Eigen::Dynamic> solve_dare(const DynamicMatrix<Scalar>& A, const DynamicMatrix<Scalar>& B,
                                                const DynamicMatrix<Scalar>& Q, const DynamicMatrix<Scalar>& R,
                                                DareOptions options) {
  using Square = DynamicMatrix<Scalar>;
  constexpr std::string_view who = "solve_dare";
  require_square(A, who, "A");
  require_finite(A, who, "A");
  const Index n = A.rows();
  require_shape(B, n, B.cols(), who, "B");
  require_finite(B, who, "B");
  require_shape(Q, n, n, who, "Q");
  require_positive_semidefinite(Q, who, "Q");
  require_shape(R, B.cols(), B.cols(), who, "R");
  require_positive_definite(R, who, "R");

  const Scalar tol = options.tolerance > 0 ? Scalar(options.tolerance)
                                           : Scalar(100) * std::numeric_limits<Scalar>::epsilon();
  const Square identity = Square::Identity(n, n);
  Square a = A;
  Square g = B * R.llt().solve(B.transpose());
  Square h = Q;
  DareSolution<Scalar, Eigen::Dynamic> result;
  bool converged = false;
  for (int j = 0; j < options.max_iterations && !converged; ++j) {
    const Eigen::PartialPivLU<Square> w(identity + g * h);
    const Square w_inv_a = w.solve(a);
    const Square w_inv_g = w.solve(g);
    const Square h_next = h + a.transpose() * h * w_inv_a;
    const Square g_next = g + a * w_inv_g * a.transpose();
    a = (a * w_inv_a).eval();
    const Scalar change = (h_next - h).norm();
    h = Scalar(0.5) * (h_next + h_next.transpose());
    g = Scalar(0.5) * (g_next + g_next.transpose());
    result.iterations = j + 1;
    if (!h.allFinite() || !g.allFinite() || !a.allFinite()) break;
    converged = change <= tol * std::max(Scalar(1), h.norm());
  }
  result.X = h;
  constexpr std::string_view no_solution =
      "admit no stabilizing DARE solution: (A, B) must be stabilizable and (A, Q) detectable";
  if (!converged || !result.X.allFinite()) fail_argument(who, "A, B", no_solution);
  result.relative_residual = detail::dare_relative_residual<Scalar>(result.X, A, B, Q, R);
  // The stabilizing solution makes A − B (R + BᵀXB)⁻¹ BᵀXA Schur.
  const Square s = R + B.transpose() * result.X * B;
  const Square closed_loop = A - B * s.llt().solve(B.transpose() * result.X * A);
  if (!is_schur_stable(closed_loop)) fail_argument(who, "A, B", no_solution);
  return result;
}
#ifdef ADAPTOBS_PRECOMPILED
ADAPTOBS_INSTANTIATE DareSolution<double, Eigen::Dynamic> solve_dare<double>(const DynamicMatrix<double>&,
                                                                            const DynamicMatrix<double>&,
                                                                            const DynamicMatrix<double>&,
                                                                            const DynamicMatrix<double>&, DareOptions);
#endif

}  // namespace detail

/// Relative residual \f$\|X - (A^TXA - A^TXB(R + B^TXB)^{-1}B^TXA + Q)\|_F / \max(1,\|X\|_F)\f$.
template <class DX, class DA, class DB, class DQ, class DR>
[[nodiscard]] typename DX::Scalar dare_relative_residual(const Eigen::MatrixBase<DX>& X, const Eigen::MatrixBase<DA>& A,
                                                         const Eigen::MatrixBase<DB>& B, const Eigen::MatrixBase<DQ>& Q,
                                                         const Eigen::MatrixBase<DR>& R) {
  using detail::dynamic_copy;
  return detail::dare_relative_residual<typename DA::Scalar>(dynamic_copy(X), dynamic_copy(A), dynamic_copy(B),
                                                             dynamic_copy(Q), dynamic_copy(R));
}

/// Stabilizing solution of the control-form DARE (see file comment).
/// Throws `ConfigurationError` on invalid arguments or when no stabilizing
/// solution exists ((A, B) not stabilizable or (A, Q) not detectable).
template <class DA, class DB, class DQ, class DR>
[[nodiscard]] auto solve_dare(const Eigen::MatrixBase<DA>& A, const Eigen::MatrixBase<DB>& B,
                              const Eigen::MatrixBase<DQ>& Q, const Eigen::MatrixBase<DR>& R,
                              DareOptions options = {}) {
  using Scalar = typename DA::Scalar;
  using detail::dynamic_copy;
  const auto dynamic = detail::solve_dare<Scalar>(dynamic_copy(A), dynamic_copy(B), dynamic_copy(Q), dynamic_copy(R), options);
  return DareSolution<Scalar, DA::RowsAtCompileTime>{dynamic.X, dynamic.iterations, dynamic.relative_residual};
}

/// Steady-state Kalman gain of \f$x_{k+1} = A x_k + w_k,\ y_k = C x_k + v_k\f$,
/// \f$\mathrm{cov}(w) = Q,\ \mathrm{cov}(v) = R\f$, in predictor form: the
/// one-step predictor \f$\hat x_{k+1} = A\hat x_k + K(y_k - C\hat x_k)\f$ has
/// error dynamics \f$A - KC\f$, which is Schur. P is the a-priori error covariance.
template <typename Scalar, int N, int M>
struct KalmanGain {
  Eigen::Matrix<Scalar, N, M> K;
  Eigen::Matrix<Scalar, N, N> P;
  Scalar relative_residual = 0;
};

namespace detail {
template <typename Scalar>
KalmanGain<Scalar, Eigen::Dynamic, Eigen::Dynamic> steady_state_kalman_gain(const DynamicMatrix<Scalar>& A,
                                                                            const DynamicMatrix<Scalar>& C,
                                                                            const DynamicMatrix<Scalar>& Q,
                                                                            const DynamicMatrix<Scalar>& R,
                                                                            DareOptions options) {
  require_shape(C, C.rows(), A.cols(), "steady_state_kalman_gain", "C");
  const DynamicMatrix<Scalar> at = A.transpose();
  const DynamicMatrix<Scalar> ct = C.transpose();
  const auto dual = detail::solve_dare<Scalar>(at, ct, Q, R, options);
  KalmanGain<Scalar, Eigen::Dynamic, Eigen::Dynamic> result;
  result.P = dual.X;
  result.relative_residual = dual.relative_residual;
  const DynamicMatrix<Scalar> s = C * result.P * ct + R;
  // K = A P Cᵀ S⁻¹  ⇔  Kᵀ = S⁻¹ C P Aᵀ (S and P symmetric).
  result.K = s.llt().solve(C * result.P * at).transpose();
  return result;
}
}  // namespace detail

/// \f$P\f$ solves the dual DARE \f$(A^T, C^T, Q, R)\f$ and
/// \f$K = A P C^T (C P C^T + R)^{-1}\f$.
template <class DA, class DC, class DQ, class DR>
[[nodiscard]] auto steady_state_kalman_gain(const Eigen::MatrixBase<DA>& A, const Eigen::MatrixBase<DC>& C,
                                            const Eigen::MatrixBase<DQ>& Q, const Eigen::MatrixBase<DR>& R,
                                            DareOptions options = {}) {
  using Scalar = typename DA::Scalar;
  using detail::dynamic_copy;
  const auto dynamic =
      detail::steady_state_kalman_gain<Scalar>(dynamic_copy(A), dynamic_copy(C), dynamic_copy(Q), dynamic_copy(R), options);
  return KalmanGain<Scalar, DA::RowsAtCompileTime, DC::RowsAtCompileTime>{dynamic.K, dynamic.P,
                                                                           dynamic.relative_residual};
}

}  // namespace adaptobs
