#pragma once
/// \file
/// Algorithm 4 of Zhang (2005), §III-D: the adaptive
/// observer of Zhang (IEEE TAC 47(3), 2002), MIMO and time varying, without
/// coordinate change — the continuous-time counterpart of `GuyaderZhangObserver`.
///
/// Static transform: T = I, output injection K(t) with \f$A - KC\f$ exponentially
/// stable. Dynamic transform: \f$F(t) = A(t) - K(t)C(t)\f$, \f$G = H = I\f$ — the bracket
/// of (4a) vanishes and θ moves to the output: (10a)
/// \f$\dot z = (A - KC)z + Bu + Ky\f$, (10b) \f$y = Cz + C\Omega\theta\f$, with (11)
/// \f$\dot\Omega = (A - KC)\Omega + \Phi\f$. Observer (12a)–(12b):
/// \f[ \dot{\hat z} = (A - KC)\hat z + Bu + Ky,\qquad
///     \dot{\hat\theta} = \Gamma\Omega^TC^T(y - C\hat z - C\Omega\hat\theta),\qquad \hat x = \hat z + \Omega\hat\theta. \f]
/// Errors: (13) \f$\dot{\tilde z} = (A - KC)\tilde z\f$ and, correcting (14) as printed,
/// \f[ \dot{\tilde\theta} = -\Gamma\Omega^TC^TC\tilde z - \Gamma\Omega^TC^TC\Omega\tilde\theta \f]
/// (the text drops Γ in the first term and prints \f$\tilde\theta\f$ for \f$\dot{\tilde\theta}\f$).
/// Exponential convergence follows from the stability of \f$A - KC\f$ and the
/// persistent excitation (15) \f$\int_t^{t+s}\Omega^TC^TC\Omega\,d\tau \ge \alpha I\f$.
/// Conditions: \f$A - KC\f$ Hurwitz (checked for a constant model; for a periodic
/// one use `floquet_exponents`); (15) is monitored by `excitation_level()`.
/// A time-varying K(t) from `RiccatiDifferentialEquation` is applied sample by
/// sample with `set_output_injection`.

#include <adaptobs/core/detail/products.hpp>
#include <adaptobs/core/dimensions.hpp>
#include <adaptobs/core/dynamic_transform.hpp>
#include <adaptobs/core/static_transform.hpp>
#include <adaptobs/core/validation.hpp>
#include <adaptobs/design/polynomial.hpp>
#include <adaptobs/observers/unified_adaptive_observer.hpp>

#include <Eigen/Core>

#include <string_view>
#include <utility>

namespace adaptobs {

/// Algorithm 4 (§III-D) as an algorithm of the unified formulation.
///
/// \copydoc zhang_continuous.hpp
template <StateSpace D>
struct ZhangContinuous {
  using Scalar = typename D::Scalar;
  static constexpr std::string_view name = "ZhangContinuousObserver";
  static constexpr int filter_rows = D::nx;

  StaticTransform<D> static_transform;  ///< T = I, output injection K
  /// \f$F(t) = A(t) - K(t)C(t)\f$ (\f$= GA_oH\f$), \f$G = H = I\f$.
  DynamicTransform<Scalar, D::nx, filter_rows> dynamic_transform;

  explicit ZhangContinuous(typename D::GainMatrix K)
      : static_transform(StaticTransform<D>::output_injection(std::move(K))),
        dynamic_transform(DynamicTransform<Scalar, D::nx, filter_rows>::projected(
            D::StateMatrix::Identity(static_transform.T().rows(), static_transform.T().rows()),
            D::StateMatrix::Identity(static_transform.T().rows(), static_transform.T().rows()))) {}

  /// L = 0: the output injection K is inside \f$A_o = A - KC\f$ and \f$\varphi = Bu + Ky\f$ (12a).
  void injection_gain(const TransformedSystem<D>& /*so*/, Scalar /*t*/, typename D::GainMatrix& L) const {
    L.setZero();
  }

  /// Its fields for `snapshot` and `restore` (core/snapshot.hpp).
  template <class Self, class Archive>
  static void visit_state(Self& self, Archive& archive) {
    archive.object("static_transform", self.static_transform);
    archive.object("dynamic_transform", self.dynamic_transform);
  }

  /// R = CΩ, so that \f$\dot{\hat\theta} = \Gamma\Omega^TC^T\varepsilon\f$ (12b).
  template <class DXi, class DOmega, class DPsi, class DR>
  void regressor(const TransformedSystem<D>& so, const Eigen::MatrixBase<DXi>& /*Xi*/,
                 const Eigen::MatrixBase<DOmega>& Omega, const Eigen::MatrixBase<DPsi>& /*Psi*/,
                 Eigen::MatrixBase<DR>& R) const {
    detail::set_product(R, so.Co, Omega);
  }

  void check(const TransformedSystem<D>& so, const Sizes& /*sizes*/, bool time_invariant) const {
    if (time_invariant)
      require(has_hurwitz_characteristic_polynomial(so.Ao), name, "K", "must make A - K C Hurwitz (eq. (13))");
  }
};

template <ContinuousModel Model>
using ZhangContinuousObserver = UnifiedAdaptiveObserver<Model, ZhangContinuous<typename Model::Dims>>;

/// Builds the continuous Zhang observer (12a)–(12b): output injection K, adaptation gain Γ.
template <ContinuousModel Model>
[[nodiscard]] ZhangContinuousObserver<Model> make_zhang_continuous_observer(
    Model model, typename Model::Dims::GainMatrix K, typename Model::Dims::ParameterMatrix gamma,
    typename Model::Dims::State eta0, typename Model::Dims::Parameters theta0, UnifiedObserverOptions options = {}) {
  using D = typename Model::Dims;
  require_shape(K, model.sizes().nx, model.sizes().ny, ZhangContinuous<D>::name, "K");
  return detail::make_gradient_observer(std::move(model), ZhangContinuous<D>(std::move(K)), std::move(gamma), "gamma",
                                        std::move(eta0), std::move(theta0), options);
}

}  // namespace adaptobs
