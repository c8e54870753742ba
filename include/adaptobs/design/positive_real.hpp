#pragma once
/// \file
/// Strict positive realness of \f$G(s) = c(sI - A)^{-1}b\f$: an exact test, a
/// frequency sweep, a Kalman–Yakubovich–Popov certificate, and the design of a
/// gain k making \f$c(sI - A + kc)^{-1}\gamma\f$ SPR.
///
/// Algorithms 1 and 2 of Zhang (2005, §III-A, §III-B) converge when
/// \f$c_o(sI - A_o + kc_o)^{-1}\gamma\f$ is SPR: then (KYP lemma) some
/// \f$P = P^T > 0\f$ satisfies \f$\bar A^TP + P\bar A < 0\f$ and \f$P\gamma = c_o^T\f$ with
/// \f$\bar A = A_o - kc_o\f$, and \f$V = e^TPe + \tilde\theta^T\Gamma^{-1}\tilde\theta\f$
/// is a Lyapunov function of the observer errors.
///
/// **Exact test:** `spr_test.hpp`.
///
/// **Choosing k.** Output injection moves poles, never zeros:
/// \f$c(sI - A + kc)^{-1}\gamma = N_\gamma(s)/\det(sI - A + kc)\f$ with
/// \f$N_\gamma = c\,\mathrm{adj}(sI - A)\gamma\f$. So an SPR choice exists iff
/// \f$c\gamma > 0\f$ and \f$N_\gamma\f$ is Hurwitz; placing the poles at
/// \f$(s + \lambda)N_\gamma(s)/(c\gamma)\f$ gives \f$G = c\gamma/(s + \lambda)\f$, SPR for every λ > 0.

#include <adaptobs/core/detail/dynamic_copy.hpp>
#include <adaptobs/core/precompiled.hpp>
#include <adaptobs/core/symmetric_eigenvalues.hpp>
#include <adaptobs/core/validation.hpp>
#include <adaptobs/design/care.hpp>
#include <adaptobs/design/observability.hpp>
#include <adaptobs/design/polynomial.hpp>
#include <adaptobs/design/spr_test.hpp>
#include <adaptobs/design/stability.hpp>

#include <Eigen/Core>
#include <Eigen/LU>
#include <Eigen/QR>

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <optional>
#include <string_view>

