#pragma once
/// \file
/// What an adaptation law is: a recursive estimator of the parameters p of a
/// linear regression
/// \f[ z_t = \varphi_t^T p + v_t,\qquad z_t \in \mathbb{R}^{n_z},\; p \in \mathbb{R}^{n_p},
///     \; \varphi_t \in \mathbb{R}^{n_p \times n_z}, \f]
/// where \f$v_t\f$ is whatever the model leaves out (noise, or the vanishing
/// term \f$CF^t\tilde x_0\f$ of Dey & Bhasin (2022), eq. (16)).
///
/// An observer whose output error is linear in its unknown parameters forms
/// \f$(\varphi_t, z_t)\f$ from its filters and hands them to any law modelling
/// `DiscreteAdaptationLaw`; the observer never needs to know how the gain is built.
/// The laws of this folder are
///
/// | law | update | header |
/// |---|---|---|
/// | `RecursiveLeastSquares` | Dey & Bhasin (2022), eq. (19)–(22) | `recursive_least_squares.hpp` |
/// | `CovarianceResettingRls` | Dey & Bhasin (2022), eq. (22)–(23) | `covariance_resetting.hpp` |
/// | `ExponentialForgettingRls` | exponentially weighted least squares (Suzuki et al. 1980, via Dey & Bhasin (2022) §5) | `exponential_forgetting.hpp` |
/// | `NormalizedGradient` | normalized (projection) gradient | `normalized_gradient.hpp` |
///
/// Every law is constructed as `Law(p0, options, nz)` with its own `Options`
/// aggregate, so that an observer templated on the law can build it.

#include <adaptobs/core/dimensions.hpp>
#include <adaptobs/core/validation.hpp>

#include <Eigen/Core>

#include <array>
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
  using Presence = Eigen::Array<bool, NZ, 1>;          ///< which entries of z were measured
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

/// Throws a `ConfigurationError` naming `present` when a run-time-sized presence
/// mask does not have nz entries.
template <class Types>
void require_presence_size(const typename Types::Presence& present, Index nz, std::string_view who) {
  if constexpr (Types::nz == Eigen::Dynamic) require(present.size() == nz, who, "present", "must have nz entries");
}

/// The regression of the measured entries only, kept at full size (see
/// `DiscreteAdaptationLaw`, "Partial measurements"): the columns of φ and the entries of z
/// of absent measurements are zero, and the weight is
/// \f$\bar R = DRD + (I - D)\f$, \f$D = \mathrm{diag}(\text{present})\f$ — R on the measured
/// block, the identity on the absent one.
template <class Types>
struct MaskedRegression {
  typename Types::Regressor phi;
  typename Types::Measurement z;
  typename Types::MeasurementWeight weight;

  MaskedRegression(Index np, Index nz, bool weighted) {
    phi.setZero(np, nz);
    z.setZero(nz);
    if (weighted) weight.setZero(nz, nz);
  }

  /// φ and z with their absent columns and entries zeroed (absent entries of z may be NaN).
  void assign(const typename Types::Regressor& phi_in, const typename Types::Measurement& z_in,
              const typename Types::Presence& present) {
    phi = phi_in;
    z = z_in;
    for (Index j = 0; j < present.size(); ++j)
      if (!present(j)) {
        phi.col(j).setZero();
        z(j) = 0;
      }
  }

  /// \f$\bar R\f$ from R.
  void assign_weight(const typename Types::MeasurementWeight& R, const typename Types::Presence& present) {
    weight = R;
    for (Index j = 0; j < present.size(); ++j)
      if (!present(j)) {
        weight.row(j).setZero();
        weight.col(j).setZero();
        weight(j, j) = 1;
      }
  }

  /// `propose(phi, z, present)` of a law: checks the sizes, then calls
  /// `step(phi, z, R)` on the regression itself when every entry is present,
  /// else on its masked copy with \f$\bar R\f$ (`R` null: an unweighted law, whose
  /// step ignores its third argument).
  template <class Step>
  bool propose(const typename Types::Regressor& phi_in, const typename Types::Measurement& z_in,
               const typename Types::Presence& present, const typename Types::MeasurementWeight* R, Index np,
               std::string_view who, Step&& step) {
    require_regression_sizes<Types>(phi_in, z_in, np, z.size(), who);
    require_presence_size<Types>(present, z.size(), who);
    if (present.all()) return step(phi_in, z_in, R ? *R : weight);
    assign(phi_in, z_in, present);
    if (R) assign_weight(*R, present);
    return step(phi, z, weight);
  }
};

}  // namespace detail

