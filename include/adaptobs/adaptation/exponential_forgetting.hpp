#pragma once
/// \file
/// Recursive least squares with exponential forgetting: the adaptation law of
/// the discrete adaptive observer of Suzuki, Nakamura & Koga (1980), the
/// baseline of Dey & Bhasin (2022) §5.
///
/// Minimizes the exponentially weighted cost
/// \f[ J_t(\hat p) = \tfrac12\Big[\sum_{i=1}^t\lambda^{t-i}(z_i - \varphi_i^T\hat p)^TR^{-1}(z_i - \varphi_i^T\hat p)
///     + \lambda^t(\hat p - \hat p_0)^T\Gamma_0^{-1}(\hat p - \hat p_0)\Big],\qquad 0 < \lambda \le 1, \f]
/// i.e. \f$\Gamma_t^{-1} = \lambda\Gamma_{t-1}^{-1} + \varphi_tR^{-1}\varphi_t^T\f$, recursively
/// \f[ W_t = (\lambda R + \varphi_t^T\Gamma_{t-1}\varphi_t)^{-1},\qquad
///     \hat p_t = \hat p_{t-1} + \Gamma_{t-1}\varphi_tW_t(z_t - \varphi_t^T\hat p_{t-1}),\qquad
///     \Gamma_t = \tfrac1\lambda\big(\Gamma_{t-1} - \Gamma_{t-1}\varphi_tW_t\varphi_t^T\Gamma_{t-1}\big). \f]
/// λ = 1 is plain RLS.
///
/// Reading: Dey & Bhasin (2022) gives Suzuki's "weighting factor" as \f$\sqrt{0.5}\f$ and
/// not the cost it enters. It is taken here as λ itself, the multiplier of the
/// past cost (Ljung's forgetting factor, Goodwin & Sin's exponential data
/// weighting); a convention where the weight enters squared would mean
/// λ = 0.5. Both forget within a few samples and fail the same way.
///
/// Without persistent excitation this law winds up: in the directions φ does
/// not reach, \f$\Gamma^{-1}\f$ decays as \f$\lambda^t\f$ and Γ grows as
/// \f$\lambda^{-t}\f$ (×1.414 per step for \f$\lambda = \sqrt{0.5}\f$) until it
/// overflows. From that step on `propose` returns false (the observer reports
/// `nonfinite_result` and keeps its last finite estimates); `covariance()`
/// shows the growth before it.
///
/// Numerics. Long before it overflows, the wound-up Γ stops being positive
/// definite in floating point (in the SISO example of Dey & Bhasin (2022) §5: from
/// step 96, with max|Γ| = 3e12), and \f$\lambda R + \varphi^T\Gamma\varphi\f$ can turn
/// negative (step 108). The law is therefore computed in its textbook gain
/// form, which assumes no definiteness: \f$K = \Gamma\varphi M^{-1}\f$ with M
/// factored by LDLᵀ, \f$\Gamma^+ = (\Gamma - K(\Gamma\varphi)^T)/\lambda\f$ with the lower
/// triangle mirrored; it then fails the way the literature reports, by
/// overflow, and not by a failed square root. The least-squares laws that
/// keep Γ bounded (`RecursiveLeastSquares`, `CovarianceResettingRls`) use
/// the square-root form of `rls_correction.hpp` instead.

#include <adaptobs/adaptation/adaptation_law.hpp>
#include <adaptobs/adaptation/recursive_least_squares.hpp>
#include <adaptobs/adaptation/rls_correction.hpp>
#include <adaptobs/core/detail/commit.hpp>
#include <adaptobs/core/detail/products.hpp>
#include <adaptobs/core/validation.hpp>

#include <Eigen/Cholesky>
#include <Eigen/Core>

#include <cmath>
#include <limits>
#include <string_view>
#include <utility>

namespace adaptobs {

/// RLS with exponential forgetting (Suzuki et al. 1980; Dey & Bhasin 2022, §5).
template <typename S, int NP, int NZ>
class ExponentialForgettingRls : public LeastSquaresLaw<ExponentialForgettingRls<S, NP, NZ>, S, NP, NZ> {
  using Base = LeastSquaresLaw<ExponentialForgettingRls, S, NP, NZ>;
  friend typename Base::Interface;

 public:
  using typename Base::Scalar, typename Base::Parameters, typename Base::Regressor, typename Base::Measurement,
      typename Base::Covariance, typename Base::MeasurementWeight;
  static constexpr std::string_view name_propose = "ExponentialForgettingRls::propose";
  static constexpr std::string_view name_restart = "ExponentialForgettingRls::restart";

