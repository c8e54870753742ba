#pragma once
/// \file
/// Eigenvalues of a small symmetric matrix by the cyclic Jacobi method.
///
/// The per-step diagnostics (‖C Υ‖₂, the excitation level of a p × p Gramian)
/// and the configuration checks (positive semidefiniteness) need a few
/// eigenvalues of small symmetric matrices. Jacobi rotations give them to high
/// relative accuracy (Demmel & Veselić, "Jacobi's method is more accurate than
/// QR", SIAM J. Matrix Anal. Appl. 13(4), 1992), and the routine is a few
/// scalar loops, cheap to compile where it is called (unlike a tridiagonal QR solver).

#include <adaptobs/core/dimensions.hpp>

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <limits>

namespace adaptobs {

/// Eigenvalues, in ascending order, of the symmetric matrix `m` (only its
/// lower triangle is read). Sweeps of Jacobi rotations
/// (Golub & Van Loan, "Matrix Computations", 4th ed., §8.5) run until every
/// off-diagonal entry is negligible against its diagonal pair,
/// \f$|a_{pq}| \le \varepsilon\sqrt{|a_{pp}a_{qq}|}\f$, or is below the
/// smallest normal number. Each sweep costs about \f$4n^3\f$ flops, and
/// convergence is quadratic: a handful of sweeps for the sizes observers use.
/// A non-finite entry in the lower triangle gives NaN for every eigenvalue.
template <class Derived>
[[nodiscard]] Eigen::Matrix<typename Derived::Scalar, Derived::RowsAtCompileTime, 1> symmetric_eigenvalues(
    const Eigen::MatrixBase<Derived>& m) {
  using Scalar = typename Derived::Scalar;
  constexpr int N = Derived::RowsAtCompileTime;
  const Index n = m.rows();
  // Checked first: a NaN off the diagonal fails every rotation test below and
  // would leave the diagonal standing as the answer, and sorting NaNs is undefined.
  for (Index j = 0; j < n; ++j)
    for (Index i = j; i < n; ++i)
      if (!std::isfinite(m(i, j)))
        return Eigen::Matrix<Scalar, N, 1>::Constant(n, std::numeric_limits<Scalar>::quiet_NaN());
  Eigen::Matrix<Scalar, N, N> a = m.template triangularView<Eigen::Lower>();
  a.template triangularView<Eigen::StrictlyUpper>() = a.transpose();
  constexpr Scalar eps = std::numeric_limits<Scalar>::epsilon();
  constexpr Scalar tiny = std::numeric_limits<Scalar>::min();
  constexpr int max_sweeps = 64;  // quadratic convergence: never reached on finite input
  for (int sweep = 0; sweep < max_sweeps; ++sweep) {
    bool rotated = false;
    for (Index p = 0; p + 1 < n; ++p) {
      for (Index q = p + 1; q < n; ++q) {
        const Scalar apq = a(q, p);
        // √|a_pp| √|a_qq|, not √|a_pp a_qq|: the product overflows (or underflows)
        // for entries beyond about 10^±154, and no rotation would then be made.
        const Scalar pair = std::sqrt(std::abs(a(p, p))) * std::sqrt(std::abs(a(q, q)));
        if (!(std::abs(apq) > std::max(eps * pair, tiny))) continue;
        rotated = true;
        // Rotation that annihilates a(q, p): t = tan φ is the smaller root of
        // t² + 2τt − 1 = 0 with τ = (a_qq − a_pp) / (2 a_pq).
        const Scalar tau = (a(q, q) - a(p, p)) / (Scalar(2) * apq);
        const Scalar t = (tau >= 0 ? Scalar(1) : Scalar(-1)) / (std::abs(tau) + std::hypot(Scalar(1), tau));
        const Scalar c = Scalar(1) / std::hypot(Scalar(1), t);
        const Scalar s = t * c;
        for (Index k = 0; k < n; ++k) {  // columns p and q
          const Scalar akp = a(k, p), akq = a(k, q);
          a(k, p) = c * akp - s * akq;
          a(k, q) = s * akp + c * akq;
        }
        for (Index k = 0; k < n; ++k) {  // rows p and q
          const Scalar apk = a(p, k), aqk = a(q, k);
          a(p, k) = c * apk - s * aqk;
          a(q, k) = s * apk + c * aqk;
        }
        a(p, q) = a(q, p) = Scalar(0);
      }
    }
    if (!rotated) break;
  }
  Eigen::Matrix<Scalar, N, 1> lambda = a.diagonal();
  std::sort(lambda.data(), lambda.data() + n);
  return lambda;
}

}  // namespace adaptobs
