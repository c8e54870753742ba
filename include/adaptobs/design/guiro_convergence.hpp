#pragma once
/// \file
/// Proposition 2.2 of Guiro et al. (2008) as a diagnostic: does
/// condition (i) or (ii) of proposition 2.1 hold for the regressor data at hand?
///
/// The observer's errors obey \f$v_{k+1} = (U + W(k))v_k\f$ with U built on a
/// nominal regressor \f$\bar H\f$ and \f$W(k)\f$ carrying \f$H_k - \bar H\f$
/// (see `guiro_gains.hpp`). Proposition 2.1: if U is Schur with
/// \f$\|U^k\| \le M\lambda^k\f$, the perturbed system is exponentially stable when
///  - (i) \f$\|W(k)\| \le b_0 < (1-\lambda)/M\f$ for all \f$k \ge k_0\f$; then
///    \f$\|v_k\| \le M(\lambda + Mb_0)^{k-k_0}\|v_{k_0}\|\f$; or
///  - (ii) \f$\sum_k \|W(k)\| < \infty\f$.
/// The norm is the spectral norm, as in the paper's §4, and
/// \f$\|W(k)\|_2 = \|(I-KC)E(H_k-\bar H)\|_2\f$.
///
/// The check is made on the supplied sequence \f$H_0, \dots, H_{K-1}\f$ with
/// the best bound of `best_power_bound` (the λ that maximizes \f$(1-\lambda)/M\f$):
///  - (i) holds for the data when \f$\|W(k)\| < (1-\lambda)/M\f$ from some
///    \f$k_0\f$ to the last sample; the report gives \f$k_0\f$ and the rate
///    \f$\lambda + M\sup_{k\ge k_0}\|W(k)\|\f$. It fails when the last sample
///    violates the bound.
///  - (ii) cannot be decided from finitely many samples; the report fits
///    \f$\|W(k)\| \sim k^{-\alpha}\f$ over the second half of the data and says
///    it holds when W vanishes there or \f$\alpha > 1.25\f$, fails when
///    \f$\alpha < 0.75\f$ (a non-decaying W has α ≈ 0), and is undetermined
///    in between, where summability is a matter of logarithms.
///
/// The choice of \f$\bar H\f$ matters. For the paper's example with
/// \f$\bar H = H_0\f$, \f$\|W(k)\|\f$ grows to 0.225 while \f$(1-\lambda)/M\f$ is at
/// most 0.049: neither condition holds although the observer converges.
/// Around the limit \f$\bar H = H_\infty\f$ of a settling regressor, \f$W(k) \to 0\f$
/// and (i) holds from some \f$k_0\f$. A failed check is not a proof of divergence.

#include <adaptobs/core/detail/dynamic_copy.hpp>
#include <adaptobs/core/dimensions.hpp>
#include <adaptobs/core/precompiled.hpp>
#include <adaptobs/core/validation.hpp>
#include <adaptobs/design/guiro_gains.hpp>
#include <adaptobs/design/power_bound.hpp>
#include <adaptobs/design/stability.hpp>

#include <Eigen/Core>

#include <cmath>
#include <optional>
#include <ranges>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

namespace adaptobs {

/// Whether a sufficient condition holds on the data.
enum class ConditionVerdict { holds, fails, undetermined };

[[nodiscard]] constexpr std::string_view to_string(ConditionVerdict v) noexcept {
  switch (v) {
    case ConditionVerdict::holds: return "holds";
    case ConditionVerdict::fails: return "fails";
    case ConditionVerdict::undetermined: return "undetermined";
  }
  return "unknown";
}

/// Outcome of `check_guiro_convergence`.
template <typename Scalar>
struct GuiroConvergenceReport {
  Scalar spectral_radius = 0;               ///< \f$\rho(U)\f$ at the chosen \f$\bar H\f$
  std::optional<PowerBound<Scalar>> bound;  ///< \f$\|U^k\|_2 \le M\lambda^k\f$; empty when U is not Schur
  std::vector<Scalar> w_norms;              ///< \f$\|W(k)\|_2\f$ for the supplied \f$H_k\f$

