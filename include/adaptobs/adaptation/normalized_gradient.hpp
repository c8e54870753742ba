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
#include <adaptobs/core/detail/products.hpp>
#include <adaptobs/core/validation.hpp>

#include <Eigen/Core>

#include <algorithm>
#include <array>
#include <cmath>
#include <string_view>
#include <utility>

namespace adaptobs {

/// Normalized gradient adaptation (Goodwin & Sin 1984, §3.3).
template <typename S, int NP, int NZ>
class NormalizedGradient : public RegressionLaw<NormalizedGradient<S, NP, NZ>, RegressionTypes<S, NP, NZ>> {
  using Law = RegressionLaw<NormalizedGradient, RegressionTypes<S, NP, NZ>>;
  friend Law;

 public:
  using typename Law::Scalar, typename Law::Parameters, typename Law::Regressor, typename Law::Measurement,
      typename Law::MeasurementWeight;
  static constexpr std::string_view name_propose = "NormalizedGradient::propose";
  static constexpr std::string_view name_restart = "NormalizedGradient::restart";

  struct Options {
    Scalar mu = 1;      ///< step μ ∈ (0, 2)
    Scalar offset = 1;  ///< c > 0, keeps the step bounded for small φ
  };

  /// \param nz measurement count (only read when `NZ` is dynamic, where it is required).
  NormalizedGradient(Parameters p0, Options options, Index nz = NZ)
      : Law(p0.rows(), std::max<Index>(NZ == Eigen::Dynamic ? nz : NZ, 0), false), options_(options) {
    constexpr std::string_view who = "NormalizedGradient";
    require(NZ != Eigen::Dynamic || nz >= 0, who, "nz",
            "must be given (non-negative) when the measurement size is dynamic");
    require_finite(p0, who, "p0");
    require(options_.mu > Scalar(0) && options_.mu < Scalar(2), who, "mu", "must lie in (0, 2)");
    require_positive(options_.offset, who, "offset");
    innovation_.setZero(this->measurement_count());
    p_[0] = p0;
    p_[1] = std::move(p0);
  }

  [[nodiscard]] const Parameters& parameters() const noexcept { return p_[current_]; }
  [[nodiscard]] const Parameters& proposal() const noexcept { return p_[1 - current_]; }
  [[nodiscard]] const Options& options() const noexcept { return options_; }
  [[nodiscard]] Index parameter_count() const noexcept { return p_[0].rows(); }

  void commit() noexcept { current_ = 1 - current_; }

 private:
  static const MeasurementWeight* weight() noexcept { return nullptr; }

  /// One gradient step with \f$(\varphi_t, z_t)\f$; see `DiscreteAdaptationLaw`. Under partial
  /// measurements the absent columns of φ and entries of z are zeroed, so they add
  /// neither to the step nor to \f$\|\varphi_t\|_F^2\f$.
  bool step(const Regressor& phi, const Measurement& z, const MeasurementWeight& /*unweighted*/) {
    const int next = 1 - current_;
    innovation_ = z;
    detail::subtract_product(innovation_, phi.transpose(), p_[current_]);
    p_[next] = p_[current_];
    const Scalar norm2 = phi.squaredNorm();
    if (std::isfinite(norm2)) {
      innovation_ *= options_.mu / (options_.offset + norm2);
      detail::add_product(p_[next], phi, innovation_);
    } else {
      // ‖φ‖² overflows for entries beyond about 10^154 (and the factor μ/(c + ‖φ‖²)
      // would underflow): with φ = sφ̃, s a power of two near its largest entry,
      // μφe/(c + ‖φ‖²) = μφ̃(e/s)/(c/s² + ‖φ̃‖²), every factor in range.
      const Scalar s = std::ldexp(Scalar(1), std::ilogb(phi.cwiseAbs().maxCoeff()));
      const Scalar inverse = Scalar(1) / s;
      innovation_ *= inverse * options_.mu / (options_.offset * inverse * inverse + (inverse * phi).squaredNorm());
      p_[next].noalias() += (inverse * phi) * innovation_;
    }
    return detail::all_finite(p_[next]);
  }

  void restart_at(const Parameters& p0) { p_[current_] = p0; }

  Options options_;
  std::array<Parameters, 2> p_;
  int current_ = 0;  // slot of the current estimate; the other slot holds the proposal
  Measurement innovation_;
};

}  // namespace adaptobs
