#pragma once
/// \file
/// Continuous-time linear models with unknown parameters (Zhang 2005, eq. (1)):
/// \f[ \dot\eta(t) = A(t)\eta(t) + B(t)u(t) + \Phi(t)\theta,\qquad y(t) = C(t)\eta(t). \f]
///
/// A model supplies the known matrices \f$(A(t), B(t), C(t))\f$ — constant
/// (`ContinuousLtiModel`) or from a callable (`ContinuousLtvModel`) — and the
/// known regressor \f$\Phi\f$, a callable of `t`, or of `(t, u, y)` for
/// state-affine systems whose regressor is built from the measured signals.
/// Measurements arrive as `ContinuousSample`s: the input and the output at a
/// sampling instant, optionally also at the midpoint of the interval since the
/// previous sample (see `core/sampled_integration.hpp` for how observers use them).

#include <adaptobs/core/dimensions.hpp>
#include <adaptobs/core/time_invariance.hpp>
#include <adaptobs/core/validation.hpp>

#include <concepts>
#include <optional>
#include <string_view>
#include <type_traits>
#include <utility>

namespace adaptobs {

/// The known matrices of a continuous-time linear system at one instant.
template <StateSpace D>
struct ContinuousSystem {
  typename D::StateMatrix A;
  typename D::InputMatrix B;
  typename D::OutputMatrix C;

  [[nodiscard]] Sizes sizes() const noexcept { return {A.rows(), B.cols(), C.rows(), D::np}; }
};

/// Input and output measured at one instant \f$t_k\f$.
///
/// `midpoint`, when set, holds \f$u\f$ and \f$y\f$ at \f$(t_{k-1} + t_k)/2\f$:
/// with it, one Runge–Kutta step per sample sees the signals exactly at its
/// stage times (see `SignalReconstruction::quadratic`).
template <StateSpace D>
struct ContinuousSample {
  struct Midpoint {
    typename D::Input u;
    typename D::Output y;
  };
  typename D::Scalar t{};
  typename D::Input u;
  typename D::Output y;
  std::optional<Midpoint> midpoint{};
};

/// A regressor callable: `Phi(t)` or `Phi(t, u, y)`, returning an nx × np matrix.
template <class F, class D>
concept RegressorFunction =
    std::invocable<const F&, typename D::Scalar> ||
    std::invocable<const F&, typename D::Scalar, const typename D::Input&, const typename D::Output&>;

namespace detail {
/// \f$\Phi\f$ at time t, from a callable of t or of (t, u, y). A result whose
/// run-time size is not nx × np throws a `ConfigurationError` naming `Phi`, at
/// whatever time it happens: with `Eigen::Dynamic` sizes nothing else would stop
/// the observer from writing past its filters.
template <StateSpace D, class F>
[[nodiscard]] decltype(auto) evaluate_regressor(const F& phi, typename D::Scalar t, const typename D::Input& u,
                                                const typename D::Output& y, const Sizes& s, std::string_view who) {
  decltype(auto) value = [&]() -> decltype(auto) {
    if constexpr (std::invocable<const F&, typename D::Scalar, const typename D::Input&, const typename D::Output&>)
      return phi(t, u, y);
    else
      return phi(t);
  }();
  if constexpr (requires {
                  value.rows();
                  value.cols();
                })
    require_shape(value, s.nx, s.np, who, "Phi");
  return value;
}

template <StateSpace D, class F>
void validate_regressor(const F& phi, const Sizes& s, std::string_view who) {
  const typename D::Input u = D::Input::Zero(s.nu);
  const typename D::Output y = D::Output::Zero(s.ny);
  static_cast<void>(evaluate_regressor<D>(phi, typename D::Scalar(0), u, y, s, who));
}
}  // namespace detail

/// A continuous-time model: `at(t)` gives \f$(A(t), B(t), C(t))\f$ and
/// `regressor(t, u, y)` gives \f$\Phi\f$. `time_invariant` says that A, B, C are
/// constant (Φ may still vary); a model type that may hold either kind says so at
/// run time (`is_time_invariant`, core/time_invariance.hpp).
template <class M>
concept ContinuousModel =
    StateSpace<typename M::Dims> &&
    requires(const M& m, typename M::Scalar t, const typename M::Dims::Input& u, const typename M::Dims::Output& y) {
      { m.at(t) } -> std::convertible_to<const ContinuousSystem<typename M::Dims>&>;
      { m.regressor(t, u, y) } -> std::convertible_to<typename M::Dims::RegressorMatrix>;
      { M::time_invariant } -> std::convertible_to<bool>;
      { m.sizes() } -> std::same_as<Sizes>;
    };

/// Constant \f$(A, B, C)\f$ and a regressor callable \f$\Phi\f$.
template <StateSpace D, RegressorFunction<D> RegressorFn>
class ContinuousLtiModel : public D {
 public:
  static constexpr bool time_invariant = true;

