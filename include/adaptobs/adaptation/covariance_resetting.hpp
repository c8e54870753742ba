#pragma once
/// \file
/// Recursive least squares with covariance resetting on the smallest
/// eigenvalue (Dey & Bhasin 2022, eq. (22)–(23)).
///
/// Each step computes the RLS covariance and estimate
/// \f[ \bar\Gamma_t = \Gamma_{t-1} - \Gamma_{t-1}\varphi_tW_t\varphi_t^T\Gamma_{t-1},\qquad
///     \hat p_t = \hat p_{t-1} + \Gamma_{t-1}\varphi_tW_t(z_t - \varphi_t^T\hat p_{t-1}),\qquad
///     W_t = (R + \varphi_t^T\Gamma_{t-1}\varphi_t)^{-1}, \f]
/// then resets (23)
/// \f[ \Gamma_t = \begin{cases} k_0 I & \text{if } \lambda_{\min}(\bar\Gamma_t) \le k_{\min}, \\ \bar\Gamma_t & \text{otherwise,}\end{cases} \f]
/// so that \f$k_{\min} I \prec \Gamma_t \preceq k_0 I\f$ at every step: the gain can
/// neither wind up nor die out, and the estimates stay bounded without any
/// excitation (theorem 5). \f$\Gamma_0 = k_0 I\f$.
///
/// Readings of the paper:
/// - the first line of (23), like (21), ends in \f$\Gamma_{t-1}^{-1}\f$ in the
///   extracted text; the trailing factor is \f$\Gamma_{t-1}\f$ (see
///   `recursive_least_squares.hpp`);
/// - (20) and (22) agree only at steps without a reset; the estimate uses (22),
///   i.e. the gain of step t is built from the post-reset \f$\Gamma_{t-1}\f$.
///
/// The reset test. \f$\lambda_{\min}(\bar\Gamma) > k_{\min}\f$ holds exactly when
/// \f$\bar\Gamma - k_{\min}I\f$ has a Cholesky factorization, which costs
/// \f$n_p^3/6\f$ multiply-adds against about \f$9n_p^3\f$ for a symmetric
/// eigendecomposition (\f$\tfrac43 n_p^3\f$ for eigenvalues only); a pivot
/// \f$\le 0\f$ counts as a reset, as the "≤" of (23) asks. The factorization is
/// moreover skipped when a bound proves that no reset is possible: from
/// \f$\bar\Gamma^{-1} = \Gamma^{-1} + \varphi R^{-1}\varphi^T\f$,
/// \f[ \lambda_{\min}(\bar\Gamma_t) \ge \ell_t = \Big(\frac1{\ell_{t-1}} + \frac{\|\varphi_t\|_F^2}{\lambda_{\min}(R)}\Big)^{-1} - \eta,
///     \qquad \ell = k_0 \text{ after a reset}, \f]
/// where \f$\eta = 8(n_p + n_z)\varepsilon k_0\f$ covers the rounding of one step
/// (\f$\|\bar\Gamma\| \le k_0\f$). While \f$\ell_t > k_{\min}\f$ the factorization
/// is not needed: the decision is the same, at \f$O(n_pn_z)\f$ cost.
///
/// Numerics: \f$k_{\min} < \lambda(\Gamma) \le k_0\f$ bounds the condition number
/// of Γ by \f$k_0/k_{\min}\f$ (1e7 in the paper's examples), and the rounding
/// of \f$\bar\Gamma\f$, about \f$n_p\varepsilon k_0\f$, stays far below
/// \f$k_{\min}\f$ in double precision, so a reset fires long before rounding
/// could make Γ indefinite. In single precision choose \f$k_0/k_{\min}\f$
/// accordingly (about 1e4 at most).

#include <adaptobs/adaptation/adaptation_law.hpp>
#include <adaptobs/adaptation/recursive_least_squares.hpp>
#include <adaptobs/adaptation/rls_correction.hpp>
#include <adaptobs/core/detail/commit.hpp>
#include <adaptobs/core/validation.hpp>

#include <Eigen/Core>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string_view>
#include <utility>

