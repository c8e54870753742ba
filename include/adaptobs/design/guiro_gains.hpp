#pragma once
/// \file
/// Gains K and Γ of the continuous-discrete adaptive observer of Guiro, Iggidr,
/// Ngom and Touré (Guiro et al. 2008, §2.2–§3) for any number of
/// states n, outputs m and parameters p.
///
/// With \f$E = e^{AT}\f$ and a nominal regressor \f$\bar H\f$ (the paper takes
/// \f$\bar H = H_0\f$), the errors \f$v_k = (z_k - x_k,\ \hat\theta_k - \theta)\f$ of
/// eq. (2) obey eq. (4)–(5):
/// \f[ v_{k+1} = (U + W(k))v_k,\quad
///     U = \begin{bmatrix}(I-KC)E & (I-KC)E\bar H\\ -\Gamma C & I_p\end{bmatrix},\quad
///     W(k) = \begin{bmatrix}0 & (I-KC)E(H_k-\bar H)\\ 0 & 0\end{bmatrix}. \f]
///
/// **Design by reduction to output injection.** Let
/// \f$\bar A = \begin{bmatrix}E & E\bar H\\ 0 & I_p\end{bmatrix}\f$, \f$\bar C = [C\ \ 0]\f$,
/// \f$L = \begin{bmatrix}EK\\ \Gamma(I_m - CK)\end{bmatrix}\f$,
/// \f$P = \mathrm{diag}(I - KC, I_p)\f$, \f$Q = \begin{bmatrix}E & E\bar H\\ -\Gamma C & I_p\end{bmatrix}\f$.
/// Then \f$U = PQ\f$ and \f$\bar A - L\bar C = QP\f$, so U has the characteristic
/// polynomial of \f$\bar A - L\bar C\f$ (the two are similar through P when
/// \f$I - CK\f$ is invertible): in a-priori error coordinates, eq. (2) is a
/// predictor for the augmented state \f$(x, \theta)\f$ with the constant gain L.
/// So the spectrum is placed on \f$(\bar A, \bar C)\f$ (`PolePlacer`), and the
/// gains follow as \f$K = E^{-1}L_1\f$, \f$N = I_m - CK\f$, \f$\Gamma = L_2N^{-1}\f$.
///
/// **When gains exist.** \f$(\bar A, \bar C)\f$ must be observable: (E, C)
/// observable and \f$\operatorname{rank}\begin{bmatrix}E - I & E\bar H\\ C & 0\end{bmatrix} = n + p\f$,
/// which requires \f$p \le \operatorname{rank}C\f$ (otherwise at least
/// \f$p - \operatorname{rank}C\f$ eigenvalues of U stay at 1 whatever K and Γ:
/// one output identifies at most one parameter). And N must be invertible for
/// some placing L; with one output L is unique, and a singular N means Γ
/// would be infinite: the spectrum is then not assignable. For the paper's
/// n = 2 example this is \f$aT\prod\lambda_i \ne bQ(1)\f$ with
/// \f$H_0 = (a, b)\f$ and \f$Q(z) = \prod(z - \lambda_i)\f$; the paper's own
/// condition \f$a(1 + b\Gamma) \ne 0\f$ comes from its route (Ackermann on
/// \f$(\tilde U^T, \tilde C^T)\f$, then Γ chosen to cancel the third gain): its
/// \f$a \ne 0\f$ is the rank condition above, while \f$1 + b\Gamma = 0\f$ occurs
/// exactly when 0 is a requested pole, a spectrum this design does assign.
///
/// Every returned design is verified: Cayley–Hamilton residual of U against
/// the requested spectrum, and \f$\rho(U) < 1\f$.

#include <adaptobs/core/detail/dynamic_copy.hpp>
#include <adaptobs/core/dimensions.hpp>
#include <adaptobs/core/precompiled.hpp>
#include <adaptobs/core/validation.hpp>
#include <adaptobs/design/observability.hpp>
#include <adaptobs/design/pole_placement.hpp>
#include <adaptobs/design/stability.hpp>

#include <Eigen/Core>
#include <Eigen/LU>
#include <Eigen/SVD>

#include <cmath>
#include <limits>
#include <optional>
#include <sstream>
#include <string>

