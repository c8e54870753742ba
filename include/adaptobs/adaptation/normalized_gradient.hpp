#pragma once
/// \file
/// Normalized gradient (the "projection algorithm" of Goodwin & Sin 1984,
/// §3.3, the reference Dey & Bhasin (2022) cites for its RLS):
/// \f[ \hat p_t = \hat p_{t-1} + \mu\,\frac{\varphi_t(z_t - \varphi_t^T\hat p_{t-1})}{c + \|\varphi_t\|_F^2},
///     \qquad 0 < \mu < 2,\; c > 0. \f]
/// Without perturbation the error obeys
/// \f$\tilde p_t = (I - \mu\varphi_t\varphi_t^T/(c + \|\varphi_t\|_F^2))\tilde p_{t-1}\f$, whose
/// matrix has eigenvalues in \f$(1 - \mu, 1]\f$: \f$\|\tilde p_t\|\f$ never grows,
/// whatever the excitation, at a cost of \f$2n_pn_z\f$ per step and no
/// covariance — but it converges much more slowly than least squares when the
/// regressor is poorly conditioned.

#include <adaptobs/adaptation/adaptation_law.hpp>
#include <adaptobs/core/detail/commit.hpp>
#include <adaptobs/core/validation.hpp>

#include <Eigen/Core>

#include <algorithm>
#include <array>
#include <string_view>
#include <utility>

namespace adaptobs {

/// Normalized gradient adaptation (Goodwin & Sin 1984, §3.3).
template <typename S, int NP, int NZ>
class NormalizedGradient {
 public:
  using Types = RegressionTypes<S, NP, NZ>;
  using Scalar = S;
  using Parameters = typename Types::Parameters;
  using Regressor = typename Types::Regressor;
  using Measurement = typename Types::Measurement;
  using Presence = typename Types::Presence;

  struct Options {
    Scalar mu = 1;      ///< step μ ∈ (0, 2)
    Scalar offset = 1;  ///< c > 0, keeps the step bounded for small φ
  };

  /// \param nz measurement count (only read when `NZ` is dynamic, where it is required).
  NormalizedGradient(Parameters p0, Options options, Index nz = NZ)
      : options_(options), nz_(NZ == Eigen::Dynamic ? nz : NZ), masked_(p0.rows(), std::max<Index>(nz_, 0), false) {
    constexpr std::string_view who = "NormalizedGradient";
    detail::require(nz_ >= 0, who, "nz", "must be given (non-negative) when the measurement size is dynamic");
    detail::require_finite(p0, who, "p0");
    detail::require(options_.mu > Scalar(0) && options_.mu < Scalar(2), who, "mu", "must lie in (0, 2)");
    detail::require_positive(options_.offset, who, "offset");
    innovation_.setZero(nz_);
    p_[0] = p0;
    p_[1] = std::move(p0);
  }

  [[nodiscard]] const Parameters& parameters() const noexcept { return p_[current_]; }
  [[nodiscard]] const Parameters& proposal() const noexcept { return p_[1 - current_]; }
  [[nodiscard]] const Options& options() const noexcept { return options_; }
  [[nodiscard]] Index parameter_count() const noexcept { return p_[0].rows(); }
  [[nodiscard]] Index measurement_count() const noexcept { return nz_; }

  /// One gradient step with \f$(\varphi_t, z_t)\f$; see `AdaptationLaw`.
  [[nodiscard]] bool propose(const Regressor& phi, const Measurement& z) {
    detail::require_regression_sizes<Types>(phi, z, parameter_count(), nz_, "NormalizedGradient::propose");
    return step(phi, z);
  }

  /// One gradient step with the present entries of \f$z_t\f$ only (absent columns of φ
  /// and entries of z zeroed, so they add neither to the step nor to \f$\|\varphi_t\|_F^2\f$);
  /// see `AdaptationLaw`, "Partial measurements".
  [[nodiscard]] bool propose(const Regressor& phi, const Measurement& z, const Presence& present) {
    return masked_.propose(phi, z, present, nullptr, parameter_count(), "NormalizedGradient::propose",
                           [this](const auto& f, const auto& y, const auto&) { return step(f, y); });
  }

  void commit() noexcept { current_ = 1 - current_; }

  void restart(const Parameters& p0) {
    detail::require_shape(p0, parameter_count(), 1, "NormalizedGradient::restart", "p0");
    detail::require_finite(p0, "NormalizedGradient::restart", "p0");
    p_[current_] = p0;
  }

 private:
  bool step(const Regressor& phi, const Measurement& z) {
    const int next = 1 - current_;
    innovation_ = z;
    innovation_.noalias() -= phi.transpose() * p_[current_];
    innovation_ *= options_.mu / (options_.offset + phi.squaredNorm());
    p_[next] = p_[current_];
    p_[next].noalias() += phi * innovation_;
    return detail::all_finite(p_[next]);
  }

  Options options_;
  Index nz_;
  std::array<Parameters, 2> p_;
  int current_ = 0;  // slot of the current estimate; the other slot holds the proposal
  Measurement innovation_;
  detail::MaskedRegression<Types> masked_;
};

}  // namespace adaptobs
