#pragma once
/// \file
/// Exponential stability of periodic linear time-varying systems \f$\dot e = A(t)e\f$.
///
/// Frozen-time eigenvalues say nothing about a time-varying system (the
/// Markus–Yamabe matrix has eigenvalues \f$-\tfrac14 \pm 0.66i\f$ at every t and
/// still grows like \f$e^{t/2}\f$). For a T-periodic A(t) the exact test is
/// Floquet's: the monodromy matrix \f$M = \Phi(T, 0)\f$ (transition over one
/// period) has eigenvalues \f$\mu_i\f$, the Floquet exponents are
/// \f$\log|\mu_i|/T\f$, and the system is exponentially stable iff all are negative.
/// Used for the conditions of Algorithm 3 (\f$\dot e_2 = A_{22}(t)e_2\f$) and
/// Algorithm 4 (\f$\dot{\tilde z} = (A(t) - K(t)C(t))\tilde z\f$, eq. (13)) of Zhang (2005).

#include <adaptobs/core/detail/dynamic_copy.hpp>
#include <adaptobs/core/runge_kutta.hpp>
#include <adaptobs/core/validation.hpp>
#include <adaptobs/design/dense_eigenvalues.hpp>

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <concepts>
#include <functional>
#include <limits>
#include <sstream>
#include <string_view>

