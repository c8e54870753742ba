#pragma once
/// \file
/// Choosing the step size μ of the Guyader–Zhang observer from a recorded or
/// simulated regressor sequence: the largest μ that keeps assumption 2, and
/// the convergence rate of θ̂ a given μ gives.
///
/// Both rest on one fact of eq. (2a): the filtered regressor
/// \f$\Upsilon_{k+1} = (A_k - K_kC_k)\Upsilon_k + \Psi_k\f$ depends on neither μ nor
/// θ̂, so it can be run ahead of the observer on the regressors alone. With it:
/// - **Assumption 2** (eq. (3)), \f$\|\sqrt{\mu}C_k\Upsilon_k\|_2 \le 1\f$ at every k,
///   holds exactly for \f$\mu \le 1/\max_k\|C_k\Upsilon_k\|_2^2\f$.
/// - **Convergence.** Once η has decayed (it does at the rate of
///   \f$A - KC\f$), the proof of theorem 1 leaves
///   \f$\tilde\theta_{k+1} = (I - \mu\Phi_k)\tilde\theta_k\f$ with
///   \f$\Phi_k = \Upsilon_k^TC_k^TC_k\Upsilon_k\f$. Its rate over the sequence is the
///   largest Lyapunov exponent of the product of the \f$I - \mu\Phi_k\f$, which is
///   computed here, not estimated: \f$\rho = \lim\|\prod_k(I - \mu\Phi_k)\|^{1/N}\f$,
///   the factor by which the slowest component of θ̃ shrinks per step.
/// - **Averaging** predicts \f$\rho \approx 1 - \mu\lambda_{\min}(\bar\Phi)\f$, with
///   \f$\bar\Phi\f$ the mean of \f$\Phi_k\f$ (what `excitation_level()` measures over
///   its window). It holds only while \f$\mu\|\Phi_k\|\f$ is small at every step;
///   when it is not, a larger μ can converge *slower*: a step of
///   \f$\mu\lambda > 1\f$ overshoots along the excited direction, by
///   \f$|1 - \mu\lambda|\f$, and a regressor that excites one direction at a time
///   (a one-sided square wave) turns that into slow progress in the other.
///
/// Measurement noise enters θ̂ through the same gain: in steady state its
/// covariance is about \f$\frac\mu2\sigma^2 I\f$ per unit of \f$\Phi\f$ for small μ, so
/// halving μ halves the variance of θ̂ and doubles its time constant
/// (docs/tuning.md shows the trade-off).

#include <adaptobs/core/dimensions.hpp>
#include <adaptobs/core/discrete_model.hpp>
#include <adaptobs/core/spectral_norm.hpp>
#include <adaptobs/core/symmetric_eigenvalues.hpp>
#include <adaptobs/core/validation.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string_view>
#include <vector>

