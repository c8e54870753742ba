#pragma once
/// \file
/// Continuous algebraic Riccati equations and the steady-state Kalman–Bucy gain.
///
/// The stabilizing solution of
/// \f[ A^TX + XA - XGX + Q = 0 \f]
/// spans the stable invariant subspace of the Hamiltonian
/// \f$\mathcal H = \begin{bmatrix} A & -G \\ -Q & -A^T\end{bmatrix}\f$:
/// \f$\mathcal H\begin{bmatrix} I\\ X\end{bmatrix} = \begin{bmatrix} I\\ X\end{bmatrix}(A - GX)\f$.
/// It is read off the matrix sign function \f$W = \mathrm{sign}(\mathcal H)\f$
/// (Newton iteration \f$Z \leftarrow \tfrac12(cZ + (cZ)^{-1})\f$ with determinant
/// scaling; R. Byers, "Solving the algebraic Riccati equation with the matrix
/// sign function", Linear Algebra Appl. 85, 1987) from
/// \f$(W + I)\begin{bmatrix} I\\ X\end{bmatrix} = 0\f$, then polished by Newton–Kleinman
/// steps (each a Lyapunov solve) and verified by its residual. G may be
/// indefinite, which the positive-real certificate of `positive_real.hpp` needs.

#include <adaptobs/core/validation.hpp>
#include <adaptobs/design/lyapunov.hpp>
#include <adaptobs/design/stability.hpp>

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <Eigen/LU>
#include <Eigen/QR>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