  /// \param np number of unknown parameters (`D::np` itself when that is fixed).
  /// Compile-time sizes that disagree with D's are refused by a `static_assert`
  /// naming the matrix; run-time sizes are checked against the order of A.
  template <class DA, class DB, class DC>
  ContinuousLtiModel(const Eigen::MatrixBase<DA>& A, const Eigen::MatrixBase<DB>& B, const Eigen::MatrixBase<DC>& C,
                     RegressorFn Phi, Index np = D::np)
      : system_{detail::fitted<typename D::StateMatrix>(A), detail::fitted<typename D::InputMatrix>(B),
                detail::fitted<typename D::OutputMatrix>(C)},
        phi_(std::move(Phi)) {
    static_assert(detail::fits_size<DA, D::nx, D::nx>, "ContinuousLtiModel: A must be nx x nx");
    static_assert(detail::fits_size<DB, D::nx, D::nu>, "ContinuousLtiModel: B must be nx x nu");
    static_assert(detail::fits_size<DC, D::ny, D::nx>, "ContinuousLtiModel: C must be ny x nx");
    constexpr std::string_view who = "ContinuousLtiModel";
    validate_state_space(system_, who);
    require_size<D::np>(np, who, "np");
    sizes_ = {system_.A.rows(), system_.B.cols(), system_.C.rows(), np};
    detail::validate_regressor<D>(phi_, sizes_, who);
  }

  [[nodiscard]] const ContinuousSystem<D>& at(typename D::Scalar /*t*/) const noexcept { return system_; }
  [[nodiscard]] const ContinuousSystem<D>& system() const noexcept { return system_; }
  [[nodiscard]] decltype(auto) regressor(typename D::Scalar t, const typename D::Input& u,
                                         const typename D::Output& y) const {
    return detail::evaluate_regressor<D>(phi_, t, u, y, sizes_, "ContinuousLtiModel");
  }
  [[nodiscard]] Sizes sizes() const noexcept { return sizes_; }
  /// The regressor callable Φ as given.
  [[nodiscard]] const RegressorFn& regressor_function() const noexcept { return phi_; }

  /// Its fields for `snapshot` and `restore` (core/snapshot.hpp): A, B, C; np a
  /// setting. The regressor Φ is the model's code, not its state: it is not saved.
  static constexpr std::string_view snapshot_type = "ContinuousLtiModel";
  static constexpr int snapshot_version = 1;
  template <class Self, class Archive>
  static void visit_state(Self& self, Archive& archive) {
    archive("A", self.system_.A);
    archive("B", self.system_.B);
    archive("C", self.system_.C);
    archive.setting("np", self.sizes_.np);
  }

 private:
  ContinuousSystem<D> system_;
  RegressorFn phi_;
  Sizes sizes_;
};

/// Time-varying model: a callable `t -> ContinuousSystem<D>` and a regressor callable.
template <StateSpace D, class MatricesFn, RegressorFunction<D> RegressorFn>
  requires std::convertible_to<std::invoke_result_t<const MatricesFn&, typename D::Scalar>, ContinuousSystem<D>>
class ContinuousLtvModel : public D {
 public:
  static constexpr bool time_invariant = false;

  ContinuousLtvModel(MatricesFn matrices_at, RegressorFn Phi, Sizes sizes = {D::nx, D::nu, D::ny, D::np})
      : matrices_at_(std::move(matrices_at)), phi_(std::move(Phi)), sizes_(sizes) {
    constexpr std::string_view who = "ContinuousLtvModel";
    require(sizes_.nx >= 0 && sizes_.nu >= 0 && sizes_.ny >= 0 && sizes_.np >= 0, who, "sizes",
            "must be non-negative (dynamic dimensions need explicit sizes)");
    const ContinuousSystem<D> first = matrices_at_(typename D::Scalar(0));
    validate_state_space(first, who);
    require_size<D::np>(sizes_.np, who, "sizes.np");
    require(first.sizes().nx == sizes_.nx && first.sizes().nu == sizes_.nu && first.sizes().ny == sizes_.ny, who,
            "matrices_at", "returns matrices whose sizes differ from 'sizes'");
    detail::validate_regressor<D>(phi_, sizes_, who);
  }

  /// \f$(A(t), B(t), C(t))\f$; with dynamic sizes, matrices of other sizes than
  /// `sizes` throw a `ConfigurationError` naming `matrices_at`, at any t.
  [[nodiscard]] ContinuousSystem<D> at(typename D::Scalar t) const {
    ContinuousSystem<D> system = matrices_at_(t);
    if constexpr (!D::is_fixed) require_system_sizes(system, sizes_, "ContinuousLtvModel", "matrices_at(t)");
    return system;
  }
  [[nodiscard]] decltype(auto) regressor(typename D::Scalar t, const typename D::Input& u,
                                         const typename D::Output& y) const {
    return detail::evaluate_regressor<D>(phi_, t, u, y, sizes_, "ContinuousLtvModel");
  }
  [[nodiscard]] Sizes sizes() const noexcept { return sizes_; }

 private:
  MatricesFn matrices_at_;
  RegressorFn phi_;
  Sizes sizes_;
};

/// `make_continuous_lti_model<D>(A, B, C, Phi)`: deduces the regressor type.
template <StateSpace D, class RegressorFn>
[[nodiscard]] auto make_continuous_lti_model(typename D::StateMatrix A, typename D::InputMatrix B,
                                             typename D::OutputMatrix C, RegressorFn Phi, Index np = D::np) {
  return ContinuousLtiModel<D, RegressorFn>(std::move(A), std::move(B), std::move(C), std::move(Phi), np);
}

/// `make_continuous_ltv_model<D>(matrices_at, Phi)`: deduces the callable types.
template <StateSpace D, class MatricesFn, class RegressorFn>
[[nodiscard]] auto make_continuous_ltv_model(MatricesFn matrices_at, RegressorFn Phi,
                                             Sizes sizes = {D::nx, D::nu, D::ny, D::np}) {
  return ContinuousLtvModel<D, MatricesFn, RegressorFn>(std::move(matrices_at), std::move(Phi), sizes);
}

}  // namespace adaptobs