/// The estimate \f$(\hat p, \Gamma)\f$ of a least-squares law, current and proposed,
/// with the accessors `DiscreteAdaptationLaw` asks for: a step writes the proposal,
/// `commit` makes it current by flipping an index (no copy), so a rejected
/// proposal costs nothing to discard.
template <class Parameters, class Covariance>
class LeastSquaresEstimate {
 public:
  /// Estimate \f$\hat p_{t-1}\f$.
  [[nodiscard]] const Parameters& parameters() const noexcept { return p_[current_]; }
  /// Covariance \f$\Gamma_{t-1}\f$.
  [[nodiscard]] const Covariance& covariance() const noexcept { return gamma_[current_]; }
  [[nodiscard]] const Parameters& proposal() const noexcept { return p_[1 - current_]; }
  [[nodiscard]] const Covariance& proposed_covariance() const noexcept { return gamma_[1 - current_]; }
  [[nodiscard]] Index parameter_count() const noexcept { return p_[0].rows(); }
  void commit() noexcept { current_ = 1 - current_; }

 protected:
  /// Both slots to \f$(\hat p, \Gamma_{\text{current}})\f$ and \f$(\hat p, \Gamma_{\text{proposed}})\f$.
  void assign(const Parameters& p, const Covariance& gamma, const Covariance& proposed_gamma) {
    p_[0] = p;
    p_[1] = p;
    gamma_[current_] = gamma;
    gamma_[1 - current_] = proposed_gamma;
  }
  Parameters& current_parameters() noexcept { return p_[current_]; }
  Covariance& current_covariance() noexcept { return gamma_[current_]; }
  Parameters& next_parameters() noexcept { return p_[1 - current_]; }
  Covariance& next_covariance() noexcept { return gamma_[1 - current_]; }
  /// 0 or 1: lets a law keep more per-slot state beside the estimate.
  [[nodiscard]] int current_slot() const noexcept { return current_; }

  /// The estimate's part of a law's `visit_state` (core/snapshot.hpp): both
  /// slots of p̂ and Γ, and which one is current.
  template <class Self, class Archive>
  static void visit_estimate_state(Self& self, Archive& archive) {
    archive("p[0]", self.p_[0]);
    archive("p[1]", self.p_[1]);
    archive("gamma[0]", self.gamma_[0]);
    archive("gamma[1]", self.gamma_[1]);
    archive("current", self.current_);
    if constexpr (Archive::reading)
      require(self.current_ == 0 || self.current_ == 1, "restore", "snapshot",
              "holds a current slot other than 0 or 1");
  }

 private:
  std::array<Parameters, 2> p_;
  std::array<Covariance, 2> gamma_;
  int current_ = 0;
};

/// Base of the adaptation laws of this folder (CRTP), not used on its own: what
/// they share, written once — the regression types, the size-checked
/// `propose(phi, z)`, its masked form, `restart` and the measurement count. A law
/// `L` supplies
/// - `L::name_propose` and `L::name_restart`, the names its error messages give;
/// - `step(phi, z, R)`, its update into the proposal slot (R: the weight of the
///   sample, ignored by an unweighted law);
/// - `weight()`, the R of a complete sample (may return null for an unweighted law);
/// - `restart_at(p0)`, its own return to the initial gain, after the checks of p0;
/// - `parameter_count()`.
template <class Law, class T>
class RegressionLaw {
 public:
  using Types = T;
  using Scalar = typename T::Scalar;
  using Parameters = typename T::Parameters;
  using Regressor = typename T::Regressor;
  using Measurement = typename T::Measurement;
  using Covariance = typename T::Covariance;
  using MeasurementWeight = typename T::MeasurementWeight;
  using Presence = typename T::Presence;

  [[nodiscard]] Index measurement_count() const noexcept { return nz_; }

  /// One step with \f$(\varphi_t, z_t)\f$; see `DiscreteAdaptationLaw`.
  [[nodiscard]] bool propose(const Regressor& phi, const Measurement& z) {
    detail::require_regression_sizes<T>(phi, z, law().parameter_count(), nz_, Law::name_propose);
    const MeasurementWeight* weight = law().weight();
    return law().step(phi, z, weight ? *weight : masked_.weight);
  }

