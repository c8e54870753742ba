#pragma once
/// \file
/// Discrete algebraic Riccati equation and the steady-state Kalman gain.
///
/// The DARE
/// \f[ X = A^T X A - A^T X B (R + B^T X B)^{-1} B^T X A + Q \f]
/// has a stabilizing solution (A − BK Schur with \f$K = (R + B^TXB)^{-1}B^TXA\f$)
/// exactly when (A, B) is stabilizable and no mode of A on the unit circle is
/// unobserved by Q. It is computed in three stages:
///
/// 1. **Scaling.** With \f$X = \sigma\tilde X\f$ the equation keeps its form with
///    \f$(A, B, Q/\sigma, R/\sigma)\f$. σ, a power of two (no rounding), is the larger
///    of \f$\|Q\|\f$ and \f$\|R\|/\|B\|^2\f$ (design/riccati_support.hpp), so that a huge R
///    (X of order R) or a huge Q cannot overflow the products below.
/// 2. **Doubling.** The structure-preserving doubling algorithm (SDA; E. K.-W. Chu,
///    H.-Y. Fan, W.-W. Lin, "A structure-preserving doubling algorithm for
///    discrete-time algebraic Riccati equations", Linear Algebra Appl. 396, 2005):
///    with \f$A_0 = A,\ G_0 = B R^{-1} B^T,\ H_0 = Q\f$,
///    \f[ A_{j+1} = A_j W_j^{-1} A_j,\quad G_{j+1} = G_j + A_j W_j^{-1} G_j A_j^T,\quad
///        H_{j+1} = H_j + A_j^T H_j W_j^{-1} A_j,\quad W_j = I + G_j H_j, \f]
///    and \f$H_j \to X\f$ quadratically. When \f$G_0H_0\f$ is huge (a tiny R), \f$W_j\f$ is
///    ill-conditioned and SDA loses digits or fails; the start then comes from
///    a stabilizing gain \f$K_0\f$ of the well-scaled DARE \f$(A, B, I, \|B\|^2 I)\f$,
///    whose solution exists exactly when (A, B) is stabilizable, and the Stein
///    equation \f$X_0 = A_0^TX_0A_0 + Q + K_0^TRK_0\f$, \f$A_0 = A - BK_0\f$ (Hewer's step).
/// 3. **Newton refinement** (G. A. Hewer, "An iterative technique for the computation
///    of the steady state gains for the discrete optimal regulator", IEEE TAC 16(4),
///    1971), in defect-correction form: with the residual
///    \f$\mathcal R(X) = A^TXA - A^TXBK + Q - X\f$ and \f$A_c = A - BK\f$, the
///    derivative of \f$\mathcal R\f$ is \f$N \mapsto A_c^TNA_c - N\f$, so the step N solves the
///    Stein equation \f$N = A_c^TNA_c + \mathcal R(X)\f$ (design/stein.hpp). Steps stop
///    when the residual no longer decreases.
///
/// The result is accepted only if its relative residual is at most the stated
/// tolerance and its closed loop is Schur with a margin. The residual is scaled
/// per term, \f$\|\mathcal R(X)\|_F / (\|X\|_F + \|A^TXA\|_F + \|A^TXBK\|_F + \|Q\|_F)\f$: it is the
/// relative size of the perturbation of the terms that X satisfies exactly, and
/// it does not read large when two huge terms cancel. Otherwise the solver
/// refuses, naming the reason it can establish: (A, B) not stabilizable, a mode
/// on the unit circle unobserved by Q, or an equation too ill-conditioned for
/// the working precision (with the residual reached).

#include <adaptobs/core/detail/dynamic_copy.hpp>
#include <adaptobs/core/dimensions.hpp>
#include <adaptobs/core/precompiled.hpp>
#include <adaptobs/core/validation.hpp>
#include <adaptobs/design/riccati_support.hpp>
#include <adaptobs/design/schur_stability.hpp>
#include <adaptobs/design/stein.hpp>

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string_view>

