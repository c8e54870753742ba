#pragma once
/// \file
/// Discrete Lyapunov (Stein) equation \f$X = F^TXF + W\f$ by Smith's doubling.
///
/// For a Schur-stable F the solution is the series \f$\sum_{k\ge0} (F^T)^k W F^k\f$.
/// Doubling sums it in \f$\log_2\f$ as many steps as the series needs terms,
/// \f[ X_{j+1} = X_j + F_j^T X_j F_j,\qquad F_{j+1} = F_j^2,\qquad X_0 = W,\ F_0 = F, \f]
/// so that \f$X_j\f$ holds the first \f$2^j\f$ terms (R. A. Smith, "Matrix equation
/// XA + BX = C", SIAM J. Appl. Math. 16(1), 1968). It needs matrix products
/// only, and is accurate for the Schur-stable F of Newton's method for the
/// discrete Riccati equation, whose spectral radius the caller has already
/// bounded away from 1.

#include <adaptobs/core/detail/dynamic_copy.hpp>
#include <adaptobs/core/precompiled.hpp>

#include <Eigen/Core>

#include <cmath>
#include <limits>

namespace adaptobs {

/// Solution of \f$X = F^TXF + W\f$ for a Schur-stable F (W symmetric) by Smith's
/// doubling (file comment), or a non-finite matrix when the series does not
/// converge within 64 doublings (\f$2^{64}\f$ terms: \f$\rho(F) \ge 1 - 10^{-18}\f$ in practice).
/// The arguments are not checked: F square, W of its size.
template <typename Scalar>
[[nodiscard]] detail::DynamicMatrix<Scalar> solve_stein_doubling(const detail::DynamicMatrix<Scalar>& F,
                                                                 const detail::DynamicMatrix<Scalar>& W) {
  using Matrix = detail::DynamicMatrix<Scalar>;
  Matrix x = W, f = F;
  if (F.size() == 0) return x;
  constexpr Scalar eps = std::numeric_limits<Scalar>::epsilon();
  const Index n = F.rows();
  for (int j = 0; j < 64; ++j) {
    Matrix term = f.transpose().lazyProduct(x).lazyProduct(f);
    term = Scalar(0.5) * (term + term.transpose()).eval();
    x += term;
    // The tail left after 2^(j+1) terms is at most about the term: stop once
    // it is rounding in every entry. Entry by entry against √(|x_ii x_jj|), the
    // scale of x_ij for a semidefinite X, so that a small diagonal block (W =
    // diag(1, 1e-20)) is summed to its own accuracy and not to that of the
    // largest entry; against the largest |x| where that scale is zero.
    const Scalar largest = x.cwiseAbs().maxCoeff();
    bool converged = true;
    for (Index c = 0; c < n && converged; ++c)
      for (Index r = 0; r < n && converged; ++r) {
        const Scalar scale = std::sqrt(std::abs(x(r, r)) * std::abs(x(c, c)));
        converged = std::abs(term(r, c)) <= eps * (scale > Scalar(0) ? scale : largest);
      }
    if (converged) return x;
    f = f.lazyProduct(f).eval();
  }
  return Matrix::Constant(F.rows(), F.cols(), std::numeric_limits<Scalar>::quiet_NaN());
}

#ifdef ADAPTOBS_PRECOMPILED
ADAPTOBS_INSTANTIATE detail::DynamicMatrix<double> solve_stein_doubling<double>(const detail::DynamicMatrix<double>&,
                                                                                const detail::DynamicMatrix<double>&);
#endif

}  // namespace adaptobs