  /// One step with the present entries of \f$z_t\f$ only; see `DiscreteAdaptationLaw`, "Partial measurements".
  [[nodiscard]] bool propose(const Regressor& phi, const Measurement& z, const Presence& present) {
    return masked_.propose(phi, z, present, law().weight(), law().parameter_count(), Law::name_propose,
                           [this](const auto& f, const auto& y, const auto& r) { return law().step(f, y, r); });
  }

  /// Back to \f$\hat p_0\f$ and the law's initial gain.
  void restart(const Parameters& p0) {
    require_finite_shape(p0, law().parameter_count(), 1, Law::name_restart, "p0");
    law().restart_at(p0);
  }

 protected:
  /// \param weighted whether the law has a weight R (the masked copy then keeps \f$\bar R\f$).
  RegressionLaw(Index np, Index nz, bool weighted) : nz_(nz), masked_(np, nz, weighted) {}

  Index nz_;

 private:
  Law& law() noexcept { return static_cast<Law&>(*this); }
  const Law& law() const noexcept { return static_cast<const Law&>(*this); }

  detail::MaskedRegression<T> masked_;
};

/// The bases of a weighted least-squares law `L` (CRTP), written once: the
/// estimate \f$(\hat p, \Gamma)\f$ with its proposal slot, and the `RegressionLaw`
/// interface, whose types it exports.
template <class L, typename S, int NP, int NZ>
class LeastSquaresLaw : public LeastSquaresEstimate<typename RegressionTypes<S, NP, NZ>::Parameters,
                                                    typename RegressionTypes<S, NP, NZ>::Covariance>,
                        public RegressionLaw<L, RegressionTypes<S, NP, NZ>> {
 public:
  using Interface = RegressionLaw<L, RegressionTypes<S, NP, NZ>>;
  using Estimate = LeastSquaresEstimate<typename Interface::Parameters, typename Interface::Covariance>;
  using Estimate::parameter_count;

 protected:
  LeastSquaresLaw(Index np, Index nz) : Interface(np, nz, /*weighted=*/true) {}
};

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
///
/// **Partial measurements.** `propose(phi, z, present)` uses only the entries
/// of z marked present (the others may be NaN): it is the law's step on the
/// sub-regression \f$z_P = \varphi_P^Tp + v_P\f$ of the present set P, the columns
/// \f$\varphi_P\f$ of φ and, for the weighted laws, the block \f$R_{PP}\f$ of R. It runs
/// as the full-size step with the absent columns of φ and entries of z zeroed and R
/// replaced by \f$\bar R = DRD + (I - D)\f$: then
/// \f$\bar R + \bar\varphi^T\Gamma\bar\varphi\f$ (φ̄: φ with those columns zeroed) is block diagonal, \f$R_{PP} + \varphi_P^T\Gamma\varphi_P\f$ and I, so
/// the gain of an absent entry is zero and the rest is the sub-regression's step
/// exactly. (Zeroing alone would not do when R couples the entries: the present
/// block of \f$(R + \varphi^T\Gamma\varphi)^{-1}\f$ would then condition on the noise of
/// entries that were never measured.) All present is `propose(phi, z)`, bit for
/// bit; none present is the recursion without data (p unchanged; Γ unchanged,
/// or divided by λ under forgetting).
template <class L>
concept DiscreteAdaptationLaw =
    requires(L& law, const L& const_law, const typename L::Regressor& phi, const typename L::Measurement& z,
             const typename L::Presence& present, const typename L::Parameters& p0) {
      typename L::Scalar;
      typename L::Parameters;
      typename L::Regressor;
      typename L::Measurement;
      typename L::Presence;
      typename L::Options;
      { const_law.parameters() } -> std::convertible_to<const typename L::Parameters&>;
      { law.propose(phi, z) } -> std::same_as<bool>;
      { law.propose(phi, z, present) } -> std::same_as<bool>;
      { const_law.proposal() } -> std::convertible_to<const typename L::Parameters&>;
      law.commit();
      law.restart(p0);
      { const_law.parameter_count() } -> std::convertible_to<Index>;
      { const_law.measurement_count() } -> std::convertible_to<Index>;
    };

}  // namespace adaptobs
