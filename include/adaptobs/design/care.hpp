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
/// \f$(W + I)\begin{bmatrix} I\\ X\end{bmatrix} = 0\f$, then refined by Newton's method
/// (D. L. Kleinman, "On an iterative technique for Riccati equation computations",
/// IEEE TAC 13(1), 1968) in defect-correction form: with
/// \f$\mathcal R(X) = A^TX + XA - XGX + Q\f$ and \f$A_c = A - GX\f$, the step N solves the
/// Lyapunov equation \f$A_c^TN + NA_c + \mathcal R(X) = 0\f$; steps stop when the residual
/// no longer decreases. G may be indefinite, which the positive-real
/// certificate of `positive_real.hpp` needs.
///
/// `solve_care` (G = BR⁻¹Bᵀ ⪰ 0) first scales X and balances the states
/// (design/riccati_support.hpp). When the sign function fails (a badly
/// conditioned Hamiltonian), Newton's method starts instead from a gain K₀ with
/// A − BK₀ Hurwitz, taken from the well-scaled CARE (A, B, I, ‖B‖²I), whose
/// solution exists exactly when (A, B) is stabilizable: X₀ solves
/// \f$(A - BK_0)^TX_0 + X_0(A - BK_0) + Q + K_0^TRK_0 = 0\f$. The result is accepted only if
/// its relative residual
/// \f$\|\mathcal R(X)\|_F / (2\|A\|_F\|X\|_F + \|G\|_F\|X\|_F^2 + \|Q\|_F)\f$ is at most max(1e-10, 1000 ε)
/// and A − GX is Hurwitz with a margin of √ε‖A − GX‖_F. Otherwise it refuses,
/// naming the reason it can establish: (A, B) not stabilizable, a mode on the
/// imaginary axis unobserved by Q, or an equation too ill-conditioned for the
/// working precision.

#include <adaptobs/core/detail/dynamic_copy.hpp>
#include <adaptobs/core/precompiled.hpp>
#include <adaptobs/core/validation.hpp>
#include <adaptobs/design/lyapunov.hpp>
#include <adaptobs/design/riccati_support.hpp>
#include <adaptobs/design/stability.hpp>

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <Eigen/LU>
#include <Eigen/QR>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string_view>

