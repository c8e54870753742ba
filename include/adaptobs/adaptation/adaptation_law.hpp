#pragma once
/// \file
/// What an adaptation law is: a recursive estimator of the parameters p of a
/// linear regression
/// \f[ z_t = \varphi_t^T p + v_t,\qquad z_t \in \mathbb{R}^{n_z},\; p \in \mathbb{R}^{n_p},
///     \; \varphi_t \in \mathbb{R}^{n_p \times n_z}, \f]
/// where \f$v_t\f$ is whatever the model leaves out (noise, or the vanishing
/// term \f$CF^t\tilde x_0\f$ of paper 003, eq. (16)).
///
/// An observer whose output error is linear in its unknown parameters forms
/// \f$(\varphi_t, z_t)\f$ from its filters and hands them to any law modelling
/// `AdaptationLaw`; the observer never needs to know how the gain is built.
/// The laws of this folder are
///
/// | law | update | header |
/// |---|---|---|
/// | `RecursiveLeastSquares` | paper 003, eq. (19)–(22) | `recursive_least_squares.hpp` |
/// | `CovarianceResettingRls` | paper 003, eq. (22)–(23) | `covariance_resetting.hpp` |
/// | `ExponentialForgettingRls` | exponentially weighted least squares (Suzuki et al. 1980, via paper 003 §5) | `exponential_forgetting.hpp` |
/// | `NormalizedGradient` | normalized (projection) gradient | `normalized_gradient.hpp` |
///
/// Every law is constructed as `Law(p0, options, nz)` with its own `Options`
/// aggregate, so that an observer templated on the law can build it.

#include <adaptobs/core/dimensions.hpp>
#include <adaptobs/core/validation.hpp>

#include <Eigen/Core>

#include <concepts>
#include <string_view>
#include <type_traits>

namespace adaptobs {

/// Scalar and sizes of a linear regression \f$z = \varphi^T p + v\f$ (`NP`
/// parameters, `NZ` measurements per sample), with the Eigen types that follow.
template <typename S, int NP, int NZ>
struct RegressionTypes {
  static_assert(std::is_floating_point_v<S>, "adaptobs: the scalar must be a floating-point type");
  static_assert(detail::valid_size(NP) && detail::valid_size(NZ),
                "adaptobs: sizes must be non-negative or Eigen::Dynamic");

  using Scalar = S;
  static constexpr int np = NP;
  static constexpr int nz = NZ;
  /// True when both sizes are known at compile time.
  static constexpr bool is_fixed = NP != Eigen::Dynamic && NZ != Eigen::Dynamic;

  using Parameters = Eigen::Matrix<S, NP, 1>;          ///< p
  using Regressor = Eigen::Matrix<S, NP, NZ>;          ///< φ
  using Measurement = Eigen::Matrix<S, NZ, 1>;         ///< z
  using Covariance = Eigen::Matrix<S, NP, NP>;         ///< Γ
  using MeasurementWeight = Eigen::Matrix<S, NZ, NZ>;  ///< R (the cost weighs errors with R⁻¹)
  using Gain = Eigen::Matrix<S, NP, NZ>;               ///< Γφ and its factors
};

namespace detail {

/// Throws a `ConfigurationError` naming `phi` or `z` when a sample's run-time size
/// differs from the law's (np × nz and nz), before anything is read: Eigen checks
/// `Eigen::Dynamic` sizes only by assertions, which `NDEBUG` removes.
template <class Types>
void require_regression_sizes(const typename Types::Regressor& phi, const typename Types::Measurement& z, Index np,
                              Index nz, std::string_view who) {
  if constexpr (!Types::is_fixed) {
    require_shape(phi, np, nz, who, "phi");
    require_shape(z, nz, 1, who, "z");
  }
}

}  // namespace detail

/// A recursive estimator of p from samples \f$(\varphi_t, z_t)\f$, split into
/// a proposal and a commit so that observers can compute a whole step before
/// changing anything (compute-then-commit):
///
/// - `parameters()` is the current estimate \f$\hat p_{t-1}\f$;
/// - `propose(phi, z)` computes \f$\hat p_t\f$ (and the law's own next state,
///   e.g. its covariance) into the law's scratch and returns true when every
///   number of the proposal is finite and the step was well defined; nothing
///   that `parameters()` or any other accessor shows changes;
/// - `proposal()` is the proposed \f$\hat p_t\f$;
/// - `commit()` makes the proposal current. Calling it after `propose`
///   returned false moves the unusable proposal in (NaN and ±Inf included):
///   the law then follows its recursion in plain IEEE arithmetic, which is
///   how an example records a law breaking down. Observers never do that;
/// - `restart(p0)` starts again from \f$\hat p_0\f$ and the initial gain.
template <class L>
concept AdaptationLaw = requires(L& law, const L& const_law, const typename L::Regressor& phi,
                                 const typename L::Measurement& z, const typename L::Parameters& p0) {
  typename L::Scalar;
  typename L::Parameters;
  typename L::Regressor;
  typename L::Measurement;
  typename L::Options;
  { const_law.parameters() } -> std::convertible_to<const typename L::Parameters&>;
  { law.propose(phi, z) } -> std::same_as<bool>;
  { const_law.proposal() } -> std::convertible_to<const typename L::Parameters&>;
  law.commit();
  law.restart(p0);
  { const_law.parameter_count() } -> std::convertible_to<Index>;
  { const_law.measurement_count() } -> std::convertible_to<Index>;
};

}  // namespace adaptobs