  struct Options {
    Covariance gamma0;    ///< \f$\Gamma_0\f$, symmetric positive definite
    MeasurementWeight R;  ///< \f$R\f$, symmetric positive definite
    Scalar lambda;        ///< forgetting factor λ ∈ (0, 1]
  };

  /// \param nz measurement count, read only when `NZ` is dynamic (default: the size of R).
  ExponentialForgettingRls(Parameters p0, Options options, Index nz = NZ)
      : Base(p0.rows(), detail::measurement_size<NZ>(nz, options.R)),
        options_(std::move(options)),
        factorization_(this->nz_) {
    constexpr std::string_view who = "ExponentialForgettingRls";
    nz = this->measurement_count();  // the resolved size
    detail::validate_least_squares(p0, options_.gamma0, options_.R, nz, who);
    require(options_.lambda > Scalar(0) && options_.lambda <= Scalar(1), who, "lambda", "must lie in (0, 1]");
    weight_ = options_.lambda * options_.R;
    gamma_phi_.setZero(p0.rows(), nz);
    gain_transposed_.setZero(nz, p0.rows());
    innovation_weight_.setZero(nz, nz);
    innovation_.setZero(nz);
    this->assign(p0, options_.gamma0, options_.gamma0);
  }

  [[nodiscard]] const Options& options() const noexcept { return options_; }

  /// Its fields for `snapshot` and `restore` (core/snapshot.hpp): the estimate and the options.
  template <class Self, class Archive>
  static void visit_state(Self& self, Archive& archive) {
    Base::Estimate::visit_estimate_state(self, archive);
    archive("gamma0", self.options_.gamma0);
    archive("R", self.options_.R);
    archive("lambda", self.options_.lambda);
    archive("weight", self.weight_);
  }

 private:
  const MeasurementWeight* weight() const noexcept { return &weight_; }

  /// One weighted step with \f$(\varphi_t, z_t)\f$ and weight λR (or its masked form);
  /// see `DiscreteAdaptationLaw`. Forgetting is per call, measured or not: with no entry
  /// present, Γ is divided by λ. (An observer may skip the call on a sample without
  /// data; Dey–Bhasin and Suzuki do, so Γ does not grow over a gap.)
  bool step(const Regressor& phi, const Measurement& z, const MeasurementWeight& weight) {
    const Covariance& gamma = this->covariance();
    Parameters& next_p = this->next_parameters();
    Covariance& next_gamma = this->next_covariance();
    detail::set_product(gamma_phi_, gamma, phi);
    innovation_weight_ = weight;
    detail::add_product(innovation_weight_, phi.transpose(), gamma_phi_);
    factorization_.compute(innovation_weight_);
    // A singular or non-finite M leaves no gain (the factorization would quietly
    // zero it): the step breaks down, and its proposal says so with NaN.
    if (factorization_.info() != Eigen::Success || !(factorization_.vectorD().array().abs() > Scalar(0)).all()) {
      next_p.setConstant(std::numeric_limits<Scalar>::quiet_NaN());
      next_gamma.setConstant(std::numeric_limits<Scalar>::quiet_NaN());
      return false;
    }
    gain_transposed_ = gamma_phi_.transpose();
    factorization_.solveInPlace(gain_transposed_);  // Kᵀ = M⁻¹(Γφ)ᵀ
    innovation_ = z;
    detail::subtract_product(innovation_, phi.transpose(), this->parameters());
    next_p = this->parameters();
    detail::add_product(next_p, gain_transposed_.transpose(), innovation_);
    next_gamma = gamma;
    detail::subtract_product(next_gamma, gain_transposed_.transpose(), gamma_phi_.transpose());
    next_gamma *= Scalar(1) / options_.lambda;
    detail::mirror_lower_triangle(next_gamma);
    return detail::all_finite(next_p, next_gamma);
  }

  void restart_at(const Parameters& p0) {
    this->current_parameters() = p0;
    this->current_covariance() = options_.gamma0;
  }

  Options options_;
  MeasurementWeight weight_;                      // λR
  typename Base::Types::Gain gamma_phi_;          // Γφ
  Eigen::Matrix<S, NZ, NP> gain_transposed_;      // Kᵀ
  MeasurementWeight innovation_weight_;           // M = λR + φᵀΓφ
  Eigen::LDLT<MeasurementWeight> factorization_;  // of M, which need not be positive definite
  Measurement innovation_;
};

}  // namespace adaptobs