namespace adaptobs {

/// Stabilizing solution of a DARE, with the figures that certify it.
template <typename Scalar, int N>
struct DareSolution {
  Eigen::Matrix<Scalar, N, N> X;  ///< symmetric positive semidefinite solution
  int iterations = 0;             ///< doubling steps plus Newton steps
  Scalar relative_residual = 0;   ///< per-term relative residual (see file comment), at most the tolerance
};

struct DareOptions {
  int max_iterations = 100;  ///< doubling steps; Newton steps are limited to 50
  double tolerance = 0;      ///< relative change that stops the doubling; 0 selects 100 ε
  /// Largest accepted per-term relative residual; 0 selects max(1e-10, 1000 ε).
  double residual_tolerance = 0;
  /// The closed loop must have spectral radius below 1 − margin; 0 selects √ε.
  /// A smaller radius cannot be told apart from a mode on the unit circle.
  double stability_margin = 0;
};

namespace detail {

// The products here (and in stein.hpp, schur_stability.hpp, polynomial.hpp) are
// Eigen's lazy, coefficient-based ones: the few dozen rows of a design problem
// do not need the cache-blocked product, costly to compile per combination of
// transposed operands.

inline constexpr RiccatiRoles control_dare_roles{
    "solve_dare", "B",
    "must be stabilizable: a mode of A on or outside the unit circle is not reached by B, so no gain makes A - BK "
    "Schur",
    "leave a mode of A on the unit circle unobserved by Q: the DARE has no stabilizing solution"};

/// The DARE residual at X and the quantities Newton's method reuses.
template <typename Scalar>
struct DareEvaluation {
  DynamicMatrix<Scalar> residual;  ///< AᵀXA − AᵀXBK + Q − X
  DynamicMatrix<Scalar> gain;      ///< K = (R + BᵀXB)⁻¹BᵀXA
  Scalar relative = std::numeric_limits<Scalar>::infinity();
  bool valid = false;  ///< R + BᵀXB positive definite and everything finite
};

template <typename Scalar>
DareEvaluation<Scalar> evaluate_dare(const DynamicMatrix<Scalar>& X, const DynamicMatrix<Scalar>& A,
                                     const DynamicMatrix<Scalar>& B, const DynamicMatrix<Scalar>& Q,
                                     const DynamicMatrix<Scalar>& R) {
  using Square = DynamicMatrix<Scalar>;
  DareEvaluation<Scalar> e;
  const Square xa = X.lazyProduct(A);
  const Eigen::LLT<Square> s(R + B.transpose().lazyProduct(X).lazyProduct(B));
  if (s.info() != Eigen::Success) return e;
  const Square btxa = B.transpose().lazyProduct(xa);
  e.gain = s.solve(btxa);
  const Square ata = A.transpose().lazyProduct(xa);
  const Square correction = btxa.transpose().lazyProduct(e.gain);
  e.residual = symmetric_part<Scalar>(ata - correction + Q - X);
  const Scalar scale = X.norm() + ata.norm() + correction.norm() + Q.norm();
  const Scalar residual_norm = e.residual.norm();
  e.relative = scale > Scalar(0) ? residual_norm / scale : residual_norm;
  e.valid = X.allFinite() && std::isfinite(e.relative) && e.gain.allFinite();
  return e;
}

/// SDA (file comment, stage 2) on G = B R⁻¹ Bᵀ, H = Q: the limit of H_j, or
/// nothing when an iterate is not finite or the doubling does not settle.
template <typename Scalar>
std::optional<DynamicMatrix<Scalar>> structure_preserving_doubling(const DynamicMatrix<Scalar>& A,
                                                                   const DynamicMatrix<Scalar>& B,
                                                                   const DynamicMatrix<Scalar>& Q,
                                                                   const DynamicMatrix<Scalar>& R, int max_iterations,
                                                                   Scalar tolerance, int& iterations) {
  using Square = DynamicMatrix<Scalar>;
  const Index n = A.rows();
  const Square identity = Square::Identity(n, n);
  Square a = A;
  Square g = symmetric_part<Scalar>(B.lazyProduct(Eigen::LLT<Square>(R).solve(B.transpose())));
  Square h = Q;
  for (int j = 0; j < max_iterations; ++j) {
    const Eigen::PartialPivLU<Square> w(identity + g.lazyProduct(h));
    if (!has_regular_pivots(w)) return std::nullopt;
    const Square w_inv_a = w.solve(a);
    const Square w_inv_g = w.solve(g);
    const Square h_next = h + a.transpose().lazyProduct(h).lazyProduct(w_inv_a);
    const Square g_next = g + a.lazyProduct(w_inv_g).lazyProduct(a.transpose());
    a = a.lazyProduct(w_inv_a).eval();
    const Scalar change = (h_next - h).norm();
    h = symmetric_part(h_next);
    g = symmetric_part(g_next);
    ++iterations;
    if (!h.allFinite() || !g.allFinite() || !a.allFinite()) return std::nullopt;
    if (change <= tolerance * h.norm()) return h;
  }
  return std::nullopt;
}

/// A gain K with A − BK Schur, from the well-scaled DARE (A, B, I, ‖B‖²I), or
/// nothing when (A, B) is not stabilizable (or too close to it for the precision).
template <typename Scalar>
std::optional<DynamicMatrix<Scalar>> stabilizing_gain(const DynamicMatrix<Scalar>& A, const DynamicMatrix<Scalar>& B,
                                                      int max_iterations, Scalar tolerance, int& iterations) {
  const Index n = A.rows(), m = B.cols();
  const Scalar b2 = B.squaredNorm();
  const DynamicMatrix<Scalar> q = DynamicMatrix<Scalar>::Identity(n, n);
  const DynamicMatrix<Scalar> r = (b2 > Scalar(0) ? b2 : Scalar(1)) * DynamicMatrix<Scalar>::Identity(m, m);
  const auto x = structure_preserving_doubling<Scalar>(A, B, q, r, max_iterations, tolerance, iterations);
  if (!x) return std::nullopt;
  const auto e = evaluate_dare<Scalar>(*x, A, B, q, r);
  if (!e.valid || !is_schur_stable(DynamicMatrix<Scalar>(A - B.lazyProduct(e.gain)), stabilizability_margin<Scalar>))
    return std::nullopt;
  return e.gain;
}

}  // namespace detail

/// Per-term relative residual of X in the DARE (A, B, Q, R) on dynamic-size
/// matrices of fitting shapes (unchecked): \f$\|\mathcal R(X)\|_F /
/// (\|X\|_F + \|A^TXA\|_F + \|A^TXBK\|_F + \|Q\|_F)\f$ (see file comment); infinite when
/// \f$R + B^TXB\f$ is not positive definite (Cholesky, `Eigen::LLT`).
template <typename Scalar>
[[nodiscard]] Scalar dare_relative_residual(const detail::DynamicMatrix<Scalar>& X,
                                            const detail::DynamicMatrix<Scalar>& A,
                                            const detail::DynamicMatrix<Scalar>& B,
                                            const detail::DynamicMatrix<Scalar>& Q,
                                            const detail::DynamicMatrix<Scalar>& R) {
  const auto e = detail::evaluate_dare<Scalar>(X, A, B, Q, R);
  return e.valid ? e.relative : std::numeric_limits<Scalar>::infinity();
}

/// Stabilizing solution of the control-form DARE on dynamic-size matrices: the
/// design routine behind every `solve_dare`, one instance per scalar type
/// (compiled once for `double` in `adaptobs::precompiled`). The algorithm is
/// the file comment's: scaling by a power of two, the structure-preserving
/// doubling of Chu, Fan and Lin (2005) or, when it fails, Hewer's step from a
/// stabilizing gain, then Newton–Hewer refinement (Hewer 1971) with Stein steps
/// by Smith's doubling (design/stein.hpp). The factorizations are Eigen's: `LLT`
/// for \f$R + B^TXB\f$ and R, `PartialPivLU` for \f$I + G_jH_j\f$. `roles` gives the
/// names a refusal uses (the Kalman gain, which solves the dual equation, passes its own).
/// Throws `ConfigurationError` as the fixed-size `solve_dare` below.
template <typename Scalar>
[[nodiscard]] DareSolution<Scalar, Eigen::Dynamic> solve_dare(
    const detail::DynamicMatrix<Scalar>& A, const detail::DynamicMatrix<Scalar>& B,
    const detail::DynamicMatrix<Scalar>& Q, const detail::DynamicMatrix<Scalar>& R, DareOptions options = {},
    const detail::RiccatiRoles& roles = detail::control_dare_roles) {
  using Square = detail::DynamicMatrix<Scalar>;
  using namespace detail;
  validate_riccati_data(A, B, Q, R, roles);
  // Checked first: a bad limit would otherwise surface as a refusal of the data
  // (with no doubling step allowed no stabilizing gain is found, and the pair
  // would be called unstabilizable).
  require(options.max_iterations >= 1, roles.who, "options.max_iterations", "must be at least 1");
  require_non_negative(options.tolerance, roles.who, "options.tolerance");
  require_non_negative(options.residual_tolerance, roles.who, "options.residual_tolerance");
  require(options.stability_margin >= 0 && options.stability_margin < 1, roles.who, "options.stability_margin",
          "must lie in [0, 1) (0: the default)");
  DareSolution<Scalar, Eigen::Dynamic> result;
  if (A.rows() == 0) return result;

  constexpr Scalar eps = std::numeric_limits<Scalar>::epsilon();
  const Scalar sda_tolerance = options.tolerance > 0 ? Scalar(options.tolerance) : Scalar(100) * eps;
  const Scalar residual_tolerance =
      options.residual_tolerance > 0 ? Scalar(options.residual_tolerance) : std::max(Scalar(1e-10), Scalar(1000) * eps);
  const Scalar margin = options.stability_margin > 0 ? Scalar(options.stability_margin) : std::sqrt(eps);

  // Stage 1: X = σ X̃ with σ a power of two (design/riccati_support.hpp).
  const Scalar sigma = riccati_solution_scale<Scalar>(B, Q, R);
  const Square q = Q / sigma, r = R / sigma;

  auto stabilizing = [&](const Square& gain, Scalar radius_margin) {
    return is_schur_stable(Square(A - B.lazyProduct(gain)), radius_margin);
  };

  // Stage 2: a start whose closed loop is Schur.
  std::optional<Square> start =
      structure_preserving_doubling<Scalar>(A, B, q, r, options.max_iterations, sda_tolerance, result.iterations);
  bool stabilizable = false;  // proven by a gain that makes A − BK Schur
  if (start) {
    const auto e = evaluate_dare<Scalar>(*start, A, B, q, r);
    stabilizable = e.valid && stabilizing(e.gain, stabilizability_margin<Scalar>);
    if (!stabilizable) start.reset();
  }
  if (!start) {
    const auto k0 = stabilizing_gain<Scalar>(A, B, options.max_iterations, sda_tolerance, result.iterations);
    if (!k0) {
      // Not found within the caller's limit: the pair is unstabilizable only if
      // the default limit finds no gain either.
      int ignored = 0;
      if (options.max_iterations < DareOptions{}.max_iterations &&
          stabilizing_gain<Scalar>(A, B, DareOptions{}.max_iterations, sda_tolerance, ignored))
        fail_argument(roles.who, "options.max_iterations",
                      "is too small for the doubling to reach a stabilizing start (the default limit reaches one)");
      fail_not_stabilizable(roles);
    }
    stabilizable = true;
    const Square closed = A - B.lazyProduct(*k0);
    start = solve_stein_doubling<Scalar>(closed,
                                         symmetric_part<Scalar>(q + k0->transpose().lazyProduct(r).lazyProduct(*k0)));
  }

  // Stage 3: Newton steps while the residual decreases. No stop at a small
  // residual: near a marginal mode the steps converge only linearly, and the
  // closed loop reaches the circle's neighbourhood that the margin rejects.
  Square x = *start;
  auto e = evaluate_dare<Scalar>(x, A, B, q, r);
  for (int step = 0; step < 50 && e.valid; ++step) {
    const Square closed = A - B.lazyProduct(e.gain);
    if (!is_schur_stable(closed)) break;
    const Square candidate = symmetric_part<Scalar>(x + solve_stein_doubling<Scalar>(closed, e.residual));
    auto next = evaluate_dare<Scalar>(candidate, A, B, q, r);
    if (!(next.valid && next.relative < e.relative)) break;
    x = candidate;
    e = std::move(next);
    ++result.iterations;
  }
  if (e.valid && e.relative <= residual_tolerance && stabilizing(e.gain, margin)) {
    result.X = sigma * x;
    if (!result.X.allFinite()) fail_out_of_range(roles);
    result.relative_residual = e.relative;
    return result;
  }

  // Refusal: the first reason that can be established (with the default
  // doubling limit, whatever the caller's).
  int ignored = 0;
  const auto stabilizable_pair = [&](const Square& a, const Square& b) {
    return stabilizing_gain<Scalar>(a, b, DareOptions{}.max_iterations, Scalar(100) * eps, ignored).has_value();
  };
  if (!stabilizable && !stabilizable_pair(A, B)) fail_not_stabilizable(roles);
  // A mode unobserved by Q on the unit circle: (Aᵀ, Q) is not stabilizable,
  // but becomes so once A is shrunk by 1 + 1e-6, which moves the circle's
  // modes inside and leaves those further out where they were.
  const Square at = A.transpose();
  if (!stabilizable_pair(at, q) && stabilizable_pair(Square(at / Scalar(1 + 1e-6)), q)) fail_unreached_mode(roles);
  fail_ill_conditioned(
      roles, e.relative, residual_tolerance, "spectral radius",
      e.valid ? spectral_radius_bound(Square(A - B.lazyProduct(e.gain))) : std::numeric_limits<Scalar>::infinity(),
      Scalar(1) - margin);
}

/// Per-term relative residual of X in the DARE (A, B, Q, R) (see file comment
/// and the dynamic-size overload above). Throws `ConfigurationError` naming the
/// first argument whose shape does not fit A (n × n) and B (n × m).
template <class DX, class DA, class DB, class DQ, class DR>
[[nodiscard]] typename DX::Scalar dare_relative_residual(const Eigen::MatrixBase<DX>& X, const Eigen::MatrixBase<DA>& A,
                                                         const Eigen::MatrixBase<DB>& B, const Eigen::MatrixBase<DQ>& Q,
                                                         const Eigen::MatrixBase<DR>& R) {
  using detail::dynamic_copy;
  constexpr std::string_view who = "dare_relative_residual";
  require_square(A, who, "A");
  const Index n = A.rows(), m = B.cols();
  require_shape(B, n, m, who, "B");
  require_shape(X, n, n, who, "X");
  require_shape(Q, n, n, who, "Q");
  require_shape(R, m, m, who, "R");
  return dare_relative_residual(dynamic_copy(X), dynamic_copy(A), dynamic_copy(B), dynamic_copy(Q), dynamic_copy(R));
}

/// Stabilizing solution of the control-form DARE (see file comment), sized as
/// the caller's A; it runs the dynamic-size overload above.
/// Throws `ConfigurationError` on invalid arguments, and refuses, naming the
/// reason, when no stabilizing solution exists ((A, B) not stabilizable, or a
/// mode on the unit circle unobserved by Q) or when the working precision
/// cannot reach `options.residual_tolerance` with a closed-loop spectral radius
/// below 1 − `options.stability_margin`.
template <class DA, class DB, class DQ, class DR>
[[nodiscard]] auto solve_dare(const Eigen::MatrixBase<DA>& A, const Eigen::MatrixBase<DB>& B,
                              const Eigen::MatrixBase<DQ>& Q, const Eigen::MatrixBase<DR>& R,
                              DareOptions options = {}) {
  using detail::dynamic_copy;
  return detail::with_order<DA::RowsAtCompileTime>(
      solve_dare(dynamic_copy(A), dynamic_copy(B), dynamic_copy(Q), dynamic_copy(R), options));
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

/// The steady-state Kalman gain on dynamic-size matrices: P solves the dual
/// DARE \f$(A^T, C^T, Q, R)\f$ (`solve_dare` above) and
/// \f$K = A P C^T (C P C^T + R)^{-1}\f$, with the innovation covariance factored
/// by `Eigen::LLT`. Compiled once for `double` in `adaptobs::precompiled`.
template <typename Scalar>
[[nodiscard]] KalmanGain<Scalar, Eigen::Dynamic, Eigen::Dynamic> steady_state_kalman_gain(
    const detail::DynamicMatrix<Scalar>& A, const detail::DynamicMatrix<Scalar>& C,
    const detail::DynamicMatrix<Scalar>& Q, const detail::DynamicMatrix<Scalar>& R, DareOptions options = {}) {
  using Matrix = detail::DynamicMatrix<Scalar>;
  // The dual equation (Aᵀ, Cᵀ, Q, R): its stabilizability is the detectability
  // of (A, C), and its "unobserved by Q" is "not excited by the process noise".
  static constexpr detail::RiccatiRoles roles{
      "steady_state_kalman_gain", "C",
      "must be detectable: a mode of A on or outside the unit circle is not seen by C, so no gain makes A - KC Schur",
      "leave a mode of A on the unit circle unexcited by the process noise Q: the filter DARE has no stabilizing "
      "solution"};
  require_square(A, roles.who, "A");
  require_shape(C, C.rows(), A.cols(), roles.who, "C");
  const Matrix at = A.transpose();
  const Matrix ct = C.transpose();
  const auto dual = solve_dare(at, ct, Q, R, options, roles);
  KalmanGain<Scalar, Eigen::Dynamic, Eigen::Dynamic> result;
  result.P = dual.X;
  result.relative_residual = dual.relative_residual;
  // K = A P Cᵀ S⁻¹ with S = C P Cᵀ + R is unchanged when P and R are divided by
  // the same power of two, which keeps S in range when P and R are near the
  // largest number (P, already refused if it overflowed, may still be close).
  // An even power: the Cholesky factor then scales by a power of two as well,
  // and K comes out bit for bit as without the scaling.
  const Scalar largest = std::max(result.P.size() ? result.P.cwiseAbs().maxCoeff() : Scalar(0),
                                  R.size() ? R.cwiseAbs().maxCoeff() : Scalar(0));
  const Scalar scale = largest > Scalar(1) ? std::ldexp(Scalar(1), 2 * (std::ilogb(largest) / 2)) : Scalar(1);
  const Matrix p_scaled = result.P / scale;
  const Eigen::LLT<Matrix> s(detail::symmetric_part<Scalar>(C.lazyProduct(p_scaled).lazyProduct(ct) + R / scale));
  if (s.info() != Eigen::Success) detail::fail_out_of_range(roles);
  // Kᵀ = S⁻¹ C P Aᵀ (S and P symmetric).
  result.K = s.solve(C.lazyProduct(p_scaled).lazyProduct(at)).transpose();
  if (!result.K.allFinite()) detail::fail_out_of_range(roles);
  return result;
}

#ifdef ADAPTOBS_PRECOMPILED
ADAPTOBS_INSTANTIATE DareSolution<double, Eigen::Dynamic> solve_dare<double>(const detail::DynamicMatrix<double>&,
                                                                             const detail::DynamicMatrix<double>&,
                                                                             const detail::DynamicMatrix<double>&,
                                                                             const detail::DynamicMatrix<double>&,
                                                                             DareOptions, const detail::RiccatiRoles&);
ADAPTOBS_INSTANTIATE double dare_relative_residual<double>(const detail::DynamicMatrix<double>&,
                                                           const detail::DynamicMatrix<double>&,
                                                           const detail::DynamicMatrix<double>&,
                                                           const detail::DynamicMatrix<double>&,
                                                           const detail::DynamicMatrix<double>&);
ADAPTOBS_INSTANTIATE KalmanGain<double, Eigen::Dynamic, Eigen::Dynamic> steady_state_kalman_gain<double>(
    const detail::DynamicMatrix<double>&, const detail::DynamicMatrix<double>&, const detail::DynamicMatrix<double>&,
    const detail::DynamicMatrix<double>&, DareOptions);
#endif

/// \f$P\f$ solves the dual DARE \f$(A^T, C^T, Q, R)\f$ and
/// \f$K = A P C^T (C P C^T + R)^{-1}\f$, sized as the caller's A and C (the
/// dynamic-size overload above does the work).
template <class DA, class DC, class DQ, class DR>
[[nodiscard]] auto steady_state_kalman_gain(const Eigen::MatrixBase<DA>& A, const Eigen::MatrixBase<DC>& C,
                                            const Eigen::MatrixBase<DQ>& Q, const Eigen::MatrixBase<DR>& R,
                                            DareOptions options = {}) {
  using Scalar = typename DA::Scalar;
  using detail::dynamic_copy;
  const auto dynamic =
      steady_state_kalman_gain(dynamic_copy(A), dynamic_copy(C), dynamic_copy(Q), dynamic_copy(R), options);
  return KalmanGain<Scalar, DA::RowsAtCompileTime, DC::RowsAtCompileTime>{dynamic.K, dynamic.P,
                                                                          dynamic.relative_residual};
}

}  // namespace adaptobs