  ConditionVerdict condition_i = ConditionVerdict::fails;
  std::optional<Index> k0;  ///< first index from which \f$\|W(k)\| < (1-\lambda)/M\f$ on the data
  Scalar tail_sup = 0;      ///< \f$\sup_{k\ge k_0}\|W(k)\|\f$ on the data
  Scalar rate = 0;          ///< \f$\lambda + M\,\text{tail\_sup}\f$: the decay rate (i) certifies

  ConditionVerdict condition_ii = ConditionVerdict::undetermined;
  Scalar w_sum = 0;           ///< \f$\sum_k\|W(k)\|\f$ over the data
  Scalar decay_exponent = 0;  ///< α of \f$\|W(k)\| \sim k^{-\alpha}\f$ over the second half of the data

  /// Proposition 2.2 applies: U is Schur and (i) or (ii) holds on the data.
  [[nodiscard]] bool certified() const noexcept {
    return bound.has_value() && (condition_i == ConditionVerdict::holds || condition_ii == ConditionVerdict::holds);
  }

  /// One paragraph in words.
  [[nodiscard]] std::string summary() const {
    std::ostringstream os;
    os.precision(4);
    if (!bound) {
      os << "U is not Schur stable (spectral radius " << spectral_radius << "): proposition 2.1 does not apply.";
      return os.str();
    }
    const auto samples = w_norms.size();
    os << "U is Schur (spectral radius " << spectral_radius << "), |U^k| <= " << bound->M << " * " << bound->lambda
       << "^k, so (i) tolerates |W(k)| < " << bound->perturbation_margin() << ". ";
    if (condition_i == ConditionVerdict::holds) {
      os << "(i) holds from k0 = " << *k0 << " (sup |W| = " << tail_sup << ", rate " << rate << "). ";
    } else {
      os << "(i) fails: |W(" << samples - 1 << ")| = " << (samples ? w_norms.back() : Scalar(0))
         << " exceeds the margin. ";
    }
    os << "(ii) " << to_string(condition_ii) << ": sum |W| = " << w_sum << " over " << samples
       << " samples, |W(k)| ~ k^(" << -decay_exponent << ") on the second half.";
    return os.str();
  }
};

/// Proposition 2.2 of Guiro et al. (2008) for gains (K, Γ), nominal regressor
/// \f$\bar H\f$ and the data \f$H_0, H_1, \dots\f$, on run-time sizes (see the
/// file comment): U by `guiro_error_matrix_dynamic`, its bound
/// \f$\|U^k\|_2 \le M\lambda^k\f$ by `best_power_bound`,
/// \f$\|W(k)\|_2 = \|(I-KC)E(H_k-\bar H)\|_2\f$, condition (i) on the longest tail
/// of the data below \f$(1-\lambda)/M\f$, condition (ii) from the least-squares
/// slope of \f$\log\|W(k)\|\f$ against \f$\log k\f$ over the second half.
/// One instance per scalar type (compiled once in `adaptobs::precompiled`);
/// `check_guiro_convergence` takes fixed-size arguments and any range of H_k.
/// Refuses (`ConfigurationError` naming `check_guiro_convergence`) arguments
/// whose sizes do not fit E, a U that is not finite and an \f$H_k\f$ not
/// finite or not n × p.
template <typename Scalar>
[[nodiscard]] GuiroConvergenceReport<Scalar> check_guiro_convergence_dynamic(
    const Eigen::MatrixX<Scalar>& E, const Eigen::MatrixX<Scalar>& C, const Eigen::MatrixX<Scalar>& K,
    const Eigen::MatrixX<Scalar>& Gamma, const Eigen::MatrixX<Scalar>& Hbar,
    const std::vector<Eigen::MatrixX<Scalar>>& H_sequence) {
  using Matrix = Eigen::MatrixX<Scalar>;
  constexpr std::string_view who = "check_guiro_convergence";
  detail::require_guiro_sizes(E, C, Hbar, K, Gamma, who);
  const Index n = E.rows(), p = Hbar.cols();
  const Matrix u = guiro_error_matrix_dynamic<Scalar>(E, C, Hbar, K, Gamma);
  require_finite(u, who, "E, C, Hbar, K, Gamma");

  GuiroConvergenceReport<Scalar> report;
  report.spectral_radius = spectral_radius(u);
  report.bound = best_power_bound(u);

  // ‖W(k)‖₂ = ‖(I − KC) E (H_k − H̄)‖₂.
  const Matrix ikc_e = (Matrix::Identity(n, n) - K * C) * E;
  for (const Matrix& h : H_sequence) {
    require_finite_shape(h, n, p, who, "H_sequence");
    report.w_norms.push_back(detail::largest_singular_value<Scalar>(ikc_e * (h - Hbar)));
  }
  const auto& w = report.w_norms;
  const Index samples = Index(w.size());
  for (Scalar x : w) report.w_sum += x;

  // (i): the longest tail of the data below the margin.
  if (report.bound && samples > 0) {
    const Scalar margin = report.bound->perturbation_margin();
    Index k0 = samples;
    Scalar sup = 0;
    while (k0 > 0 && w[std::size_t(k0 - 1)] < margin) {
      --k0;
      sup = std::max(sup, w[std::size_t(k0)]);
    }
    if (k0 < samples) {
      report.condition_i = ConditionVerdict::holds;
      report.k0 = k0;
      report.tail_sup = sup;
      report.rate = report.bound->lambda + report.bound->M * sup;
    }
  }

  // (ii): decay of ‖W(k)‖ over the second half of the data.
  const Scalar scale = std::max(Scalar(1), Scalar(u.norm()));
  const Scalar negligible = Scalar(100) * std::numeric_limits<Scalar>::epsilon() * scale;
  Scalar sx = 0, sy = 0, sxx = 0, sxy = 0, count = 0;
  bool vanishes = samples >= 2;
  for (Index k = std::max<Index>(1, samples / 2); k < samples; ++k) {
    const Scalar wk = w[std::size_t(k)];
    if (wk > negligible) vanishes = false;
    if (!(wk > 0)) continue;
    const Scalar x = std::log(Scalar(k)), y = std::log(wk);
    sx += x;
    sy += y;
    sxx += x * x;
    sxy += x * y;
    count += 1;
  }
  if (vanishes) {
    report.condition_ii = ConditionVerdict::holds;
    report.decay_exponent = std::numeric_limits<Scalar>::infinity();
  } else if (count >= 8 && count * sxx - sx * sx > 0) {
    report.decay_exponent = -(count * sxy - sx * sy) / (count * sxx - sx * sx);
    if (report.decay_exponent > Scalar(1.25))
      report.condition_ii = ConditionVerdict::holds;
    else if (report.decay_exponent < Scalar(0.75))
      report.condition_ii = ConditionVerdict::fails;
  }
  if (!report.bound) {
    report.condition_i = ConditionVerdict::fails;
    report.condition_ii = ConditionVerdict::fails;
  }
  return report;
}
#ifdef ADAPTOBS_PRECOMPILED
ADAPTOBS_INSTANTIATE GuiroConvergenceReport<double> check_guiro_convergence_dynamic<double>(
    const Eigen::MatrixXd&, const Eigen::MatrixXd&, const Eigen::MatrixXd&, const Eigen::MatrixXd&,
    const Eigen::MatrixXd&, const std::vector<Eigen::MatrixXd>&);
#endif

/// Checks proposition 2.2 for gains (K, Γ), nominal regressor \f$\bar H\f$ and
/// the sequence \f$H_0, H_1, \dots\f$ of the data (a range of n × p matrices):
/// `check_guiro_convergence_dynamic` on copies; see the file comment.
template <class DE, class DC, class DK, class DG, class DH, std::ranges::forward_range Range>
[[nodiscard]] GuiroConvergenceReport<typename DE::Scalar> check_guiro_convergence(
    const Eigen::MatrixBase<DE>& E, const Eigen::MatrixBase<DC>& C, const Eigen::MatrixBase<DK>& K,
    const Eigen::MatrixBase<DG>& Gamma, const Eigen::MatrixBase<DH>& Hbar, const Range& H_sequence) {
  using Scalar = typename DE::Scalar;
  std::vector<Eigen::MatrixX<Scalar>> h;
  for (const auto& hk : H_sequence) h.push_back(detail::dynamic_copy(hk));
  return check_guiro_convergence_dynamic<Scalar>(detail::dynamic_copy(E), detail::dynamic_copy(C),
                                                 detail::dynamic_copy(K), detail::dynamic_copy(Gamma),
                                                 detail::dynamic_copy(Hbar), h);
}

}  // namespace adaptobs
