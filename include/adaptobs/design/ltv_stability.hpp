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
#include <limits>

namespace adaptobs {

/// Transition matrix \f$\Phi(t_1, t_0)\f$ of \f$\dot e = A(t)e\f$ by RK4 with `steps` steps.
template <class AFn, typename Scalar = double>
[[nodiscard]] Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic> transition_matrix(const AFn& A, Scalar t0,
                                                                                       Scalar t1, int steps = 2000) {
  using Matrix = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;
  const Matrix a0 = A(t0);
  detail::require_square(a0, "transition_matrix", "A");
  detail::require(steps >= 1, "transition_matrix", "steps", "must be at least 1");
  Matrix phi = Matrix::Identity(a0.rows(), a0.rows());
  RungeKutta4<Matrix> rk4(phi);
  rk4.integrate([&](const Matrix& x, Matrix& dx, Scalar t) { dx.noalias() = Matrix(A(t)) * x; }, phi, t0, t1, steps);
  return phi;
}

/// Floquet exponents \f$\log|\mu_i|/T\f$ of a `period`-periodic \f$\dot e = A(t)e\f$, largest first.
/// All NaN when the monodromy matrix is not finite: the solution left the
/// floating-point range within one period (or A(t) was not finite), and no
/// exponent can be told; `is_exponentially_stable_periodic` is then false.
template <class AFn, typename Scalar = double>
[[nodiscard]] Eigen::Matrix<Scalar, Eigen::Dynamic, 1> floquet_exponents(const AFn& A, Scalar period,
                                                                         int steps = 2000) {
  using Vector = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;
  detail::require_positive(period, "floquet_exponents", "period");
  const auto m = transition_matrix(A, Scalar(0), period, steps);
  if (!m.allFinite()) return Vector::Constant(m.rows(), std::numeric_limits<Scalar>::quiet_NaN());
  Vector exponents = detail::dense_eigenvalues(detail::dynamic_copy(m)).cwiseAbs().array().log() / period;
  std::sort(exponents.begin(), exponents.end(), [](Scalar a, Scalar b) { return a > b; });
  return exponents;
}

/// Exponential stability of a periodic \f$\dot e = A(t)e\f$: every Floquet exponent below −margin
/// (false when they are NaN).
template <class AFn, typename Scalar = double>
[[nodiscard]] bool is_exponentially_stable_periodic(const AFn& A, Scalar period, Scalar margin = 0,
                                                    int steps = 2000) {
  return floquet_exponents(A, period, steps)(0) < -margin;
}

}  // namespace adaptobs