namespace adaptobs {

/// \f$\lambda_{\min}(\Gamma) > \text{bound}\f$ for a symmetric Γ (lower triangle
/// read), decided exactly by a Cholesky factorization of \f$\Gamma - \text{bound}\,I\f$;
/// false for a Γ with non-finite entries.
template <class Derived>
[[nodiscard]] bool smallest_eigenvalue_exceeds(const Eigen::MatrixBase<Derived>& gamma,
                                               typename Derived::Scalar bound) {
  if (!gamma.derived().allFinite()) return false;
  typename Derived::PlainObject shifted = gamma;
  shifted.diagonal().array() -= bound;
  return detail::cholesky_in_place(shifted);
}

/// RLS with covariance resetting, eq. (22)–(23) of Dey & Bhasin (2022).
template <typename S, int NP, int NZ>
class CovarianceResettingRls : public LeastSquaresLaw<CovarianceResettingRls<S, NP, NZ>, S, NP, NZ> {
  using Base = LeastSquaresLaw<CovarianceResettingRls, S, NP, NZ>;
  friend typename Base::Interface;

 public:
  using typename Base::Scalar, typename Base::Parameters, typename Base::Regressor, typename Base::Measurement,
      typename Base::Covariance, typename Base::MeasurementWeight;
  static constexpr std::string_view name_propose = "CovarianceResettingRls::propose";
  static constexpr std::string_view name_restart = "CovarianceResettingRls::restart";

  struct Options {
    Scalar k0;            ///< \f$\Gamma_0 = k_0I\f$ and the reset value, > kmin
    Scalar kmin;          ///< reset threshold on \f$\lambda_{\min}(\bar\Gamma)\f$, > 0
    MeasurementWeight R;  ///< weight of the output error, symmetric positive definite
    /// Skip the Cholesky test when the eigenvalue bound \f$\ell_t\f$ already
    /// excludes a reset (same decisions, lower cost).
    bool screen_reset_test = true;
  };

  /// \param nz measurement count, read only when `NZ` is dynamic (default: the size of R).
  CovarianceResettingRls(Parameters p0, Options options, Index nz = NZ)
      : Base(p0.rows(), detail::measurement_size<NZ>(nz, options.R)),
        options_(std::move(options)),
        correction_(p0.rows(), this->nz_) {
    constexpr std::string_view who = "CovarianceResettingRls";
    nz = this->measurement_count();  // the resolved size
    require_finite(p0, who, "p0");
    require_positive(options_.k0, who, "k0");
    require_positive(options_.kmin, who, "kmin");
    require(options_.kmin < options_.k0, who, "kmin", "must be smaller than k0");
    require_shape(options_.R, nz, nz, who, "R");
    require_positive_definite(options_.R, who, "R");
    const Index np = p0.rows();
    if (nz > 0) {
      // Configuration time, on a dynamic copy: one instantiation per scalar type.
      using Dense = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;
      inverse_weight_bound_ = Scalar(1) / symmetric_eigenvalues(Dense(options_.R))(0);
    }
    rounding_margin_ = Scalar(8) * Scalar(np + nz) * std::numeric_limits<Scalar>::epsilon() * options_.k0;
    shifted_.setZero(np, np);
    this->assign(p0, Covariance::Zero(np, np), Covariance::Zero(np, np));
    start();
  }

  /// Number of resets since construction or the last restart.
  [[nodiscard]] Index reset_count() const noexcept { return track_[this->current_slot()].resets; }
  /// True when the last committed step reset the covariance.
  [[nodiscard]] bool reset_at_last_step() const noexcept { return track_[this->current_slot()].reset_last; }
  /// Number of Cholesky reset tests run (the others were settled by the bound \f$\ell_t\f$).
  [[nodiscard]] Index reset_tests_run() const noexcept { return track_[this->current_slot()].tests; }
  /// The bound \f$\ell\f$: \f$\lambda_{\min}(\Gamma) \ge \ell\f$ holds for the current covariance.
  [[nodiscard]] Scalar eigenvalue_lower_bound() const noexcept { return track_[this->current_slot()].bound; }
  [[nodiscard]] const Options& options() const noexcept { return options_; }

