#pragma once
/// \file
/// What the algebraic Riccati solvers (dare.hpp, care.hpp) share: the
/// scalings they apply before they iterate, and the terms of their refusals.
///
/// Both the discrete and the continuous equation keep their form under
/// - **X = σX̃**: (A, B, Q, R) becomes (A, B, Q/σ, R/σ);
/// - **a state scaling x = Dx̃** (D diagonal): (A, B, Q, R) becomes
///   (D⁻¹AD, D⁻¹B, DQD, R) and X̃ = DXD.
///
/// Both are exact when σ and the entries of D are powers of two. The first
/// keeps X, Q and R of order one (X of order R for a huge R would overflow
/// the products otherwise); the second equalizes the rows and columns of the
/// Hamiltonian matrix so that an iteration on it does not lose the small
/// entries against the large ones.

#include <adaptobs/core/detail/dynamic_copy.hpp>
#include <adaptobs/core/validation.hpp>

#include <Eigen/Core>
#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <sstream>
#include <string>
#include <string_view>

namespace adaptobs::detail {

/// The power of two nearest below max(max|Q|, max|R| / max‖B e_j‖²), or 1 when
/// that is 0, formed from binary exponents so that it cannot overflow.
template <typename Scalar>
[[nodiscard]] Scalar riccati_solution_scale(const DynamicMatrix<Scalar>& B, const DynamicMatrix<Scalar>& Q,
                                            const DynamicMatrix<Scalar>& R) {
  const Scalar b2 = B.size() ? B.cwiseAbs2().colwise().sum().maxCoeff() : Scalar(0);
  const Scalar r = R.size() ? R.cwiseAbs().maxCoeff() : Scalar(0);
  const Scalar q = Q.size() ? Q.cwiseAbs().maxCoeff() : Scalar(0);
  constexpr int lowest = std::numeric_limits<Scalar>::min_exponent;
  constexpr int highest = std::numeric_limits<Scalar>::max_exponent - 2;
  int exponent = lowest - 1;  // "none yet"
  if (q > Scalar(0) && std::isfinite(q)) exponent = std::ilogb(q);
  if (b2 > Scalar(0) && std::isfinite(b2) && r > Scalar(0))
    exponent = std::max(exponent, std::ilogb(r) - std::ilogb(b2));
  return exponent < lowest ? Scalar(1) : std::ldexp(Scalar(1), std::min(exponent, highest));
}

/// Diagonal state scaling D (powers of two) that balances the Hamiltonian
/// \f$\mathcal H = \begin{bmatrix} A & -G\\ -Q & -A^T\end{bmatrix}\f$ under the symplectic
/// similarity diag(D, D⁻¹), applied in place to A, G = BR⁻¹Bᵀ and Q; returns the diagonal of D.
///
/// Scaling state i by f multiplies the off-diagonal entries of column i of A
/// and of column and row i of Q by f, and q_ii by f²; it divides those of row i
/// of A and of row and column i of G by f, and g_ii by f². In \f$\mathcal H\f$ each
/// off-diagonal entry of A, Q and G appears twice. The sum of the absolute
/// entries of \f$\mathcal H\f$ that depend on f is therefore
/// \f$S(f) = 2c f + q_{ii} f^2 + 2r / f + g_{ii} / f^2\f$, with
/// \f$c = \sum_{j\ne i}(|a_{ji}| + |q_{ji}|)\f$ and \f$r = \sum_{j\ne i}(|a_{ij}| + |g_{ij}|)\f$.
/// S is convex in log f. Each sweep moves every f to the power of two that
/// minimizes S, when that lowers S by 5% or more: coordinate descent on the
/// entry sum of \f$\mathcal H\f$, as in Osborne's balancing (E. E. Osborne, "On
/// pre-conditioning of matrices", J. ACM 7(4), 1960).
template <typename Scalar>
Eigen::Matrix<Scalar, Eigen::Dynamic, 1> balance_hamiltonian(DynamicMatrix<Scalar>& A, DynamicMatrix<Scalar>& G,
                                                             DynamicMatrix<Scalar>& Q) {
  const Index n = A.rows();
  Eigen::Matrix<Scalar, Eigen::Dynamic, 1> d = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>::Ones(n);
  for (int sweep = 0; sweep < 64; ++sweep) {
    bool changed = false;
    for (Index i = 0; i < n; ++i) {
      const Scalar qii = std::abs(Q(i, i)), gii = std::abs(G(i, i));
      const Scalar c = A.col(i).cwiseAbs().sum() - std::abs(A(i, i)) + Q.col(i).cwiseAbs().sum() - qii;
      const Scalar r = A.row(i).cwiseAbs().sum() - std::abs(A(i, i)) + G.row(i).cwiseAbs().sum() - gii;
      // S needs a growing and a shrinking part to have a minimum.
      if (!std::isfinite(c + qii + r + gii) || !(c + qii > Scalar(0)) || !(r + gii > Scalar(0))) continue;
      const auto sum = [&](int k) {
        const Scalar f = std::ldexp(Scalar(1), k);
        return Scalar(2) * c * f + qii * f * f + Scalar(2) * r / f + gii / (f * f);
      };
      // Descend from 0 while S decreases (convex in k), at most the exponent range.
      int k = 0;
      const int direction = sum(1) < sum(0) ? 1 : (sum(-1) < sum(0) ? -1 : 0);
      if (direction == 0) continue;
      while (std::abs(k) < std::numeric_limits<Scalar>::max_exponent / 4 && sum(k + direction) < sum(k)) k += direction;
      if (!(sum(k) < Scalar(0.95) * sum(0))) continue;
      changed = true;
      const Scalar f = std::ldexp(Scalar(1), k);
      d(i) *= f;
      A.col(i) *= f;
      A.row(i) /= f;
      Q.col(i) *= f;
      Q.row(i) *= f;
      G.col(i) /= f;
      G.row(i) /= f;
    }
    if (!changed) break;
  }
  return d;
}

/// \f$\tfrac12(M + M^T)\f$: the iterates of both solvers are symmetric in exact
/// arithmetic, and are kept so against rounding.
template <typename Scalar>
[[nodiscard]] DynamicMatrix<Scalar> symmetric_part(const DynamicMatrix<Scalar>& m) {
  return Scalar(0.5) * (m + m.transpose());
}

/// True when the partial-pivoting LU has no zero or non-finite pivot, so that
/// its solves are defined (PartialPivLU itself divides by whatever pivot it finds).
template <typename Scalar>
[[nodiscard]] bool has_regular_pivots(const Eigen::PartialPivLU<DynamicMatrix<Scalar>>& lu) {
  const auto pivots = lu.matrixLU().diagonal();
  return pivots.allFinite() && (pivots.array() != Scalar(0)).all();
}

/// Relative distance from the stability boundary below which a closed-loop
/// mode does not prove stabilizability: an uncontrollable mode on the circle
/// or the axis comes back from the solvers displaced by rounding, of order
/// ε‖M‖ (10⁴ ε is 2.2e-12 in double).
template <typename Scalar>
inline constexpr Scalar stabilizability_margin = Scalar(1e4) * std::numeric_limits<Scalar>::epsilon();

/// The names a refusal uses. The control equations speak of (A, B, Q, R);
/// the Kalman gains solve the dual equation (Aᵀ, Cᵀ, Q, R) and speak of C,
/// detectability and process noise.
struct RiccatiRoles {
  std::string_view who;
  std::string_view b;                 ///< the input (or output) matrix
  std::string_view not_stabilizable;  ///< message for argument "A, <b>"
  std::string_view unreached_mode;    ///< message for argument "A, Q": a marginal mode Q does not see
};

/// A solution computed at run-time size, handed back at the caller's
/// compile-time order N: the public solvers of both equations run on dynamic
/// copies (`dynamic_copy`), and return `CareSolution` or `DareSolution` sized as
/// the caller's A.
template <int N, template <typename, int> class Solution, typename Scalar>
[[nodiscard]] Solution<Scalar, N> with_order(const Solution<Scalar, Eigen::Dynamic>& solution) {
  return Solution<Scalar, N>{solution.X, solution.iterations, solution.relative_residual};
}

/// The checks both equations make of their data: A square and finite, B
/// finite with A's rows, Q positive semidefinite, R positive definite.
template <typename Scalar>
void validate_riccati_data(const DynamicMatrix<Scalar>& A, const DynamicMatrix<Scalar>& B,
                           const DynamicMatrix<Scalar>& Q, const DynamicMatrix<Scalar>& R, const RiccatiRoles& roles) {
  require_square(A, roles.who, "A");
  require_finite(A, roles.who, "A");
  require_finite_shape(B, A.rows(), B.cols(), roles.who, roles.b);
  require_shape(Q, A.rows(), A.rows(), roles.who, "Q");
  require_positive_semidefinite(Q, roles.who, "Q");
  require_shape(R, B.cols(), B.cols(), roles.who, "R");
  require_positive_definite(R, roles.who, "R");
}

[[noreturn]] inline void fail_not_stabilizable(const RiccatiRoles& roles) {
  fail_argument(roles.who, std::string("A, ").append(roles.b), roles.not_stabilizable);
}

[[noreturn]] inline void fail_unreached_mode(const RiccatiRoles& roles) {
  fail_argument(roles.who, "A, Q", roles.unreached_mode);
}

/// Refusal of a solution found in scaled form whose scale-back \f$X = \sigma\tilde X\f$
/// leaves the floating-point range. X is proportional to (Q, R) scaled together,
/// so the caller can scale them down and the result back up.
[[noreturn]] inline void fail_out_of_range(const RiccatiRoles& roles) {
  fail_argument(roles.who, "Q, R",
                "give a solution X beyond the floating-point range (X scales with Q and R: scale both down)");
}

/// Refusal of a well-posed equation that the precision cannot solve to the
/// stated accuracy: the figures reached and those required.
template <typename Scalar>
[[noreturn]] void fail_ill_conditioned(const RiccatiRoles& roles, Scalar residual, Scalar tolerance,
                                       std::string_view stability_figure, Scalar reached, Scalar required) {
  std::ostringstream os;
  os << "give a Riccati equation too ill-conditioned for this precision: the best solution found has relative "
        "residual "
     << residual << " (at most " << tolerance << " required) and closed-loop " << stability_figure << " " << reached
     << " (below " << required << " required)";
  fail_argument(roles.who, std::string("A, ").append(roles.b).append(", Q, R"), os.str());
}

}  // namespace adaptobs::detail
