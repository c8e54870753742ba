#pragma once
/// \file
/// Algorithm 1 of Zhang (2005), §III-A: the adaptive
/// observer of Bastin & Gevers (IEEE TAC 33(7), 1988), SISO, constant A and c.
///
/// Static transform: form (5), \f$c_o = e_1^T\f$,
/// \f$A_o = \begin{bmatrix} 0 & a_{12}\\ 0 & A_{22}\end{bmatrix}\f$, \f$A_{22}\f$ Hurwitz
/// (`bastin_gevers_form` computes T and K). Dynamic transform:
/// \f$F = A_{22}\f$, \f$G = [0\ I_{n-1}]\f$, \f$H = [0; I_{n-1}]\f$, so that (4a) becomes (6a)
/// \f$\dot z = A_oz + \varphi + \gamma\xi^T\theta\f$, \f$\gamma = e_1\f$, \f$\xi^T = a_{12}\Xi + \Psi_1\f$. Observer:
/// \f[ \dot{\hat z} = A_o\hat z + \varphi + \gamma\xi^T\hat\theta + k(y - c_o\hat z),\qquad
///     \dot{\hat\theta} = \Gamma\xi(y - c_o\hat z). \f]
/// Errors \f$e = \hat z - z\f$, \f$\tilde\theta = \hat\theta - \theta\f$:
/// \f$\dot e = (A_o - kc_o)e + \gamma\xi^T\tilde\theta\f$, \f$\dot{\tilde\theta} = -\Gamma\xi c_oe\f$;
/// with the KYP matrix P of the SPR triple \f$(A_o - kc_o, \gamma, c_o)\f$,
/// \f$V = e^TPe + \tilde\theta^T\Gamma^{-1}\tilde\theta\f$ has \f$\dot V = -e^TQe \le 0\f$.
/// Conditions checked at construction: one output, constant (A, c),
/// \f$c_o = e_1^T\f$, \f$A_{22}\f$ Hurwitz, and \f$c_o(sI - A_o + kc_o)^{-1}\gamma\f$ SPR
/// (exact test of `design/spr_test.hpp`); Γ > 0 by `GradientLaw`; ξ must be
/// persistently exciting (see `excitation_level()`).
///
/// Reading: the zero first column of \f$A_o\f$ is a normalization. The bracket
/// identity needs only \f$c_o = e_1^T\f$ and \f$F = A_{22}\f$ (the first column never
/// enters \f$A_oH\f$), so any first column is accepted; `spr_injection_gain`
/// absorbs it in k.

#include <adaptobs/core/detail/products.hpp>
#include <adaptobs/core/detail/segments.hpp>
#include <adaptobs/core/dimensions.hpp>
#include <adaptobs/core/dynamic_transform.hpp>
#include <adaptobs/core/static_transform.hpp>
#include <adaptobs/core/validation.hpp>
#include <adaptobs/design/polynomial.hpp>
#include <adaptobs/observers/spr_observer_conditions.hpp>
#include <adaptobs/observers/unified_adaptive_observer.hpp>

#include <Eigen/Core>

#include <string_view>
#include <utility>

namespace adaptobs {

/// Algorithm 1 (§III-A) as an algorithm of the unified formulation.
///
/// \copydoc bastin_gevers.hpp
template <StateSpace D>
struct BastinGevers {
  using Scalar = typename D::Scalar;
  static constexpr std::string_view name = "BastinGeversObserver";
  static constexpr int filter_rows = difference_of_sizes(D::nx, 1);

  StaticTransform<D> static_transform;  ///< (T, K) giving the form (5)
  /// \f$F = A_{22}\f$ (\f$= GA_oH\f$), \f$G = [0\ I]\f$, \f$H = [0; I]\f$.
  DynamicTransform<Scalar, D::nx, filter_rows> dynamic_transform;
  typename D::GainMatrix k;  ///< observer gain k (n × 1)

  BastinGevers(StaticTransform<D> transform, typename D::GainMatrix gain)
      : static_transform(std::move(transform)),
        dynamic_transform(make_dynamic_transform(static_transform)),
        k(std::move(gain)) {
    require_finite_shape(k, static_transform.T().rows(), 1, name, "k");
  }

  void injection_gain(const TransformedSystem<D>& /*so*/, Scalar /*t*/, typename D::GainMatrix& L) const { L = k; }

  /// Its fields for `snapshot` and `restore` (core/snapshot.hpp).
  template <class Self, class Archive>
  static void visit_state(Self& self, Archive& archive) {
    archive.object("static_transform", self.static_transform);
    archive.object("dynamic_transform", self.dynamic_transform);
    archive("k", self.k);
  }

  /// \f$\xi^T = a_{12}\Xi + \Psi_1\f$ (§III-A, below (6b)).
  template <class DXi, class DOmega, class DPsi, class DR>
  void regressor(const TransformedSystem<D>& so, const Eigen::MatrixBase<DXi>& Xi,
                 const Eigen::MatrixBase<DOmega>& /*Omega*/, const Eigen::MatrixBase<DPsi>& Psi,
                 Eigen::MatrixBase<DR>& R) const {
    const Index r = Xi.rows();
    detail::set_product(R, detail::segment<filter_rows>(so.Ao.row(0), 1, r), Xi);
    R += Psi.row(0);
  }

  void check(const TransformedSystem<D>& so, const Sizes& sizes, bool time_invariant) const {
    detail::require_single_output_spr_form(so, sizes, time_invariant, name);
    const Index n = sizes.nx;
    require(n == 1 || has_hurwitz_characteristic_polynomial(so.Ao.bottomRightCorner(n - 1, n - 1)), name,
            "static_transform", "must give a Hurwitz A22 (form (5))");
    Eigen::Matrix<Scalar, D::nx, 1> gamma = Eigen::Matrix<Scalar, D::nx, 1>::Zero(n);
    gamma(0) = Scalar(1);
    detail::require_spr_error_system(so, k, gamma, "e1", name);
  }

 private:
  // G = [0 I], H = [0; I] around the n − 1 unmeasured states of form (5).
  static DynamicTransform<Scalar, D::nx, filter_rows> make_dynamic_transform(const StaticTransform<D>& transform) {
    const Index r = detail::unmeasured_states(transform.T().rows(), 1, name, "transform");
    return detail::block_transform<Scalar, D::nx, filter_rows>(r + 1, r,
                                                               Eigen::Matrix<Scalar, filter_rows, 1>::Zero(r));
  }
};

/// Bastin–Gevers observer over a model (see `BastinGevers`).
template <ContinuousModel Model>
using BastinGeversObserver = UnifiedAdaptiveObserver<Model, BastinGevers<typename Model::Dims>>;

/// Builds the Bastin–Gevers observer: transform to form (5), gain k, adaptation gain Γ.
template <ContinuousModel Model>
[[nodiscard]] BastinGeversObserver<Model> make_bastin_gevers_observer(
    Model model, StaticTransform<typename Model::Dims> transform, typename Model::Dims::GainMatrix k,
    typename Model::Dims::ParameterMatrix gamma, typename Model::Dims::State eta0,
    typename Model::Dims::Parameters theta0, UnifiedObserverOptions options = {}) {
  return detail::make_gradient_observer(std::move(model),
                                        BastinGevers<typename Model::Dims>(std::move(transform), std::move(k)),
                                        std::move(gamma), "gamma", std::move(eta0), std::move(theta0), options);
}

}  // namespace adaptobs