  /// Its fields for `snapshot` and `restore` (core/snapshot.hpp): the estimate,
  /// the options, and the reset counters of both slots.
  template <class Self, class Archive>
  static void visit_state(Self& self, Archive& archive) {
    Base::Estimate::visit_estimate_state(self, archive);
    archive("k0", self.options_.k0);
    archive("kmin", self.options_.kmin);
    archive("R", self.options_.R);
    archive("screen_reset_test", self.options_.screen_reset_test);
    for (std::size_t i = 0; i < self.track_.size(); ++i) {
      auto track = archive.nested(detail::element_name("track", i));
      track("resets", self.track_[i].resets);
      track("tests", self.track_[i].tests);
      track("reset_last", self.track_[i].reset_last);
      track("bound", self.track_[i].bound);
    }
    archive("inverse_weight_bound", self.inverse_weight_bound_);
    archive("rounding_margin", self.rounding_margin_);
  }

 private:
  const MeasurementWeight* weight() const noexcept { return &options_.R; }

  /// (22), then (23), with \f$(\varphi_t, z_t)\f$ and weight R; see `DiscreteAdaptationLaw`.
  /// Under partial measurements the reset screen stays valid: with the absent
  /// columns of φ zeroed, \f$\varphi\bar R^{-1}\varphi^T\f$ involves only \f$R_{PP}^{-1}\f$, whose
  /// largest eigenvalue is at most \f$1/\lambda_{\min}(R)\f$ (interlacing).
  bool step(const Regressor& phi, const Measurement& z, const MeasurementWeight& weight) {
    const Tracking& current = track_[this->current_slot()];
    Tracking& track = track_[1 - this->current_slot()];
    track = current;
    track.reset_last = false;
    Covariance& next_gamma = this->next_covariance();
    if (!correction_.apply(this->covariance(), weight, phi, z, this->parameters(), Scalar(1), this->next_parameters(),
                           next_gamma))
      return false;
    if (!detail::all_finite(this->next_parameters(), next_gamma)) return false;

    Scalar bound = -std::numeric_limits<Scalar>::infinity();
    if (options_.screen_reset_test && current.bound > Scalar(0))
      bound = Scalar(1) / (Scalar(1) / current.bound + inverse_weight_bound_ * phi.squaredNorm()) - rounding_margin_;
    if (bound > options_.kmin) {
      track.bound = bound;
      return true;
    }
    ++track.tests;
    shifted_ = next_gamma;
    shifted_.diagonal().array() -= options_.kmin;
    if (detail::cholesky_in_place(shifted_)) {
      track.bound = std::max(bound, std::max(options_.kmin - rounding_margin_, Scalar(0)));
      return true;
    }
    next_gamma.setIdentity();
    next_gamma.diagonal().setConstant(options_.k0);
    track.bound = options_.k0;
    track.reset_last = true;
    ++track.resets;
    return true;
  }

  /// Back to \f$\hat p_0\f$ and \f$\Gamma_0 = k_0I\f$, counters cleared.
  void restart_at(const Parameters& p0) {
    this->current_parameters() = p0;
    start();
  }

  void start() {
    const Index np = this->parameter_count();
    this->current_covariance().setZero(np, np);
    this->current_covariance().diagonal().setConstant(options_.k0);
    track_[this->current_slot()] = Tracking{0, 0, false, options_.k0};
  }

  struct Tracking {
    Index resets = 0;
    Index tests = 0;
    bool reset_last = false;
    Scalar bound = 0;  // ℓ: a lower bound on λ_min(Γ)
  };

  Options options_;
  std::array<Tracking, 2> track_{};  // per slot of the estimate
  Scalar inverse_weight_bound_ = 0;  // λ_max(R⁻¹) = 1/λ_min(R)
  Scalar rounding_margin_ = 0;       // η
  Covariance shifted_;               // Γ̄ − kmin I, factored in place by the reset test
  detail::RlsCorrection<S, NP, NZ> correction_;
};

}  // namespace adaptobs