namespace adaptobs {

/// Frequency-sweep cross-check of strict positive realness.
template <typename Scalar>
struct SprSweep {
  bool strictly_positive_real = false;
  bool hurwitz = false;
  Scalar min_weighted_real_part = 0;  ///< \f$\min_\omega (1 + \omega^2)\,\mathrm{Re}\,G(j\omega)\f$ over the grid
  Scalar at_frequency = 0;            ///< ω of that minimum
  Scalar high_frequency_limit = 0;    ///< \f$\lim \omega^2\mathrm{Re}\,G(j\omega) = -cAb\f$
  explicit operator bool() const noexcept { return strictly_positive_real; }
};

/// A Kalman–Yakubovich–Popov certificate of \f$c(sI - A)^{-1}b\f$ being SPR:
/// \f$P = P^T > 0\f$ with \f$A^TP + PA < 0\f$ and \f$Pb = c^T\f$, and its residuals.
template <typename Scalar, int N>
struct KypCertificate {
  Eigen::Matrix<Scalar, N, N> P;
  Scalar equality_residual = 0;        ///< \f$\|Pb - c^T\|_\infty\f$
  Scalar min_eigenvalue_P = 0;         ///< \f$\lambda_{\min}(P)\f$ (> 0)
  Scalar max_eigenvalue_lyapunov = 0;  ///< \f$\lambda_{\max}(A^TP + PA)\f$ (< 0)
};

/// The frequency sweep of `spr_frequency_sweep` on run-time sizes:
/// \f$(1 + \omega^2)\,\mathrm{Re}\,G(j\omega)\f$ with \f$G(j\omega) = c(j\omega I - A)^{-1}b\f$
/// (an LU solve per frequency) at ω = 0 and on `points` logarithmically spaced
/// frequencies of [omega_min, omega_max]; strictly positive real when A is
/// Hurwitz, the minimum is positive and \f$-cAb\f$ exceeds \f$10^{-9}\f$ times
/// the scales of A, b and c. One instance per scalar type (compiled once in
/// `adaptobs::precompiled`). Refuses (naming `spr_frequency_sweep`) a triple
/// that is not SISO or not finite, and a grid without
/// 0 < omega_min < omega_max < ∞ and points ≥ 2.
template <typename Scalar>
[[nodiscard]] SprSweep<Scalar> spr_frequency_sweep_dynamic(const Eigen::MatrixX<Scalar>& A,
                                                           const Eigen::MatrixX<Scalar>& b,
                                                           const Eigen::MatrixX<Scalar>& c, Scalar omega_min = 1e-4,
                                                           Scalar omega_max = 1e4, int points = 2001) {
  using Complex = std::complex<Scalar>;
  using ComplexMatrix = Eigen::Matrix<Complex, Eigen::Dynamic, Eigen::Dynamic>;
  constexpr std::string_view who = "spr_frequency_sweep";
  const Index n = detail::require_siso_triple(A, b, c, who);
  require(omega_min > 0 && omega_max > omega_min && std::isfinite(omega_max) && points >= 2, who,
          "omega_min, omega_max, points", "must satisfy 0 < omega_min < omega_max < ∞ and points ≥ 2");
  SprSweep<Scalar> r;
  if (n == 0) {  // G = 0: not strictly positive real; an empty A has no unstable mode
    r.hurwitz = true;
    return r;
  }
  r.hurwitz = is_hurwitz_stable(A);
  r.high_frequency_limit = -(c * A * b)(0, 0);
  const ComplexMatrix a = A.template cast<Complex>();
  const ComplexMatrix bb = b.template cast<Complex>();
  const ComplexMatrix cc = c.template cast<Complex>();
  r.min_weighted_real_part = std::numeric_limits<Scalar>::infinity();
  for (int i = -1; i < points; ++i) {
    const Scalar w = i < 0 ? Scalar(0) : omega_min * std::pow(omega_max / omega_min, Scalar(i) / Scalar(points - 1));
    const ComplexMatrix m = Complex(0, w) * ComplexMatrix::Identity(n, n) - a;
    const Complex g = (cc * m.partialPivLu().solve(bb))(0, 0);
    const Scalar weighted = (Scalar(1) + w * w) * g.real();
    // A NaN (jω an eigenvalue of A within rounding) becomes the minimum and
    // fails the test below, instead of being skipped by the comparison.
    if (!(weighted >= r.min_weighted_real_part)) {
      r.min_weighted_real_part = weighted;
      r.at_frequency = w;
    }
  }
  const Scalar tol = Scalar(1e-9) * std::max(Scalar(1), A.cwiseAbs().maxCoeff()) *
                     std::max(Scalar(1), b.cwiseAbs().maxCoeff()) * std::max(Scalar(1), c.cwiseAbs().maxCoeff());
  r.strictly_positive_real = r.hurwitz && r.min_weighted_real_part > 0 && r.high_frequency_limit > tol;
  return r;
}

/// The residuals of a candidate KYP certificate P of \f$c(sI - A)^{-1}b\f$ on
/// run-time sizes: \f$\|Pb - c^T\|_\infty\f$, \f$\lambda_{\min}\f$ of the
/// symmetric part of P and \f$\lambda_{\max}\f$ of that of \f$A^TP + PA\f$
/// (`symmetric_eigenvalues`). Refuses (naming `kyp_residuals`) sizes that do
/// not fit P (n × n), A (n × n), b (n × 1) and c (1 × n).
template <typename Scalar>
[[nodiscard]] KypCertificate<Scalar, Eigen::Dynamic> kyp_residuals_dynamic(const Eigen::MatrixX<Scalar>& P,
                                                                           const Eigen::MatrixX<Scalar>& A,
                                                                           const Eigen::MatrixX<Scalar>& b,
                                                                           const Eigen::MatrixX<Scalar>& c) {
  using Matrix = Eigen::MatrixX<Scalar>;
  constexpr std::string_view who = "kyp_residuals";
  require_square(P, who, "P");
  const Index n = P.rows();
  require_shape(A, n, n, who, "A");
  require_shape(b, n, 1, who, "b");
  require_shape(c, 1, n, who, "c");
  KypCertificate<Scalar, Eigen::Dynamic> k;
  k.P = P;
  k.equality_residual = (P * b - c.transpose()).cwiseAbs().template maxCoeff<Eigen::PropagateNaN>();
  const Matrix lyap = A.transpose() * P + P * A;
  k.min_eigenvalue_P = symmetric_eigenvalues(Matrix(0.5 * (P + P.transpose())))(0);
  k.max_eigenvalue_lyapunov = symmetric_eigenvalues(Matrix(0.5 * (lyap + lyap.transpose())))(P.rows() - 1);
  return k;
}

/// The KYP certificate of `kyp_certificate` on run-time sizes, or nothing
/// when \f$c(sI - A)^{-1}b\f$ is not SPR (or no certificate is found): the
/// construction by a Riccati equation solved from its Hamiltonian
/// (`solve_riccati_hamiltonian`) described there, verified by
/// `kyp_residuals_dynamic`. One instance per scalar type (compiled once in
/// `adaptobs::precompiled`). Refuses (naming `kyp_certificate`) a triple
/// that is not SISO or not finite.
template <typename Scalar>
[[nodiscard]] std::optional<KypCertificate<Scalar, Eigen::Dynamic>> kyp_certificate_dynamic(
    const Eigen::MatrixX<Scalar>& A, const Eigen::MatrixX<Scalar>& b, const Eigen::MatrixX<Scalar>& c) {
  using Matrix = Eigen::MatrixX<Scalar>;
  using Vector = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;
  constexpr std::string_view who = "kyp_certificate";
  const Index n = detail::require_siso_triple(A, b, c, who);
  const Scalar cb = (c * b)(0, 0);
  if (!(cb > 0)) return std::nullopt;

  // T_n = [c; N⊥]: the rows of N⊥ span the orthogonal complement of b.
  const Vector bv = b;
  const Eigen::HouseholderQR<Matrix> qr{Matrix(bv)};
  const Matrix basis = qr.householderQ() * Matrix::Identity(n, n);
  Matrix tn(n, n);
  tn.row(0) = c;
  tn.bottomRows(n - 1) = basis.rightCols(n - 1).transpose();
  const Eigen::FullPivLU<Matrix> tn_lu(tn);
  if (!tn_lu.isInvertible()) return std::nullopt;
  const Matrix tn_inv = tn_lu.inverse();
  const Matrix ap = tn * A * tn_inv;
  const Scalar a = ap(0, 0);
  const Scalar a_scale = std::max(Scalar(1), ap.cwiseAbs().maxCoeff());
  if (!(a < -Scalar(1e-9) * a_scale)) return std::nullopt;

  const Scalar p11 = Scalar(1) / cb;
  Matrix p_prime = Matrix::Zero(n, n);
  p_prime(0, 0) = p11;
  const Scalar p_norm_tol = Scalar(1e-9);
  const auto verified = [&](const Matrix& pp) -> std::optional<KypCertificate<Scalar, Eigen::Dynamic>> {
    const Matrix p_dynamic = tn.transpose() * pp * tn;
    const Matrix p = Scalar(0.5) * (p_dynamic + p_dynamic.transpose());
    auto k = kyp_residuals_dynamic<Scalar>(p, A, b, c);
    const Scalar margin = p_norm_tol * p.norm() * std::max(Scalar(1), A.norm());
    if (k.equality_residual <= Scalar(1e-10) * std::max(Scalar(1), c.cwiseAbs().maxCoeff()) && k.min_eigenvalue_P > 0 &&
        k.max_eigenvalue_lyapunov < -margin)
      return k;
    return std::nullopt;
  };
  if (n == 1) return verified(p_prime);

  const Vector q = ap.row(0).tail(n - 1).transpose();
  const Vector r = ap.col(0).tail(n - 1);
  const Matrix a0 = ap.bottomRightCorner(n - 1, n - 1);
  const Scalar delta = -Scalar(2) * a * p11;
  const Matrix a_tilde = a0 + r * q.transpose() / (Scalar(2) * std::abs(a));
  const Matrix r_quad = r * r.transpose() / delta;
  Scalar eps = 1;
  for (int attempt = 0; attempt < 40; ++attempt, eps /= 2) {
    const Matrix q_quad = (p11 * p11 / delta) * q * q.transpose() + eps * Matrix::Identity(n - 1, n - 1);
    if (!q_quad.allFinite() || !r_quad.allFinite()) return std::nullopt;  // c b or a beyond the range: no certificate
    // Ãᵀ X + X Ã − X(−R)X + Q = 0.
    const auto x = solve_riccati_hamiltonian(a_tilde, Matrix(-r_quad), q_quad);
    if (!x) continue;
    p_prime.bottomRightCorner(n - 1, n - 1) = x->X;
    if (auto k = verified(p_prime)) return k;
  }
  return std::nullopt;
}

#ifdef ADAPTOBS_PRECOMPILED
ADAPTOBS_INSTANTIATE SprSweep<double> spr_frequency_sweep_dynamic<double>(const Eigen::MatrixXd&,
                                                                          const Eigen::MatrixXd&,
                                                                          const Eigen::MatrixXd&, double, double, int);
ADAPTOBS_INSTANTIATE KypCertificate<double, Eigen::Dynamic> kyp_residuals_dynamic<double>(const Eigen::MatrixXd&,
                                                                                          const Eigen::MatrixXd&,
                                                                                          const Eigen::MatrixXd&,
                                                                                          const Eigen::MatrixXd&);
ADAPTOBS_INSTANTIATE std::optional<KypCertificate<double, Eigen::Dynamic>> kyp_certificate_dynamic<double>(
    const Eigen::MatrixXd&, const Eigen::MatrixXd&, const Eigen::MatrixXd&);
#endif

namespace detail {
/// The certificate with P of `N` rows.
template <int N, typename Scalar>
[[nodiscard]] KypCertificate<Scalar, N> sized_certificate(const KypCertificate<Scalar, Eigen::Dynamic>& k) {
  return {Eigen::Matrix<Scalar, N, N>(k.P), k.equality_residual, k.min_eigenvalue_P, k.max_eigenvalue_lyapunov};
}

}  // namespace detail

/// Samples \f$(1 + \omega^2)\,\mathrm{Re}\,G(j\omega)\f$ at ω = 0 and on a
/// logarithmic grid of [omega_min, omega_max]; requires it positive, A Hurwitz
/// and \f$-cAb > 0\f$. (Weighting by \f$1 + \omega^2\f$ keeps the test from
/// reading round-off as a sign where \f$\mathrm{Re}\,G\f$ decays like \f$\omega^{-2}\f$.)
template <class DA, class DB, class DC>
[[nodiscard]] SprSweep<typename DA::Scalar> spr_frequency_sweep(
    const Eigen::MatrixBase<DA>& A, const Eigen::MatrixBase<DB>& b, const Eigen::MatrixBase<DC>& c,
    typename DA::Scalar omega_min = 1e-4, typename DA::Scalar omega_max = 1e4, int points = 2001) {
  return spr_frequency_sweep_dynamic<typename DA::Scalar>(detail::dynamic_copy(A), detail::dynamic_copy(b),
                                                          detail::dynamic_copy(c), omega_min, omega_max, points);
}

/// Residuals of a candidate certificate P.
template <class DP, class DA, class DB, class DC>
[[nodiscard]] KypCertificate<typename DP::Scalar, DP::RowsAtCompileTime> kyp_residuals(const Eigen::MatrixBase<DP>& P,
                                                                                       const Eigen::MatrixBase<DA>& A,
                                                                                       const Eigen::MatrixBase<DB>& b,
                                                                                       const Eigen::MatrixBase<DC>& c) {
  return detail::sized_certificate<DP::RowsAtCompileTime>(kyp_residuals_dynamic<typename DP::Scalar>(
      detail::dynamic_copy(P), detail::dynamic_copy(A), detail::dynamic_copy(b), detail::dynamic_copy(c)));
}

/// KYP certificate of an SPR \f$c(sI - A)^{-1}b\f$, found without an SDP solver,
/// or nothing when G is not SPR.
///
/// In coordinates \f$x' = T_nx\f$, \f$T_n = [c; N_\perp]\f$ with \f$N_\perp b = 0\f$:
/// \f$A' = \begin{bmatrix} a & q^T\\ r & A_0\end{bmatrix}\f$, \f$b' = (cb, 0)\f$, \f$c' = e_1^T\f$;
/// \f$Pb = c^T\f$ forces \f$P' = \mathrm{diag}(1/cb, X)\f$, and (Schur complement on
/// the (1,1) entry, which needs cb > 0 and a < 0) \f$A'^TP' + P'A' = -\mathrm{diag}(\cdot, \varepsilon I)\f$ becomes
/// \f[ \tilde A^TX + X\tilde A + X\frac{rr^T}{\delta}X + \frac{qq^T}{(cb)^2\delta} + \varepsilon I = 0,\quad
///     \delta = \frac{-2a}{cb},\ \tilde A = A_0 + \frac{rq^T}{2|a|}, \f]
/// solved from its Hamiltonian (ε = 1, halved on failure). The returned P is
/// verified: \f$\|Pb - c^T\| \le 10^{-10}\|c\|\f$, \f$P > 0\f$ and
/// \f$\lambda_{\max}(A^TP + PA) < -10^{-9}\|P\|\|A\|\f$ (a margin, so that a
/// borderline function is not certified by round-off).
template <class DA, class DB, class DC>
[[nodiscard]] std::optional<KypCertificate<typename DA::Scalar, DA::RowsAtCompileTime>> kyp_certificate(
    const Eigen::MatrixBase<DA>& A, const Eigen::MatrixBase<DB>& b, const Eigen::MatrixBase<DC>& c) {
  const auto k = kyp_certificate_dynamic<typename DA::Scalar>(detail::dynamic_copy(A), detail::dynamic_copy(b),
                                                              detail::dynamic_copy(c));
  if (!k) return std::nullopt;
  return detail::sized_certificate<DA::RowsAtCompileTime>(*k);
}

/// Output-injection gain k with \f$\det(sI - A + kc) = p(s)\f$ (observer form of
/// Ackermann's formula, \f$k = p(A)\,\mathcal O^{-1}e_n\f$). Throws when (A, c)
/// is not observable, p is not monic of degree n, or any of them is not finite.
/// Observability is decided by the staircase (`observability`), whose verdict
/// does not depend on the units of the output or of time: a rank test on
/// \f$\mathcal O\f$ itself, whose rows grow like the powers of A, refused
/// observable pairs with graded dynamics. \f$\mathcal O\f$ is still what the
/// formula solves with; an observable pair whose \f$\mathcal O\f$ is singular to
/// working accuracy is refused as too ill-conditioned for the formula.
template <class DA, class DC>
[[nodiscard]] Eigen::Matrix<typename DA::Scalar, DA::RowsAtCompileTime, 1> ackermann_observer_gain(
    const Eigen::MatrixBase<DA>& A, const Eigen::MatrixBase<DC>& c, const Polynomial<typename DA::Scalar>& p) {
  using Scalar = typename DA::Scalar;
  constexpr std::string_view who = "ackermann_observer_gain";
  const Index n = detail::require_single_output_pair(A, c, who);
  require(p.size() == n + 1 && p(0) == Scalar(1), who, "p", "must be monic of degree n");
  require_finite(p, who, "p");
  if (n == 0) return Eigen::Matrix<Scalar, DA::RowsAtCompileTime, 1>(0);
  require(observability(A, c).observable(), who, "A, c", "must be an observable pair");
  const Eigen::FullPivLU<Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>> lu(observability_matrix(A, c));
  require(lu.rank() == n, who, "A, c",
          "is too ill-conditioned for Ackermann's formula: its observability matrix is singular to working "
          "accuracy");
  Eigen::Matrix<Scalar, Eigen::Dynamic, 1> en = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>::Zero(n);
  en(n - 1) = Scalar(1);
  return evaluate_polynomial(p, A) * lu.solve(en);
}

/// Output-injection gain k making \f$c(sI - A + kc)^{-1}\gamma = c\gamma/(s + \lambda)\f$
/// (SPR): the poles are placed at \f$(s + \lambda)N_\gamma(s)/(c\gamma)\f$, cancelling the zeros.
/// Throws when \f$c\gamma \le 0\f$ or \f$N_\gamma\f$ is not Hurwitz (then no k makes
/// the function SPR), when λ ≤ 0, when (A, c) is not observable, or when A, c or
/// γ is not finite.
template <class DA, class DC, class DG>
[[nodiscard]] Eigen::Matrix<typename DA::Scalar, DA::RowsAtCompileTime, 1> spr_injection_gain(
    const Eigen::MatrixBase<DA>& A, const Eigen::MatrixBase<DC>& c, const Eigen::MatrixBase<DG>& gamma,
    typename DA::Scalar lambda) {
  using Scalar = typename DA::Scalar;
  constexpr std::string_view who = "spr_injection_gain";
  const Index n = detail::require_single_output_pair(A, c, who);
  require_finite_shape(gamma, n, 1, who, "gamma");
  require_positive(lambda, who, "lambda");
  const auto g = transfer_function(A, gamma, c);
  const Scalar cg = (c * gamma)(0, 0);
  require(cg > 0, who, "gamma", "must satisfy c gamma > 0 (relative degree one, positive gain)");
  const Polynomial<Scalar> zeros = g.numerator / cg;  // monic, degree n − 1 since cγ = N's leading coefficient
  require(n == 1 || is_hurwitz_polynomial(zeros), who, "gamma",
          "gives a numerator c adj(sI - A) gamma that is not Hurwitz: no gain makes the function SPR");
  Polynomial<Scalar> pole(2);
  pole << Scalar(1), lambda;
  const Polynomial<Scalar> target = multiply_polynomials<Scalar>(pole, zeros);
  return ackermann_observer_gain(A, c, target);
}

}  // namespace adaptobs