namespace adaptobs {

struct GuiroDesignOptions {
  PolePlacementOptions placement;
  /// \f$N = I - CK\f$ counts as singular when \f$\sigma_{\min}(N) \le\f$ this × \f$\max(1, \sigma_{\max}(N))\f$.
  double singularity_tolerance = 1e-8;
  /// Relative tolerance of the rank test at the eigenvalue 1 (\f$\theta\f$ identifiable).
  double rank_tolerance = 1e-10;
};

/// Designed gains with the figures that certify them.
template <typename Scalar, int NX, int NY, int NP>
struct GuiroGains {
  static constexpr int na = sum_of_sizes(NX, NP);
  Eigen::Matrix<Scalar, NX, NY> K;      ///< state correction gain
  Eigen::Matrix<Scalar, NP, NY> Gamma;  ///< parameter gain Γ
  Eigen::Matrix<Scalar, na, NY> L;      ///< equivalent predictor gain \f$[EK;\ \Gamma(I - CK)]\f$
  Eigen::Matrix<Scalar, na, na> U;      ///< error matrix U at \f$\bar H\f$
  Scalar cayley_hamilton_residual = 0;  ///< of U against the requested spectrum
  Scalar spectral_radius = 0;           ///< \f$\rho(U)\f$
  /// cond₂ of \f$\mathrm{diag}(I-KC, I)X^{-1}\f$, the eigenvector matrix of U up to
  /// that of the target: how much the placed eigenvalues move under perturbation.
  Scalar eigenvector_condition = 0;
  Scalar eigenvalue_mismatch = 0;  ///< largest |eig(U) − requested| (greedy matching)
};

namespace detail {

/// The sizes U of Guiro et al. (2008), §2.2, is built from: refuses, naming
/// `who`, an E that is not square and a C (m × n), \f$\bar H\f$ (n × p), K (n × m)
/// or Γ (p × m) that does not fit it.
template <typename Scalar>
void require_guiro_sizes(const Eigen::MatrixX<Scalar>& E, const Eigen::MatrixX<Scalar>& C,
                         const Eigen::MatrixX<Scalar>& Hbar, const Eigen::MatrixX<Scalar>& K,
                         const Eigen::MatrixX<Scalar>& Gamma, std::string_view who) {
  require_square(E, who, "E");
  const Index n = E.rows(), p = Hbar.cols(), m = C.rows();
  require_shape(C, m, n, who, "C");
  require_shape(Hbar, n, p, who, "Hbar");
  require_shape(K, n, m, who, "K");
  require_shape(Gamma, p, m, who, "Gamma");
}

}  // namespace detail

/// Error matrix \f$U = \begin{bmatrix}(I-KC)E & (I-KC)E\bar H\\ -\Gamma C & I\end{bmatrix}\f$
/// of Guiro et al. (2008), §2.2 (eq. (5) with \f$H_0\f$ replaced by \f$\bar H\f$),
/// on run-time sizes; `guiro_error_matrix` is the same for fixed-size
/// arguments. Refuses, naming `guiro_error_matrix`, arguments whose sizes do
/// not fit E (n × n), C (m × n), \f$\bar H\f$ (n × p), K (n × m), Γ (p × m).
template <typename Scalar>
[[nodiscard]] Eigen::MatrixX<Scalar> guiro_error_matrix_dynamic(const Eigen::MatrixX<Scalar>& E,
                                                                const Eigen::MatrixX<Scalar>& C,
                                                                const Eigen::MatrixX<Scalar>& Hbar,
                                                                const Eigen::MatrixX<Scalar>& K,
                                                                const Eigen::MatrixX<Scalar>& Gamma) {
  using Matrix = Eigen::MatrixX<Scalar>;
  detail::require_guiro_sizes(E, C, Hbar, K, Gamma, "guiro_error_matrix");
  const Index n = E.rows(), p = Hbar.cols();
  const Matrix ikc_e = (Matrix::Identity(n, n) - K * C) * E;
  Matrix u(n + p, n + p);
  u.topLeftCorner(n, n) = ikc_e;
  u.topRightCorner(n, p) = ikc_e * Hbar;
  u.bottomLeftCorner(p, n) = -Gamma * C;
  u.bottomRightCorner(p, p).setIdentity();
  return u;
}
#ifdef ADAPTOBS_PRECOMPILED
ADAPTOBS_INSTANTIATE Eigen::MatrixXd guiro_error_matrix_dynamic<double>(const Eigen::MatrixXd&, const Eigen::MatrixXd&,
                                                                        const Eigen::MatrixXd&, const Eigen::MatrixXd&,
                                                                        const Eigen::MatrixXd&);
#endif

/// K and Γ such that U (at \f$\bar H\f$) has the spectrum `target` (n + p
/// values inside the unit circle, closed under conjugation), on run-time sizes:
/// the reduction of the file comment. The spectrum is placed on
/// \f$(\bar A, \bar C)\f$ by `PolePlacer` (Bhattacharyya and de Souza 1982);
/// of its `options.placement.tries` candidates L (one for a single output), the
/// one with \f$N = I_m - CK\f$ invertible and the best-conditioned eigenvectors
/// \f$\mathrm{diag}(I-KC, I)X^{-1}\f$ of U is kept, and
/// \f$K = E^{-1}L_1\f$, \f$\Gamma = L_2N^{-1}\f$. The design runs on C's rows
/// scaled by powers of two to unit size and returns the gains in C's units.
/// One instance per scalar type serves every size (compiled once in
/// `adaptobs::precompiled`); `design_guiro_gains` is the same for fixed-size arguments.
///
/// Refusals (`ConfigurationError` naming `design_guiro_gains` and the
/// argument): E not square or not finite, C or \f$\bar H\f$ not finite or
/// not fitting E, C without a row, negative tolerances, not n + p poles or a
/// pole outside the unit circle, (E, C) not observable, p > rank C or the rank
/// test at the eigenvalue 1 failing (θ not identifiable), E too
/// ill-conditioned to invert, N singular for every placing gain (Γ would be
/// infinite), and a design failing its verification (Cayley–Hamilton residual,
/// \f$\rho(U) < 1\f$) or gains beyond the floating-point range.
template <typename Scalar>
[[nodiscard]] GuiroGains<Scalar, Eigen::Dynamic, Eigen::Dynamic, Eigen::Dynamic> design_guiro_gains_dynamic(
    const Eigen::MatrixX<Scalar>& E, const Eigen::MatrixX<Scalar>& C_given, const Eigen::MatrixX<Scalar>& Hbar,
    const ComplexVector<Scalar>& target, const GuiroDesignOptions& options = {}) {
  using Matrix = Eigen::MatrixX<Scalar>;
  constexpr std::string_view who = "design_guiro_gains";
  require_square(E, who, "E");
  require_finite(E, who, "E");
  const Index n = E.rows(), m = C_given.rows(), p = Hbar.cols(), na = n + p;
  require_finite_shape(C_given, m, n, who, "C");
  require(m >= 1, who, "C", "must have at least one row (output)");
  // The design does not depend on the units of the outputs: with C = D C_given,
  // D diagonal, the gains K D, Γ D and L D for C_given give the same KC, ΓC and U
  // (N = I − CK becomes the similar D⁻¹ND). It runs on the rows of C scaled by
  // powers of two (exactly) to their largest entry in [1, 2), so that the rank
  // of C and the rank test at the eigenvalue 1 judge each output in its own units.
  const auto output_exponents = detail::row_exponents<Scalar>(C_given);
  const Matrix C = detail::scaled_by_powers_of_two<Scalar>(C_given, output_exponents, true);
  require_finite_shape(Hbar, n, p, who, "Hbar");
  // Compared with `>` below, which a NaN fails: the refusal would blame the data.
  require_non_negative(options.rank_tolerance, who, "options.rank_tolerance");
  require_non_negative(options.singularity_tolerance, who, "options.singularity_tolerance");
  if (target.size() != na) {
    std::ostringstream os;
    os << "must hold n + p = " << na << " values (got " << target.size() << ")";
    fail_argument(who, "poles", os.str());
  }
  for (Index i = 0; i < na; ++i)
    require(std::abs(target(i)) < Scalar(1), who, "poles",
            "must lie inside the unit circle (the error dynamics must be Schur stable)");

  // θ identifiable through the eigenvalue 1 of Ā: (E, C) observable, p ≤ rank C,
  // then the exact rank test at 1.
  const auto state_report = observability(E, C, Scalar(options.placement.observability_tolerance));
  if (!state_report.observable()) {
    fail_argument(who, "E, C",
                  "is not observable: its mode(s) " + detail::format_complex_list(state_report.unobservable_modes) +
                      " cannot be moved");
  }
  const Scalar c_scale = C.norm();
  const auto c_sigma = Eigen::JacobiSVD<Matrix>(C).singularValues();
  Index c_rank = 0;
  while (c_rank < c_sigma.size() && c_sigma(c_rank) > Scalar(options.rank_tolerance) * c_scale) ++c_rank;
  if (p > c_rank) {
    std::ostringstream os;
    os << "has p = " << p << " columns but C has rank " << c_rank << ": at least " << p - c_rank
       << " eigenvalue(s) of U stay at 1 for every K and Gamma (the outputs identify at most rank C parameters)";
    fail_argument(who, "Hbar", os.str());
  }
  Matrix a_bar = Matrix::Zero(na, na);
  a_bar.topLeftCorner(n, n) = E;
  a_bar.topRightCorner(n, p) = E * Hbar;
  a_bar.bottomRightCorner(p, p).setIdentity();
  Matrix c_bar = Matrix::Zero(m, na);
  c_bar.leftCols(n) = C;
  if (p > 0 && !(pbh_margin(a_bar, c_bar, Scalar(1)) > Scalar(options.rank_tolerance))) {
    fail_argument(who, "Hbar",
                  "leaves theta unidentifiable: rank [E - I, E Hbar; C, 0] < n + p, so an eigenvalue 1 of U "
                  "cannot be moved by any K and Gamma");
  }

  // K = E⁻¹L: an E singular to working accuracy would show only later, as an
  // I − CK that no draw makes invertible.
  const Eigen::PartialPivLU<Matrix> e_lu(E);
  if (!(e_lu.rcond() > Scalar(100) * std::numeric_limits<Scalar>::epsilon()))
    fail_argument(who, "E", "is too ill-conditioned to invert (reciprocal condition number at most 100 eps)");
  PolePlacer<Scalar> placer(a_bar, c_bar, target, options.placement, who, "E, C", "observable");
  const Matrix identity_m = Matrix::Identity(m, m);
  struct Choice {
    Matrix L, K, N;
    Scalar score = std::numeric_limits<Scalar>::infinity();
  };
  std::optional<Choice> best;
  bool any_candidate = false;
  for (int t = 0; t < placer.draws(); ++t) {
    const auto candidate = placer.candidate(placer.draw_parameter());
    if (!candidate) continue;
    any_candidate = true;
    Choice c;
    c.L = candidate->L;
    c.K = e_lu.solve(c.L.topRows(n));
    c.N = identity_m - C * c.K;
    const auto n_sigma = Eigen::JacobiSVD<Matrix>(c.N).singularValues();
    if (!(n_sigma(m - 1) > Scalar(options.singularity_tolerance) * std::max(Scalar(1), n_sigma(0)))) continue;
    // Eigenvectors of U: diag(I − KC, I) X⁻¹ times those of the target matrix.
    Matrix p_xinv = Eigen::JacobiSVD<Matrix>(candidate->X, Eigen::ComputeFullU | Eigen::ComputeFullV)
                        .solve(Matrix::Identity(na, na));
    p_xinv.topRows(n) = ((Matrix::Identity(n, n) - c.K * C) * p_xinv.topRows(n)).eval();
    const auto s = Eigen::JacobiSVD<Matrix>(p_xinv).singularValues();
    c.score = s(0) / s(na - 1);
    if (!std::isfinite(c.score)) c.score = std::numeric_limits<Scalar>::max();
    if (!best || c.score < best->score) best = std::move(c);
  }
  if (!best) {
    if (!any_candidate)
      fail_argument(who, "poles", "could not be placed: the Sylvester transformation was singular in every draw");
    fail_argument(who, "poles",
                  m == 1 ? "cannot be assigned: I - C K is singular for the only gain that places them "
                           "(Gamma would be infinite)"
                         : "cannot be assigned: I - C K is singular for every placing gain tried "
                           "(Gamma would be infinite)");
  }

  GuiroGains<Scalar, Eigen::Dynamic, Eigen::Dynamic, Eigen::Dynamic> gains;
  // Γ = L₂ N⁻¹  ⇔  Nᵀ Γᵀ = L₂ᵀ; then each gain in the caller's output units (columns times D).
  const Matrix gamma = best->N.transpose().fullPivLu().solve(Matrix(best->L.bottomRows(p).transpose())).transpose();
  gains.U = guiro_error_matrix_dynamic<Scalar>(E, C, Hbar, best->K, gamma);
  gains.eigenvector_condition = best->score;
  gains.cayley_hamilton_residual = cayley_hamilton_residual(gains.U, target);
  gains.eigenvalue_mismatch = eigenvalue_mismatch(gains.U, target);
  gains.spectral_radius = spectral_radius(gains.U);
  const Scalar tol = detail::default_verification_tolerance<Scalar>(options.placement.verification_tolerance);
  if (!(gains.cayley_hamilton_residual <= tol) || !(gains.spectral_radius < Scalar(1)) || !best->K.allFinite() ||
      !gamma.allFinite()) {
    std::ostringstream os;
    os << "could not be assigned to the required accuracy (Cayley-Hamilton residual " << gains.cayley_hamilton_residual
       << ", tolerance " << tol << ", spectral radius of U " << gains.spectral_radius
       << "): (E, C, Hbar) is too close to a case without solution";
    fail_argument(who, "poles", os.str());
  }
  gains.K = detail::scaled_by_powers_of_two<Scalar>(best->K, output_exponents, false);
  gains.Gamma = detail::scaled_by_powers_of_two<Scalar>(gamma, output_exponents, false);
  gains.L = detail::scaled_by_powers_of_two<Scalar>(best->L, output_exponents, false);
  if (!gains.K.allFinite() || !gains.Gamma.allFinite() || !gains.L.allFinite())
    fail_argument(who, "C", "is so small that the gains for it lie beyond the floating-point range");
  return gains;
}
#ifdef ADAPTOBS_PRECOMPILED
ADAPTOBS_INSTANTIATE GuiroGains<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::Dynamic>
design_guiro_gains_dynamic<double>(const Eigen::MatrixXd&, const Eigen::MatrixXd&, const Eigen::MatrixXd&,
                                   const ComplexVector<double>&, const GuiroDesignOptions&);
#endif

/// Error matrix U of Guiro et al. (2008), §2.2: `guiro_error_matrix_dynamic`
/// on copies, sized (n + p) × (n + p) from E and \f$\bar H\f$.
template <class DE, class DC, class DH, class DK, class DG>
[[nodiscard]] auto guiro_error_matrix(const Eigen::MatrixBase<DE>& E, const Eigen::MatrixBase<DC>& C,
                                      const Eigen::MatrixBase<DH>& Hbar, const Eigen::MatrixBase<DK>& K,
                                      const Eigen::MatrixBase<DG>& Gamma) {
  using Scalar = typename DE::Scalar;
  constexpr int na = sum_of_sizes(DE::RowsAtCompileTime, DH::ColsAtCompileTime);
  return Eigen::Matrix<Scalar, na, na>(
      guiro_error_matrix_dynamic<Scalar>(detail::dynamic_copy(E), detail::dynamic_copy(C), detail::dynamic_copy(Hbar),
                                         detail::dynamic_copy(K), detail::dynamic_copy(Gamma)));
}

/// K and Γ such that U (at \f$\bar H\f$) has the spectrum `poles` (n + p values
/// inside the unit circle, closed under conjugation): `design_guiro_gains_dynamic`
/// on copies, sized by E, C and Hbar; see the file comment.
/// \param E \f$e^{AT}\f$, \param C output matrix (m × n), \param Hbar nominal
/// regressor \f$\bar H\f$ (n × p): \f$H_0\f$ as in the paper, or the limit of
/// \f$H_k\f$ when φ settles. Throws `ConfigurationError` naming the cause when
/// no gains exist or the design cannot be verified.
template <class DE, class DC, class DH, class DP>
[[nodiscard]] auto design_guiro_gains(const Eigen::MatrixBase<DE>& E, const Eigen::MatrixBase<DC>& C,
                                      const Eigen::MatrixBase<DH>& Hbar, const Eigen::MatrixBase<DP>& poles,
                                      GuiroDesignOptions options = {}) {
  using Scalar = typename DE::Scalar;
  constexpr int NX = DE::RowsAtCompileTime, NY = DC::RowsAtCompileTime, NP = DH::ColsAtCompileTime;
  const auto d =
      design_guiro_gains_dynamic<Scalar>(detail::dynamic_copy(E), detail::dynamic_copy(C), detail::dynamic_copy(Hbar),
                                         detail::complex_poles<Scalar>(poles, "design_guiro_gains"), options);
  GuiroGains<Scalar, NX, NY, NP> gains;
  gains.K = d.K;
  gains.Gamma = d.Gamma;
  gains.L = d.L;
  gains.U = d.U;
  gains.cayley_hamilton_residual = d.cayley_hamilton_residual;
  gains.spectral_radius = d.spectral_radius;
  gains.eigenvector_condition = d.eigenvector_condition;
  gains.eigenvalue_mismatch = d.eigenvalue_mismatch;
  return gains;
}

}  // namespace adaptobs
