#pragma once
/// \file
/// Recursive least squares (Dey & Bhasin 2022, eq. (17)–(22)).
///
/// Minimizes the cost (17)
/// \f[ J_t(\hat p) = \tfrac12\Big[\sum_{i=1}^t (z_i - \varphi_i^T\hat p)^T R^{-1}(z_i - \varphi_i^T\hat p)
///     + (\hat p - \hat p_0)^T\Gamma_0^{-1}(\hat p - \hat p_0)\Big], \f]
/// whose minimizer is the batch solution (18)
/// \f$\hat p_t = \Gamma_t(\Gamma_0^{-1}\hat p_0 + \sum_{i=1}^t\varphi_iR^{-1}z_i)\f$ with
/// \f$\Gamma_t^{-1} = \Gamma_0^{-1} + \sum_{i=1}^t\varphi_iR^{-1}\varphi_i^T\f$ (19). Recursively,
/// with \f$W_{t+1} = (R + \varphi_{t+1}^T\Gamma_t\varphi_{t+1})^{-1}\f$,
/// \f[ \hat p_{t+1} = \hat p_t + \Gamma_t\varphi_{t+1}W_{t+1}(z_{t+1} - \varphi_{t+1}^T\hat p_t) \quad (22),\qquad
///     \Gamma_{t+1} = \Gamma_t - \Gamma_t\varphi_{t+1}W_{t+1}\varphi_{t+1}^T\Gamma_t \quad (21). \f]
///
/// Reading of the paper: the extracted text of (21) ends in \f$\Gamma_t^{-1}\f$.
/// That form is not symmetric and does not satisfy (19); the matrix inversion
/// lemma applied to (19) gives the trailing \f$\Gamma_t\f$ used here (a test
/// checks (19) and the batch solution (18) against this recursion).

#include <adaptobs/adaptation/adaptation_law.hpp>
#include <adaptobs/adaptation/rls_correction.hpp>
#include <adaptobs/core/detail/commit.hpp>
#include <adaptobs/core/validation.hpp>

#include <Eigen/Core>

#include <string_view>
#include <utility>

namespace adaptobs {

namespace detail {

/// Measurement count of a law: the fixed size, else the given one, else the size of R.
template <int NZ, class Weight>
Index measurement_size(Index nz, const Weight& weight) {
  if constexpr (NZ != Eigen::Dynamic) return NZ;
  return nz >= 0 ? nz : weight.rows();
}

/// Checks shared by the least-squares laws: p0 finite, Γ0 and R symmetric positive definite.
template <class P, class G, class W>
void validate_least_squares(const P& p0, const G& gamma0, const W& weight, Index nz, std::string_view who) {
  require_finite(p0, who, "p0");
  require_shape(gamma0, p0.rows(), p0.rows(), who, "gamma0");
  require_positive_definite(gamma0, who, "gamma0");
  require_shape(weight, nz, nz, who, "R");
  require_positive_definite(weight, who, "R");
}

}  // namespace detail

/// Plain recursive least squares, eq. (20)–(22) of Dey & Bhasin (2022).
template <typename S, int NP, int NZ>
class RecursiveLeastSquares : public LeastSquaresLaw<RecursiveLeastSquares<S, NP, NZ>, S, NP, NZ> {
  using Base = LeastSquaresLaw<RecursiveLeastSquares, S, NP, NZ>;
  friend typename Base::Interface;

 public:
  using typename Base::Parameters, typename Base::Regressor, typename Base::Measurement, typename Base::Covariance,
      typename Base::MeasurementWeight;
  static constexpr std::string_view name_propose = "RecursiveLeastSquares::propose";
  static constexpr std::string_view name_restart = "RecursiveLeastSquares::restart";

  struct Options {
    Covariance gamma0;    ///< \f$\Gamma_0\f$, symmetric positive definite
    MeasurementWeight R;  ///< \f$R\f$, symmetric positive definite
  };

  /// \param nz measurement count, read only when `NZ` is dynamic (default: the size of R).
  RecursiveLeastSquares(Parameters p0, Options options, Index nz = NZ)
      : Base(p0.rows(), detail::measurement_size<NZ>(nz, options.R)),
        options_(std::move(options)),
        correction_(p0.rows(), this->nz_) {
    detail::validate_least_squares(p0, options_.gamma0, options_.R, this->nz_, "RecursiveLeastSquares");
    this->assign(p0, options_.gamma0, options_.gamma0);
  }

  [[nodiscard]] const Options& options() const noexcept { return options_; }

 private:
  const MeasurementWeight* weight() const noexcept { return &options_.R; }

  /// (22) and (21) with \f$(\varphi_t, z_t)\f$ and weight R; see `DiscreteAdaptationLaw`.
  bool step(const Regressor& phi, const Measurement& z, const MeasurementWeight& weight) {
    if (!correction_.apply(this->covariance(), weight, phi, z, this->parameters(), S(1), this->next_parameters(),
                           this->next_covariance()))
      return false;
    return detail::all_finite(this->next_parameters(), this->next_covariance());
  }

  void restart_at(const Parameters& p0) {
    this->current_parameters() = p0;
    this->current_covariance() = options_.gamma0;
  }

  Options options_;
  detail::RlsCorrection<S, NP, NZ> correction_;
};

}  // namespace adaptobs