namespace adaptobs {

/// Stabilizing solution of a continuous ARE, with the figures that certify it.
template <typename Scalar, int N>
struct CareSolution {
  Eigen::Matrix<Scalar, N, N> X;  ///< symmetric solution with A − GX Hurwitz
  int iterations = 0;             ///< sign-function iterations
  Scalar relative_residual = 0;   ///< ‖AᵀX + XA − XGX + Q‖_F / max(1, ‖X‖_F)
};

namespace detail {
template <class X, class A, class G, class Q>
typename X::Scalar care_residual(const X& x, const A& a, const G& g, const Q& q) {
  using Scalar = typename X::Scalar;
  return (a.transpose() * x + x * a - x * g * x + q).norm() / std::max(Scalar(1), x.norm());
}
}  // namespace detail

/// Stabilizing solution of \f$A^TX + XA - XGX + Q = 0\f$ (G, Q symmetric),
/// or nothing when the Hamiltonian has eigenvalues on the imaginary axis or
/// the computed X fails its residual or stability check.
template <class DA, class DG, class DQ>
[[nodiscard]] std::optional<CareSolution<typename DA::Scalar, DA::RowsAtCompileTime>> solve_riccati_hamiltonian(
    const Eigen::MatrixBase<DA>& A, const Eigen::MatrixBase<DG>& G, const Eigen::MatrixBase<DQ>& Q,
    int max_iterations = 100) {
  using Scalar = typename DA::Scalar;
  using Matrix = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;
  constexpr int N = DA::RowsAtCompileTime;
  const Index n = A.rows();
  const Matrix a = A, g = G, q = Q;
  Matrix z(2 * n, 2 * n);
  z << a, -g, -q, -a.transpose();
  const Scalar eps = std::numeric_limits<Scalar>::epsilon();
  CareSolution<Scalar, N> result;
  bool converged = false;
  for (int it = 0; it < max_iterations && !converged; ++it) {
    const Eigen::PartialPivLU<Matrix> lu(z);
    const Matrix& lu_matrix = lu.matrixLU();
    Scalar log_det = 0;
    for (Index i = 0; i < 2 * n; ++i) {
      const Scalar d = std::abs(lu_matrix(i, i));
      if (!(d > 0)) return std::nullopt;  // eigenvalue at 0: not hyperbolic
      log_det += std::log(d);
    }
    const Scalar c = std::exp(-log_det / Scalar(2 * n));
    const Matrix next = Scalar(0.5) * (c * z + lu.inverse() / c);
    if (!next.allFinite()) return std::nullopt;
    const Scalar change = (next - z).cwiseAbs().colwise().sum().maxCoeff();
    converged = change <= Scalar(1000) * Scalar(2 * n) * eps * next.cwiseAbs().colwise().sum().maxCoeff();
    z = next;
    result.iterations = it + 1;
  }
  Matrix lhs(2 * n, n), rhs(2 * n, n);
  lhs << z.topRightCorner(n, n), z.bottomRightCorner(n, n) + Matrix::Identity(n, n);
  rhs << -(z.topLeftCorner(n, n) + Matrix::Identity(n, n)), -z.bottomLeftCorner(n, n);
  Matrix x = lhs.colPivHouseholderQr().solve(rhs);
  x = Scalar(0.5) * (x + x.transpose());
  if (!x.allFinite()) return std::nullopt;

  // Newton–Kleinman polish: (A − GX)ᵀX⁺ + X⁺(A − GX) = −(Q + XGX).
  Scalar residual = detail::care_residual(x, a, g, q);
  for (int k = 0; k < 3 && residual > 10 * eps; ++k) {
    const Matrix closed = a - g * x;
    // A margin keeps the Lyapunov equation regular (no eigenvalue pair with λ_i + λ_j ≈ 0).
    if (!is_hurwitz_stable(closed, std::sqrt(eps) * std::max(Scalar(1), closed.cwiseAbs().maxCoeff()))) break;
    const Matrix candidate = solve_continuous_lyapunov(closed, Matrix(q + x * g * x));
    const Scalar candidate_residual = detail::care_residual(candidate, a, g, q);
    if (!(candidate_residual < residual)) break;
    x = candidate;
    residual = candidate_residual;
  }
  result.X = x;
  result.relative_residual = residual;
  if (!(residual <= std::sqrt(eps)) || !is_hurwitz_stable(Matrix(a - g * x))) return std::nullopt;
  return result;
}

/// Stabilizing solution of the control CARE \f$A^TX + XA - XBR^{-1}B^TX + Q = 0\f$.
/// Throws `ConfigurationError` when (A, B) is not stabilizable or (A, Q) not detectable.
template <class DA, class DB, class DQ, class DR>
[[nodiscard]] auto solve_care(const Eigen::MatrixBase<DA>& A, const Eigen::MatrixBase<DB>& B,
                              const Eigen::MatrixBase<DQ>& Q, const Eigen::MatrixBase<DR>& R) {
  constexpr std::string_view who = "solve_care";
  detail::require_square(A, who, "A");
  detail::require_finite(A, who, "A");
  const Index n = A.rows();
  detail::require_shape(B, n, B.cols(), who, "B");
  detail::require_finite(B, who, "B");
  detail::require_shape(Q, n, n, who, "Q");
  detail::require_positive_semidefinite(Q, who, "Q");
  detail::require_shape(R, B.cols(), B.cols(), who, "R");
  detail::require_positive_definite(R, who, "R");
  using Matrix = Eigen::Matrix<typename DA::Scalar, Eigen::Dynamic, Eigen::Dynamic>;
  const Matrix g = B * R.llt().solve(B.transpose());
  auto solution = solve_riccati_hamiltonian(A, g, Q);
  if (!solution)
    detail::fail_argument(who, "A, B", "admit no stabilizing CARE solution: (A, B) must be stabilizable and "
                                       "(A, Q) detectable");
  return *solution;
}

/// Steady-state Kalman–Bucy gain of \f$\dot x = Ax + w,\ y = Cx + v\f$ (spectral
/// densities Q, R): P solves \f$AP + PA^T - PC^TR^{-1}CP + Q = 0\f$, \f$K = PC^TR^{-1}\f$,
/// and \f$A - KC\f$ is Hurwitz.
template <typename Scalar, int N, int M>
struct KalmanBucyGain {
  Eigen::Matrix<Scalar, N, M> K;
  Eigen::Matrix<Scalar, N, N> P;
  Scalar relative_residual = 0;
};

template <class DA, class DC, class DQ, class DR>
[[nodiscard]] auto kalman_bucy_gain(const Eigen::MatrixBase<DA>& A, const Eigen::MatrixBase<DC>& C,
                                    const Eigen::MatrixBase<DQ>& Q, const Eigen::MatrixBase<DR>& R) {
  using Scalar = typename DA::Scalar;
  constexpr int N = DA::RowsAtCompileTime;
  constexpr int M = DC::RowsAtCompileTime;
  detail::require_shape(C, C.rows(), A.cols(), "kalman_bucy_gain", "C");
  const auto dual = solve_care(A.transpose(), C.transpose(), Q, R);
  KalmanBucyGain<Scalar, N, M> result;
  result.P = dual.X;
  result.relative_residual = dual.relative_residual;
  // K = P Cᵀ R⁻¹  ⇔  Kᵀ = R⁻¹ C P.
  result.K = R.llt().solve(C * result.P).transpose();
  return result;
}

}  // namespace adaptobs