namespace adaptobs {

namespace detail {

/// A(t) checked as the integrations need it: an n x n matrix (n the order of
/// A(t0)) of finite numbers, or the routine `who` refuses naming 'A' and the
/// time. `norm_seen` is raised to \f$\|A(t)\|_\infty\f$.
template <typename Scalar>
void check_dynamics_value(const Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>& a, Scalar t, Index n,
                          std::string_view who, Scalar& norm_seen) {
  if (a.rows() != n || a.cols() != n) {
    std::ostringstream os;
    os << "must return a matrix of A(t0)'s shape " << n << "x" << n << " at every t (got " << a.rows() << "x"
       << a.cols() << " at t = " << t << ")";
    fail_argument(who, "A", os.str());
  }
  if (!a.allFinite()) {
    std::ostringstream os;
    os << "must contain only finite numbers at every t (not at t = " << t << ")";
    fail_argument(who, "A", os.str());
  }
  norm_seen = std::max(norm_seen, a.cwiseAbs().rowwise().sum().maxCoeff());
}

/// A(t), checked by `check_dynamics_value`.
template <class AFn, typename Scalar>
Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic> checked_dynamics(const AFn& A, Scalar t, Index n,
                                                                       std::string_view who, Scalar& norm_seen) {
  Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic> a = A(t);
  check_dynamics_value(a, t, n, who, norm_seen);
  return a;
}

/// The transition matrix of \f$\dot e = A(t)e\f$ of order n from t0 to t1 by
/// `steps` RK4 steps, each evaluation of A(t) (the first at t0) checked by
/// `checked_dynamics`.
template <class AFn, typename Scalar>
Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic> checked_transition(const AFn& A, Scalar t0, Scalar t1, int steps,
                                                                         Index n, std::string_view who,
                                                                         Scalar& norm_seen) {
  using Matrix = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;
  Matrix phi = Matrix::Identity(n, n);
  RungeKutta4<Matrix> rk4(phi);
  rk4.integrate(
      [&](const Matrix& x, Matrix& dx, Scalar t) { dx.noalias() = checked_dynamics(A, t, n, who, norm_seen) * x; }, phi,
      t0, t1, steps);
  return phi;
}

/// Floquet exponents \f$\log|\mu_i|/T\f$ of a monodromy matrix, largest first;
/// all NaN when it is not finite.
template <typename Scalar>
Eigen::Matrix<Scalar, Eigen::Dynamic, 1> exponents_of_monodromy(
    const Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>& m, Scalar period) {
  using Vector = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;
  if (!m.allFinite()) return Vector::Constant(m.rows(), std::numeric_limits<Scalar>::quiet_NaN());
  Vector exponents = dense_eigenvalues(dynamic_copy(m)).cwiseAbs().array().log() / period;
  std::sort(exponents.begin(), exponents.end(), std::greater<>());
  return exponents;
}

/// Largest step size times \f$\max_t\|A(t)\|\f$ of the first RK4 pass.
inline constexpr double floquet_first_step_scale = 0.1;
/// Step doublings tried after the first pass before the exponents are refused.
inline constexpr int floquet_max_doublings = 6;
/// Most RK4 steps over one period.
inline constexpr int floquet_max_steps = 1 << 22;
/// The tolerance: this fraction of \f$\max(\max_t\|A(t)\|_\infty, 1/T)\f$.
inline constexpr double floquet_relative_tolerance = 1e-6;

/// The period and the step count of a Floquet computation.
template <typename Scalar>
void require_floquet_arguments(Scalar period, int steps, std::string_view who) {
  require_positive(period, who, "period");
  require(steps >= 1 && steps <= floquet_max_steps / 2, who, "steps", "must be between 1 and 2^21");
}

/// The Floquet exponents, error-controlled by step doubling. `count` leading
/// exponents (largest first) must agree between N and 2N steps within the
/// tolerance; the others are returned as computed. See `floquet_exponents`.
template <class AFn, typename Scalar>
Eigen::Matrix<Scalar, Eigen::Dynamic, 1> controlled_floquet_exponents(const AFn& A, Scalar period, int steps, Index n,
                                                                      Index count, std::string_view who) {
  using Vector = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;
  // max_t ||A(t)|| from a uniform sample of the period; the RK4 passes raise it
  // with every evaluation they make.
  Scalar norm = 0;
  const int samples = std::max(steps, 256);
  for (int k = 0; k < samples; ++k) (void)checked_dynamics(A, period * Scalar(k) / Scalar(samples), n, who, norm);
  const Scalar wanted = std::ceil(period * norm / Scalar(floquet_first_step_scale));
  if (!(wanted <= Scalar(floquet_max_steps / 2))) {  // the first doubling takes twice as many
    std::ostringstream os;
    os << "varies too fast for its period: period * max ||A(t)|| = " << period * norm << " needs more than "
       << floquet_max_steps << " RK4 steps for the stated accuracy";
    fail_argument(who, "A", os.str());
  }
  int n_steps = std::max(steps, static_cast<int>(wanted));
  Vector coarse = exponents_of_monodromy(checked_transition(A, Scalar(0), period, n_steps, n, who, norm), period);
  for (int doubling = 0;; ++doubling) {
    if (n_steps > floquet_max_steps / 2) {
      std::ostringstream os;
      os << "varies too fast for its period: the Floquet exponents need more than " << floquet_max_steps
         << " RK4 steps";
      fail_argument(who, "A", os.str());
    }
    Vector fine = exponents_of_monodromy(checked_transition(A, Scalar(0), period, 2 * n_steps, n, who, norm), period);
    // A solution beyond the floating-point range: no exponent can be told.
    if (coarse.array().isNaN().any() || fine.array().isNaN().any()) return fine;
    // A largest multiplier in the subnormal range has lost its relative
    // precision: its exponent is below log(DBL_MIN / eps) / T and no exponent can be told.
    const Scalar smallest_resolved =
        std::log(std::numeric_limits<Scalar>::min() / std::numeric_limits<Scalar>::epsilon()) / period;
    if (!(fine(0) >= smallest_resolved)) {
      std::ostringstream os;
      os << "contracts solutions beyond the floating-point range over one period: its largest Floquet exponent "
         << "is below log(" << std::numeric_limits<Scalar>::min() << " / eps) / period = " << smallest_resolved
         << " (the multiplier underflows) and cannot be told";
      fail_argument(who, "A", os.str());
    }
    const Scalar tolerance = Scalar(floquet_relative_tolerance) * std::max(norm, Scalar(1) / period);
    // The others are computed to about n·eps·|μ_max| in general: a multiplier
    // below that may be rounding noise. Its exponent is kept when both passes
    // agree on it (a triangular monodromy matrix has its multipliers exactly on
    // the diagonal), and reported as the bound log(n·eps·|μ_max|)/T otherwise
    // (the true exponent lies at or below it).
    const Scalar bound = fine(0) + std::log(Scalar(n) * std::numeric_limits<Scalar>::epsilon()) / period;
    for (Index i = 1; i < fine.size(); ++i) {
      const bool agreed =
          std::isfinite(fine(i)) && std::isfinite(coarse(i)) && std::abs(fine(i) - coarse(i)) <= tolerance;
      if (!(fine(i) >= bound) && !agreed) fine(i) = coarse(i) = bound;
    }
    std::sort(fine.begin(), fine.end(), std::greater<>());
    std::sort(coarse.begin(), coarse.end(), std::greater<>());
    Index worst = 0;
    const Scalar difference = (fine - coarse).head(count).cwiseAbs().maxCoeff(&worst);
    if (difference <= tolerance) return fine;
    if (doubling + 1 >= floquet_max_doublings) {
      std::ostringstream os;
      os << "gives Floquet exponents that do not settle under step doubling: exponent " << (worst + 1) << " reads "
         << coarse(worst) << " with " << n_steps << " RK4 steps and " << fine(worst) << " with " << 2 * n_steps
         << " (tolerance " << tolerance
         << "); a multiplier within rounding of the largest one, or an A(t) discontinuous within the period, "
            "cannot be resolved";
      fail_argument(who, "A", os.str());
    }
    coarse = fine;
    n_steps *= 2;
  }
}

}  // namespace detail

/// Transition matrix \f$\Phi(t_1, t_0)\f$ of \f$\dot e = A(t)e\f$ by RK4 with `steps` equal steps.
///
/// A fixed-step integration without an error estimate: its global error is
/// \f$O(h^4)\f$ with \f$h = (t_1 - t_0)/\text{steps}\f$ and is small only when
/// \f$h \max_t\|A(t)\| \ll 1\f$ (for the error-controlled monodromy matrix use
/// `floquet_exponents`). A(t) must return a finite square matrix of A(t0)'s
/// shape at every time the integration evaluates it; otherwise
/// `ConfigurationError` naming 'A' and the time.
template <class AFn, typename Scalar = double>
[[nodiscard]] Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic> transition_matrix(const AFn& A, Scalar t0,
                                                                                      Scalar t1, int steps = 2000) {
  require(std::isfinite(t0) && std::isfinite(t1), "transition_matrix", "t0, t1", "must be finite");
  require(steps >= 1, "transition_matrix", "steps", "must be at least 1");
  const Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic> a0 = A(t0);  // its order; RK4 checks every value
  require_square(a0, "transition_matrix", "A");
  Scalar norm_seen = 0;
  return detail::checked_transition(A, t0, t1, steps, a0.rows(), "transition_matrix", norm_seen);
}

/// Floquet exponents \f$\log|\mu_i|/T\f$ of a `period`-periodic \f$\dot e = A(t)e\f$, largest first.
///
/// Accuracy. The monodromy matrix \f$M = \Phi(T, 0)\f$ is integrated by RK4,
/// whose global error is \f$O(h^4)\f$ but which is accurate only when
/// \f$h\|A\|\f$ is small: on an oscillatory mode \f$z = i\omega h\f$ its growth
/// factor is \f$|R(z)| = 1 - (\omega h)^6/144 + O(h^8)\f$, an artificial
/// damping that can flip the sign of a small exponent, and on a stiff mode
/// \f$|R(z)| > 1\f$ once \f$z < -2.78\f$. The first pass takes
/// \f$N = \max(\text{steps}, \lceil 10\,T \max_t\|A(t)\|_\infty\rceil)\f$ steps
/// (\f$h\|A\| \le 0.1\f$, the maximum taken over a sample of the period and every
/// evaluation), and the exponents are recomputed with 2N, 4N, ... steps
/// (step doubling) until two successive passes agree within
/// \f[ \tau = 10^{-6} \max\bigl(\max_t\|A(t)\|_\infty,\ 1/T\bigr) \f]
/// for every exponent. The finer pass is returned; as RK4's error falls 16-fold
/// per doubling, its error is about \f$|\lambda_N - \lambda_{2N}|/15 \le \tau/15\f$
/// (asymptotically in h). Since \f$|\lambda_i| \le \max_t\|A(t)\|\f$, τ is a
/// relative accuracy of \f$10^{-6}\f$ on the scale of the system's fastest rate.
///
/// Refusals (`ConfigurationError` naming 'A'): A(t) not square, of another
/// shape than A(0), or not finite at a time evaluated; more than \f$2^{22}\f$
/// steps needed; exponents that do not agree within τ after six doublings (an
/// exponent whose multiplier is within rounding of another, or an A(t)
/// discontinuous within the period); a largest exponent whose multiplier
/// underflows, i.e. below \f$\log(\text{DBL\_MIN}/\varepsilon)/T\f$ (every
/// mode contracting beyond the floating-point range over one period).
///
/// Resolution. The multipliers are computed to about \f$n\varepsilon|\mu_{\max}|\f$
/// in general: an exponent below \f$\lambda_{\max} + \log(n\varepsilon)/T\f$ (a fast
/// stable mode beside a slow one, e.g. −50 beside −1 over T = 1) is kept when
/// two passes agree on it within τ (a triangular A(t) has its multipliers
/// exactly on the diagonal), and otherwise reported as that bound, which the
/// true exponent does not exceed.
///
/// All NaN when the monodromy matrix is not finite: the solution left the
/// floating-point range within one period and no exponent can be told;
/// `is_exponentially_stable_periodic` is then false.
template <class AFn, typename Scalar = double>
[[nodiscard]] Eigen::Matrix<Scalar, Eigen::Dynamic, 1> floquet_exponents(const AFn& A, Scalar period,
                                                                         int steps = 2000) {
  const Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic> a0 = A(Scalar(0));
  require_square(a0, "floquet_exponents", "A");
  detail::require_floquet_arguments(period, steps, "floquet_exponents");
  if (a0.rows() == 0) return Eigen::Matrix<Scalar, Eigen::Dynamic, 1>();
  return detail::controlled_floquet_exponents(A, period, steps, a0.rows(), a0.rows(), "floquet_exponents");
}

/// Exponential stability of a periodic \f$\dot e = A(t)e\f$: every Floquet exponent below −margin
/// (false when they are NaN: the solution left the floating-point range).
///
/// Only the largest exponent decides, so only it is error-controlled (as in
/// `floquet_exponents`, within τ); the answer is certain when it lies farther
/// than τ from −margin. Refusals as in `floquet_exponents`, for the largest
/// exponent: a largest multiplier that underflows (every mode contracting
/// beyond the floating-point range over one period) is refused, not guessed.
template <class AFn, typename Scalar = double>
[[nodiscard]] bool is_exponentially_stable_periodic(const AFn& A, Scalar period, Scalar margin = 0, int steps = 2000) {
  const Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic> a0 = A(Scalar(0));
  require_square(a0, "is_exponentially_stable_periodic", "A");
  require(std::isfinite(margin), "is_exponentially_stable_periodic", "margin", "must be finite");
  detail::require_floquet_arguments(period, steps, "is_exponentially_stable_periodic");
  if (a0.rows() == 0) return true;
  return detail::controlled_floquet_exponents(A, period, steps, a0.rows(), 1, "is_exponentially_stable_periodic")(0) <
         -margin;
}

}  // namespace adaptobs