namespace adaptobs {

/// What `guyader_zhang_convergence` found for one μ over a regressor sequence.
template <typename Scalar>
struct GuyaderZhangConvergence {
  Scalar mu = 0;
  /// ρ: factor by which the slowest component of θ̃ shrinks per step (above 1: θ̂ diverges).
  Scalar rate = 0;
  /// \f$-1/\ln\rho\f$: steps for θ̃ to shrink by e (infinite when ρ ≥ 1).
  Scalar time_constant = 0;
  /// \f$1/(\mu\lambda_{\min}(\bar\Phi))\f$, the averaging theory's prediction of it.
  Scalar averaged_time_constant = 0;
  /// \f$\max_k\mu\|C_k\Upsilon_k\|_2^2\f$: assumption 2 holds while it is at most 1.
  Scalar assumption2_measure = 0;
  /// Whether averaging applies: \f$\mu\|C_k\Upsilon_k\|_2^2 \le 0.1\f$ at every step,
  /// so that `averaged_time_constant` is within about 10 % of `time_constant`.
  bool averaging_holds = false;
};

namespace detail {

// Runs eq. (2a) over the regressors, from Υ_0 = 0 at `start_step`, and calls
// `visit(C_kΥ_k)` at each step before Υ moves.
template <DiscreteModel Model, class Visit>
void filtered_regressors(const Model& model, const typename Model::Dims::GainMatrix& K,
                         const std::vector<typename Model::Dims::RegressorMatrix>& regressors, Index start_step,
                         std::string_view who, Visit&& visit) {
  using Dims = typename Model::Dims;
  const Sizes s = model.sizes();
  require_finite_shape(K, s.nx, s.ny, who, "K");
  require(!regressors.empty(), who, "regressors", "must hold at least one Psi_k");
  require(start_step >= 0, who, "start_step", "must be non-negative");
  typename Dims::RegressorMatrix upsilon = Dims::RegressorMatrix::Zero(s.nx, s.np);
  typename Dims::OutputRegressor c_upsilon(s.ny, s.np);
  for (std::size_t i = 0; i < regressors.size(); ++i) {
    require_finite_shape(regressors[i], s.nx, s.np, who, "regressors");
    const auto& system = model.at(start_step + static_cast<Index>(i));
    c_upsilon.noalias() = system.C * upsilon;
    visit(c_upsilon);
    upsilon = system.A * upsilon - K * c_upsilon + regressors[i];
  }
}

}  // namespace detail

/// The largest step size μ for which assumption 2 (Guyader & Zhang 2003,
/// eq. (3)) holds at every step of the regressor sequence
/// \f$\Psi_{k_0}, \Psi_{k_0+1}, \dots\f$ (recorded or simulated, with the
/// observer's gain K): \f$1/\max_k\|C_k\Upsilon_k\|_2^2\f$. Refuses, naming
/// 'regressors', a sequence whose filtered regressor stays zero or overflows.
template <DiscreteModel Model>
[[nodiscard]] typename Model::Dims::Scalar guyader_zhang_mu_bound(
    const Model& model, const typename Model::Dims::GainMatrix& K,
    const std::vector<typename Model::Dims::RegressorMatrix>& regressors, Index start_step = 0) {
  using Scalar = typename Model::Dims::Scalar;
  constexpr std::string_view who = "guyader_zhang_mu_bound";
  Scalar largest = 0;
  detail::filtered_regressors(model, K, regressors, start_step, who,
                              [&](const auto& c_upsilon) { largest = std::max(largest, spectral_norm(c_upsilon)); });
  require(largest > Scalar(0), who, "regressors", "never reach the output (C_k Upsilon_k = 0): no mu is bounded");
  const Scalar bound = Scalar(1) / (largest * largest);
  require(std::isfinite(largest) && bound > Scalar(0), who, "regressors",
          "make C_k Upsilon_k overflow: scale the parameters so that Psi_k is of order one");
  return bound;
}

/// The convergence of θ̂ at step size `mu` over the regressor sequence (file
/// comment): the rate ρ of the parameter error's recursion, its time constant,
/// the averaging theory's prediction and whether that prediction applies.
template <DiscreteModel Model>
[[nodiscard]] GuyaderZhangConvergence<typename Model::Dims::Scalar> guyader_zhang_convergence(
    const Model& model, const typename Model::Dims::GainMatrix& K,
    const std::vector<typename Model::Dims::RegressorMatrix>& regressors, typename Model::Dims::Scalar mu,
    Index start_step = 0) {
  using Dims = typename Model::Dims;
  using Scalar = typename Dims::Scalar;
  constexpr std::string_view who = "guyader_zhang_convergence";
  require_positive(mu, who, "mu");
  const Index np = model.sizes().np;
  const typename Dims::ParameterMatrix identity = Dims::ParameterMatrix::Identity(np, np);
  typename Dims::ParameterMatrix product = identity;  // ∏(I − μΦ_k), renormalized at each step
  typename Dims::ParameterMatrix mean_phi = Dims::ParameterMatrix::Zero(np, np);
  Scalar log_growth = 0;
  GuyaderZhangConvergence<Scalar> result;
  result.mu = mu;
  detail::filtered_regressors(model, K, regressors, start_step, who, [&](const auto& c_upsilon) {
    const typename Dims::ParameterMatrix phi = c_upsilon.transpose() * c_upsilon;
    mean_phi += phi;
    result.assumption2_measure = std::max(result.assumption2_measure, mu * spectral_norm(phi));  // ‖CΥ‖² = ‖Φ‖
    product = (identity - mu * phi) * product;
    const Scalar norm = spectral_norm(product);
    if (norm > Scalar(0)) {
      log_growth += std::log(norm);
      product /= norm;
    }
  });
  const auto steps = static_cast<Scalar>(regressors.size());
  mean_phi /= steps;
  result.rate = std::exp(log_growth / steps);
  result.time_constant =
      result.rate < Scalar(1) ? Scalar(-1) / std::log(result.rate) : std::numeric_limits<Scalar>::infinity();
  const Scalar lambda_min = symmetric_eigenvalues(mean_phi).minCoeff();
  result.averaged_time_constant =
      lambda_min > Scalar(0) ? Scalar(1) / (mu * lambda_min) : std::numeric_limits<Scalar>::infinity();
  result.averaging_holds = result.assumption2_measure <= Scalar(0.1);
  require(std::isfinite(log_growth), who, "regressors",
          "make C_k Upsilon_k overflow: scale the parameters so that Psi_k is of order one");
  return result;
}

/// The step size of fastest convergence over the regressor sequence, among
/// `points` values spaced logarithmically from \f$10^{-4}\mu_{max}\f$ to the bound
/// \f$\mu_{max}\f$ of `guyader_zhang_mu_bound`, with its convergence. Below the
/// optimum the time constant grows as 1/μ (averaging); above it the steps
/// overshoot (file comment). Noise pulls the choice lower: θ̂'s variance grows with μ.
template <DiscreteModel Model>
[[nodiscard]] GuyaderZhangConvergence<typename Model::Dims::Scalar> guyader_zhang_fastest_mu(
    const Model& model, const typename Model::Dims::GainMatrix& K,
    const std::vector<typename Model::Dims::RegressorMatrix>& regressors, Index start_step = 0, int points = 25) {
  using Scalar = typename Model::Dims::Scalar;
  require(points >= 2, "guyader_zhang_fastest_mu", "points", "must be at least 2");
  const Scalar bound = guyader_zhang_mu_bound(model, K, regressors, start_step);
  GuyaderZhangConvergence<Scalar> best;
  best.time_constant = std::numeric_limits<Scalar>::infinity();
  for (int i = 0; i < points; ++i) {
    const Scalar mu = bound * std::pow(Scalar(10), Scalar(-4) * Scalar(points - 1 - i) / Scalar(points - 1));
    const auto candidate = guyader_zhang_convergence(model, K, regressors, mu, start_step);
    if (i == 0 || candidate.time_constant < best.time_constant) best = candidate;
  }
  return best;
}

}  // namespace adaptobs