namespace adaptobs {

/// Stabilizing solution of a continuous ARE, with the figures that certify it.
template <typename Scalar, int N>
struct CareSolution {
  Eigen::Matrix<Scalar, N, N> X;  ///< symmetric solution with A − GX Hurwitz
  int iterations = 0;             ///< sign-function iterations plus Newton steps
  /// Relative residual, each term bounded by its factors' norms (see file comment), of the
  /// scaled and balanced equation the iteration solves, not of (A, B, Q, R) as given:
  /// the error of X itself can exceed it by the condition number of the equation.
  Scalar relative_residual = 0;
};

namespace detail {

/// The CARE residual at X and the closed loop Newton's method uses.
template <typename Scalar>
struct CareEvaluation {
  DynamicMatrix<Scalar> residual;     ///< AᵀX + XA − XGX + Q
  DynamicMatrix<Scalar> closed_loop;  ///< A − GX
  Scalar relative = std::numeric_limits<Scalar>::infinity();
};

template <typename Scalar>
CareEvaluation<Scalar> evaluate_care(const DynamicMatrix<Scalar>& X, const DynamicMatrix<Scalar>& A,
                                     const DynamicMatrix<Scalar>& G, const DynamicMatrix<Scalar>& Q) {
  CareEvaluation<Scalar> e;
  const DynamicMatrix<Scalar> atx = A.transpose() * X;
  const DynamicMatrix<Scalar> gx = G * X;
  e.residual = symmetric_part<Scalar>(atx + atx.transpose() - X * gx + Q);
  e.closed_loop = A - gx;
  const Scalar x_norm = X.norm();
  const Scalar scale = Scalar(2) * A.norm() * x_norm + G.norm() * x_norm * x_norm + Q.norm();
  const Scalar residual_norm = e.residual.norm();
  e.relative = scale > Scalar(0) ? residual_norm / scale : residual_norm;
  if (!X.allFinite() || !std::isfinite(e.relative)) e.relative = std::numeric_limits<Scalar>::infinity();
  return e;
}

/// Hurwitz with a margin relative to ‖M‖_F: by default √ε, which keeps the
/// Newton Lyapunov equations regular and accepts a solution.
template <typename Scalar>
bool is_hurwitz_with_margin(const DynamicMatrix<Scalar>& m,
                            Scalar relative_margin = std::sqrt(std::numeric_limits<Scalar>::epsilon())) {
  return m.allFinite() && is_hurwitz_stable(m, relative_margin * m.norm());
}

/// Solution of \f$M^TN + NM + W = 0\f$, or nothing when M has a pair of
/// eigenvalues summing to (nearly) zero, where the Lyapunov solver refuses.
template <typename Scalar>
std::optional<DynamicMatrix<Scalar>> lyapunov_if_regular(const DynamicMatrix<Scalar>& M,
                                                         const DynamicMatrix<Scalar>& W) {
  try {
    return solve_continuous_lyapunov_dense<Scalar>(M, W);
  } catch (const ConfigurationError&) {
    return std::nullopt;
  }
}

/// X from the sign function of the Hamiltonian, or nothing when the Hamiltonian
/// has an eigenvalue at 0 or an iterate is not finite.
template <typename Scalar>
std::optional<DynamicMatrix<Scalar>> care_sign_function_start(const DynamicMatrix<Scalar>& a,
                                                              const DynamicMatrix<Scalar>& g,
                                                              const DynamicMatrix<Scalar>& q, int max_iterations,
                                                              int& iterations) {
  using Matrix = DynamicMatrix<Scalar>;
  const Index n = a.rows();
  Matrix z(2 * n, 2 * n);
  z << a, -g, -q, -a.transpose();
  const Scalar eps = std::numeric_limits<Scalar>::epsilon();
  bool converged = false;
  for (int it = 0; it < max_iterations && !converged; ++it) {
    const Eigen::PartialPivLU<Matrix> lu(z);
    if (!has_regular_pivots(lu)) return std::nullopt;  // eigenvalue at 0: not hyperbolic
    // |det Z| from the pivots' logarithms, which cannot overflow.
    const Scalar log_abs_determinant = lu.matrixLU().diagonal().cwiseAbs().array().log().sum();
    const Scalar c = std::exp(-log_abs_determinant / Scalar(2 * n));
    const Matrix next = Scalar(0.5) * (c * z + lu.inverse() / c);
    if (!next.allFinite()) return std::nullopt;
    const Scalar change = (next - z).cwiseAbs().colwise().sum().maxCoeff();
    converged = change <= Scalar(1000) * Scalar(2 * n) * eps * next.cwiseAbs().colwise().sum().maxCoeff();
    z = next;
    ++iterations;
  }
  Matrix lhs(2 * n, n), rhs(2 * n, n);
  lhs << z.topRightCorner(n, n), z.bottomRightCorner(n, n) + Matrix::Identity(n, n);
  rhs << -(z.topLeftCorner(n, n) + Matrix::Identity(n, n)), -z.bottomLeftCorner(n, n);
  const Matrix x = symmetric_part<Scalar>(lhs.colPivHouseholderQr().solve(rhs));
  if (!x.allFinite()) return std::nullopt;
  return x;
}

/// Newton steps (file comment) from x while the residual decreases and A − GX
/// stays Hurwitz with a margin; returns the evaluation of the final x.
template <typename Scalar>
CareEvaluation<Scalar> care_newton_refinement(DynamicMatrix<Scalar>& x, const DynamicMatrix<Scalar>& a,
                                              const DynamicMatrix<Scalar>& g, const DynamicMatrix<Scalar>& q,
                                              int& iterations) {
  // No stop at a small residual: near a mode on the axis the steps converge only
  // linearly, and the closed loop reaches the axis's neighbourhood that the margin rejects.
  auto e = evaluate_care<Scalar>(x, a, g, q);
  for (int step = 0; step < 50; ++step) {
    if (!is_hurwitz_with_margin(e.closed_loop)) break;
    const auto step_matrix = lyapunov_if_regular<Scalar>(e.closed_loop, e.residual);
    if (!step_matrix) break;
    DynamicMatrix<Scalar> candidate = symmetric_part<Scalar>(x + *step_matrix);
    auto next = evaluate_care<Scalar>(candidate, a, g, q);
    if (!(next.relative < e.relative)) break;
    x = std::move(candidate);
    e = std::move(next);
    ++iterations;
  }
  return e;
}

inline constexpr RiccatiRoles control_care_roles{
    "solve_care", "B",
    "must be stabilizable: a mode of A in the closed right half-plane is not reached by B, so no gain makes A - BK "
    "Hurwitz",
    "leave a mode of A on the imaginary axis unobserved by Q: the CARE has no stabilizing solution"};

/// X = D⁻¹X̃D⁻¹: a solution of the balanced equation in the caller's states.
template <typename Scalar>
DynamicMatrix<Scalar> unbalance(const DynamicMatrix<Scalar>& x, const Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& d) {
  return d.cwiseInverse().asDiagonal() * x * d.cwiseInverse().asDiagonal();
}

/// A gain K with A − BK Hurwitz, from the well-scaled CARE (A, B, I, ‖B‖²I) of
/// the balanced problem, or nothing when (A, B) is not stabilizable (or too
/// close to it for the precision).
template <typename Scalar>
std::optional<DynamicMatrix<Scalar>> continuous_stabilizing_gain(const DynamicMatrix<Scalar>& A,
                                                                 const DynamicMatrix<Scalar>& B, int& iterations) {
  using Matrix = DynamicMatrix<Scalar>;
  const Index n = A.rows();
  const Scalar b2 = B.squaredNorm();
  if (!(b2 > Scalar(0))) {  // K = 0 is the only gain: A itself must be Hurwitz
    if (!is_hurwitz_with_margin(A, stabilizability_margin<Scalar>)) return std::nullopt;
    return Matrix::Zero(B.cols(), n);
  }
  Matrix a = A, g = B * B.transpose() / b2, q = Matrix::Identity(n, n);
  const auto d = balance_hamiltonian<Scalar>(a, g, q);
  auto x = care_sign_function_start<Scalar>(a, g, q, 100, iterations);
  if (!x) return std::nullopt;
  (void)care_newton_refinement<Scalar>(*x, a, g, q, iterations);
  // Back to the caller's states, K = BᵀX / ‖B‖² with X = D⁻¹X̃D⁻¹; an A − BK
  // Hurwitz beyond rounding proves stabilizability.
  const Matrix k = B.transpose() * unbalance(*x, d) / b2;
  if (!k.allFinite() || !is_hurwitz_with_margin(Matrix(A - B * k), stabilizability_margin<Scalar>)) return std::nullopt;
  return k;
}

}  // namespace detail

/// Stabilizing solution of the control CARE on dynamic-size matrices: the design
/// routine behind every `solve_care`, one instance per scalar type (compiled once
/// for `double` in `adaptobs::precompiled`). The algorithm is the file comment's:
/// X scaled by a power of two and the states balanced (design/riccati_support.hpp),
/// the sign function of the Hamiltonian by Byers' scaled Newton iteration (1987;
/// `Eigen::PartialPivLU` for the inverses and determinants) or, when it fails,
/// Kleinman's step from a stabilizing gain, then Newton–Kleinman refinement
/// (Kleinman 1968) with Bartels–Stewart Lyapunov steps (design/lyapunov.hpp).
/// `roles` gives the names a refusal uses (the Kalman–Bucy gain, which solves the
/// dual equation, passes its own). Throws as the fixed-size `solve_care` below.
template <typename Scalar>
[[nodiscard]] CareSolution<Scalar, Eigen::Dynamic> solve_care(
    const detail::DynamicMatrix<Scalar>& A, const detail::DynamicMatrix<Scalar>& B,
    const detail::DynamicMatrix<Scalar>& Q, const detail::DynamicMatrix<Scalar>& R,
    const detail::RiccatiRoles& roles = detail::control_care_roles) {
  using Matrix = detail::DynamicMatrix<Scalar>;
  using namespace detail;
  validate_riccati_data(A, B, Q, R, roles);
  CareSolution<Scalar, Eigen::Dynamic> result;
  const Index n = A.rows();
  if (n == 0) return result;
  constexpr Scalar eps = std::numeric_limits<Scalar>::epsilon();
  const Scalar tolerance = std::max(Scalar(1e-10), Scalar(1000) * eps);

  // X = σ D⁻¹X̃D⁻¹: X̃ solves the scaled, balanced equation (a, g, q).
  const Scalar sigma = riccati_solution_scale<Scalar>(B, Q, R);
  const Matrix r = R / sigma;
  Matrix a = A, g = symmetric_part<Scalar>(B * Eigen::LLT<Matrix>(r).solve(B.transpose())), q = Q / sigma;
  const auto d = balance_hamiltonian<Scalar>(a, g, q);
  auto start = care_sign_function_start<Scalar>(a, g, q, 100, result.iterations);
  bool stabilizable = false;  // proven by a gain that makes A − BK Hurwitz
  if (start) {
    stabilizable =
        is_hurwitz_with_margin(evaluate_care<Scalar>(*start, a, g, q).closed_loop, stabilizability_margin<Scalar>);
    if (!stabilizable) start.reset();
  }
  if (!start) {
    const auto k0 = continuous_stabilizing_gain<Scalar>(A, B, result.iterations);
    if (!k0) fail_not_stabilizable(roles);
    stabilizable = true;
    // Kleinman's first step, in the scaled and balanced coordinates: K̃ = K₀D.
    const Matrix k = *k0 * d.asDiagonal();
    const Matrix b = d.cwiseInverse().asDiagonal() * B;
    start = lyapunov_if_regular<Scalar>(Matrix(a - b * k), symmetric_part<Scalar>(q + k.transpose() * r * k));
    if (!start) start = Matrix::Constant(n, n, std::numeric_limits<Scalar>::infinity());  // refused below
  }
  Matrix x = *start;
  const auto e = care_newton_refinement<Scalar>(x, a, g, q, result.iterations);
  if (e.relative <= tolerance && is_hurwitz_with_margin(e.closed_loop)) {
    result.X = sigma * unbalance(x, d);
    if (!result.X.allFinite()) fail_out_of_range(roles);
    result.relative_residual = e.relative;
    return result;
  }

  int ignored = 0;
  if (!stabilizable && !continuous_stabilizing_gain<Scalar>(A, B, ignored)) fail_not_stabilizable(roles);
  // A mode unobserved by Q on the imaginary axis: (Aᵀ, Q) is not stabilizable,
  // but becomes so once A is shifted left by 1e-6 ‖A‖, which moves the axis's
  // modes into the left half-plane and leaves those further right unstable.
  const Matrix at = A.transpose(), q_scaled = Q / sigma;
  const Scalar shift = Scalar(1e-6) * (A.norm() > Scalar(0) ? A.norm() : Scalar(1));
  if (!continuous_stabilizing_gain<Scalar>(at, q_scaled, ignored) &&
      continuous_stabilizing_gain<Scalar>(Matrix(at - shift * Matrix::Identity(n, n)), q_scaled, ignored))
    fail_unreached_mode(roles);
  const bool finite = e.closed_loop.allFinite();
  fail_ill_conditioned(roles, e.relative, tolerance, "spectral abscissa",
                       finite ? spectral_abscissa(e.closed_loop) : std::numeric_limits<Scalar>::infinity(),
                       finite ? -std::sqrt(eps) * e.closed_loop.norm() : Scalar(0));
}

/// Stabilizing solution of \f$A^TX + XA - XGX + Q = 0\f$ on dynamic-size matrices
/// (G, Q symmetric, either possibly indefinite): Byers' sign-function start refined
/// by Newton–Kleinman steps (file comment), or nothing when the Hamiltonian has
/// eigenvalues on the imaginary axis or the result fails its residual (√ε) or
/// stability check. Throws as the overload below.
template <typename Scalar>
[[nodiscard]] std::optional<CareSolution<Scalar, Eigen::Dynamic>> solve_riccati_hamiltonian(
    const detail::DynamicMatrix<Scalar>& A, const detail::DynamicMatrix<Scalar>& G,
    const detail::DynamicMatrix<Scalar>& Q, int max_iterations = 100) {
  constexpr std::string_view who = "solve_riccati_hamiltonian";
  require_square(A, who, "A");
  require_finite(A, who, "A");
  require_finite_shape(G, A.rows(), A.rows(), who, "G");
  require_symmetric(G, who, "G");
  require_finite_shape(Q, A.rows(), A.rows(), who, "Q");
  require_symmetric(Q, who, "Q");
  require(max_iterations >= 1, who, "max_iterations", "must be at least 1");
  CareSolution<Scalar, Eigen::Dynamic> result;
  if (A.rows() == 0) return result;
  auto x = detail::care_sign_function_start<Scalar>(A, G, Q, max_iterations, result.iterations);
  if (!x) return std::nullopt;
  const auto e = detail::care_newton_refinement<Scalar>(*x, A, G, Q, result.iterations);
  if (!(e.relative <= std::sqrt(std::numeric_limits<Scalar>::epsilon())) || !is_hurwitz_stable(e.closed_loop))
    return std::nullopt;
  result.X = *x;
  result.relative_residual = e.relative;
  return result;
}

/// Steady-state Kalman–Bucy gain of \f$\dot x = Ax + w,\ y = Cx + v\f$ (spectral
/// densities Q, R): P solves \f$AP + PA^T - PC^TR^{-1}CP + Q = 0\f$, \f$K = PC^TR^{-1}\f$,
/// and \f$A - KC\f$ is Hurwitz.
template <typename Scalar, int N, int M>
struct KalmanBucyGain {
  Eigen::Matrix<Scalar, N, M> K;
  Eigen::Matrix<Scalar, N, N> P;
  Scalar relative_residual = 0;  ///< that of the dual CARE (`CareSolution::relative_residual`)
};

/// The steady-state Kalman–Bucy gain on dynamic-size matrices: P from the dual
/// CARE \f$(A^T, C^T, Q, R)\f$ (`solve_care` above), \f$K^T = R^{-1}CP\f$ by `Eigen::LLT`.
template <typename Scalar>
[[nodiscard]] KalmanBucyGain<Scalar, Eigen::Dynamic, Eigen::Dynamic> kalman_bucy_gain(
    const detail::DynamicMatrix<Scalar>& A, const detail::DynamicMatrix<Scalar>& C,
    const detail::DynamicMatrix<Scalar>& Q, const detail::DynamicMatrix<Scalar>& R) {
  using Matrix = detail::DynamicMatrix<Scalar>;
  // The dual equation (Aᵀ, Cᵀ, Q, R), with its refusals in the filter's terms.
  static constexpr detail::RiccatiRoles roles{
      "kalman_bucy_gain", "C",
      "must be detectable: a mode of A in the closed right half-plane is not seen by C, so no gain makes A - KC "
      "Hurwitz",
      "leave a mode of A on the imaginary axis unexcited by the process noise Q: the filter CARE has no stabilizing "
      "solution"};
  require_square(A, roles.who, "A");
  require_shape(C, C.rows(), A.cols(), roles.who, "C");
  const auto dual = solve_care(Matrix(A.transpose()), Matrix(C.transpose()), Q, R, roles);
  KalmanBucyGain<Scalar, Eigen::Dynamic, Eigen::Dynamic> result;
  result.P = dual.X;
  result.relative_residual = dual.relative_residual;
  // K = P Cᵀ R⁻¹  ⇔  Kᵀ = R⁻¹ C P.
  result.K = Eigen::LLT<Matrix>(R).solve(C * result.P).transpose();
  return result;
}

#ifdef ADAPTOBS_PRECOMPILED
ADAPTOBS_INSTANTIATE CareSolution<double, Eigen::Dynamic> solve_care<double>(const detail::DynamicMatrix<double>&,
                                                                             const detail::DynamicMatrix<double>&,
                                                                             const detail::DynamicMatrix<double>&,
                                                                             const detail::DynamicMatrix<double>&,
                                                                             const detail::RiccatiRoles&);
ADAPTOBS_INSTANTIATE std::optional<CareSolution<double, Eigen::Dynamic>> solve_riccati_hamiltonian<double>(
    const detail::DynamicMatrix<double>&, const detail::DynamicMatrix<double>&, const detail::DynamicMatrix<double>&,
    int);
ADAPTOBS_INSTANTIATE KalmanBucyGain<double, Eigen::Dynamic, Eigen::Dynamic> kalman_bucy_gain<double>(
    const detail::DynamicMatrix<double>&, const detail::DynamicMatrix<double>&, const detail::DynamicMatrix<double>&,
    const detail::DynamicMatrix<double>&);
#endif

/// Stabilizing solution of \f$A^TX + XA - XGX + Q = 0\f$ sized as the caller's A
/// (the dynamic-size overload above does the work). A, G, Q not square, finite and
/// of one size, G or Q not symmetric, or `max_iterations` < 1 throw a
/// `ConfigurationError` naming the argument.
template <class DA, class DG, class DQ>
[[nodiscard]] std::optional<CareSolution<typename DA::Scalar, DA::RowsAtCompileTime>> solve_riccati_hamiltonian(
    const Eigen::MatrixBase<DA>& A, const Eigen::MatrixBase<DG>& G, const Eigen::MatrixBase<DQ>& Q,
    int max_iterations = 100) {
  using detail::dynamic_copy;
  const auto dynamic = solve_riccati_hamiltonian(dynamic_copy(A), dynamic_copy(G), dynamic_copy(Q), max_iterations);
  if (!dynamic) return std::nullopt;
  return detail::with_order<DA::RowsAtCompileTime>(*dynamic);
}

/// Stabilizing solution of the control CARE \f$A^TX + XA - XBR^{-1}B^TX + Q = 0\f$
/// (see file comment), sized as the caller's A; the dynamic-size overload above
/// does the work. Throws `ConfigurationError` on invalid arguments, and
/// refuses, naming the reason, when no stabilizing solution exists or the
/// working precision cannot reach the stated residual.
template <class DA, class DB, class DQ, class DR>
[[nodiscard]] auto solve_care(const Eigen::MatrixBase<DA>& A, const Eigen::MatrixBase<DB>& B,
                              const Eigen::MatrixBase<DQ>& Q, const Eigen::MatrixBase<DR>& R) {
  using detail::dynamic_copy;
  return detail::with_order<DA::RowsAtCompileTime>(
      solve_care(dynamic_copy(A), dynamic_copy(B), dynamic_copy(Q), dynamic_copy(R)));
}

/// The steady-state Kalman–Bucy gain sized as the caller's A and C (the
/// dynamic-size overload above does the work).
template <class DA, class DC, class DQ, class DR>
[[nodiscard]] auto kalman_bucy_gain(const Eigen::MatrixBase<DA>& A, const Eigen::MatrixBase<DC>& C,
                                    const Eigen::MatrixBase<DQ>& Q, const Eigen::MatrixBase<DR>& R) {
  using Scalar = typename DA::Scalar;
  using detail::dynamic_copy;
  const auto dynamic = kalman_bucy_gain(dynamic_copy(A), dynamic_copy(C), dynamic_copy(Q), dynamic_copy(R));
  return KalmanBucyGain<Scalar, DA::RowsAtCompileTime, DC::RowsAtCompileTime>{dynamic.K, dynamic.P,
                                                                              dynamic.relative_residual};
}

}  // namespace adaptobs
