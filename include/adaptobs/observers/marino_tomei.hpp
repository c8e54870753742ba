#pragma once
/// \file
/// Algorithm 2 of Zhang (2005), §III-B: the adaptive
/// observer of Marino & Tomei (Nonlinear Control Design, 1995, ch. 5), SISO,
/// constant A and c.
///
/// Static transform: form (7), \f$c_o = e_1^T\f$ and \f$A_o\f$ the shift matrix
/// (`marino_tomei_form`). Dynamic transform, with chosen \f$\gamma_2, \dots, \gamma_n\f$:
/// \f[ F = \begin{bmatrix} -\gamma_2 & 1 & & \\ \vdots & & \ddots & \\ -\gamma_{n-1} & & & 1
///     \\ -\gamma_n & 0 & \cdots & 0\end{bmatrix},\quad
///     G = \begin{bmatrix} -\gamma_{2:n} & I_{n-1}\end{bmatrix},\quad H = \begin{bmatrix} 0\\ I_{n-1}\end{bmatrix}, \f]
/// so that (4a) becomes \f$\dot z = A_oz + \varphi + \gamma\xi^T\theta\f$ with
/// \f$\gamma = (1, \gamma_2, \dots, \gamma_n)^T\f$ and \f$\xi^T = \Xi_1 + \Psi_1\f$ (first rows).
/// Observer: \f$\dot{\hat z} = A_o\hat z + \varphi + \gamma\xi^T\hat\theta + k(y - c_o\hat z)\f$,
/// \f$\dot{\hat\theta} = \Gamma\xi(y - c_o\hat z)\f$; errors and Lyapunov function as
/// for Algorithm 1. Conditions checked at construction: one output, constant
/// (A, c), \f$c_o = e_1^T\f$, columns 2..n of \f$A_o\f$ those of the shift (the first
/// column does not enter), \f$\det(sI - F) = s^{n-1} + \gamma_2s^{n-2} + \dots + \gamma_n\f$
/// Hurwitz, and \f$c_o(sI - A_o + kc_o)^{-1}\gamma\f$ SPR. `spr_injection_gain`
/// chooses k for a given γ (then \f$G(s) = 1/(s + \lambda)\f$).
///
/// Reading: the printed signs of F and G (−γᵢ in the first column) are right:
/// row i + 1 of the bracket is \f$\gamma_{i+1}(\Xi_1 + \Psi_1)\f$.

#include <adaptobs/core/dimensions.hpp>
#include <adaptobs/core/dynamic_transform.hpp>
#include <adaptobs/core/static_transform.hpp>
#include <adaptobs/core/validation.hpp>
#include <adaptobs/design/polynomial.hpp>
#include <adaptobs/observers/spr_observer_conditions.hpp>
#include <adaptobs/observers/unified_adaptive_observer.hpp>

#include <Eigen/Core>

#include <algorithm>
#include <limits>
#include <string_view>
#include <utility>

namespace adaptobs {

/// Algorithm 2 (§III-B) as an algorithm of the unified formulation.
///
/// \copydoc marino_tomei.hpp
template <StateSpace D>
struct MarinoTomei {
  using Scalar = typename D::Scalar;
  using Vector = Eigen::Matrix<Scalar, D::nx, 1>;
  static constexpr std::string_view name = "MarinoTomeiObserver";
  static constexpr int filter_rows = difference_of_sizes(D::nx, 1);

  StaticTransform<D> static_transform;                             ///< (T, K) giving the form (7)
  DynamicTransform<Scalar, D::nx, filter_rows> dynamic_transform;  ///< F, G, H as printed in §III-B
  Vector gamma;                                                    ///< \f$(1, \gamma_2, \dots, \gamma_n)\f$
  typename D::GainMatrix k;                                        ///< observer gain k (n × 1)

  MarinoTomei(StaticTransform<D> transform, Vector gamma_vector, typename D::GainMatrix gain)
      : static_transform(std::move(transform)),
        dynamic_transform(make_dynamic_transform(static_transform, gamma_vector)),
        gamma(std::move(gamma_vector)),
        k(std::move(gain)) {
    const Index n = static_transform.T().rows();
    require(gamma(0) == Scalar(1), name, "gamma", "must have a first entry equal to 1");
    require(n == 1 || is_hurwitz_polynomial(Polynomial<Scalar>(gamma)), name, "gamma",
            "must hold the coefficients of a Hurwitz polynomial (F must be Hurwitz)");
    require_finite_shape(k, n, 1, name, "k");
  }

  void injection_gain(const TransformedSystem<D>& /*so*/, Scalar /*t*/, typename D::GainMatrix& L) const { L = k; }

  /// Its fields for `snapshot` and `restore` (core/snapshot.hpp).
  template <class Self, class Archive>
  static void visit_state(Self& self, Archive& archive) {
    archive.object("static_transform", self.static_transform);
    archive.object("dynamic_transform", self.dynamic_transform);
    archive("gamma", self.gamma);
    archive("k", self.k);
  }

  /// \f$\xi^T = \Xi_1 + \Psi_1\f$ (§III-B).
  template <class DXi, class DOmega, class DPsi, class DR>
  void regressor(const TransformedSystem<D>& /*so*/, const Eigen::MatrixBase<DXi>& Xi,
                 const Eigen::MatrixBase<DOmega>& /*Omega*/, const Eigen::MatrixBase<DPsi>& Psi,
                 Eigen::MatrixBase<DR>& R) const {
    R = Xi.row(0) + Psi.row(0);
  }

  void check(const TransformedSystem<D>& so, const Sizes& sizes, bool time_invariant) const {
    detail::require_single_output_spr_form(so, sizes, time_invariant, name);
    const Index n = sizes.nx;
    typename D::StateMatrix shift = D::StateMatrix::Zero(n, n);
    shift.diagonal(1).setOnes();
    const Scalar tol =
        Scalar(1e3) * std::numeric_limits<Scalar>::epsilon() * std::max(Scalar(1), so.Ao.cwiseAbs().maxCoeff());
    require(n == 1 || (so.Ao.rightCols(n - 1) - shift.rightCols(n - 1)).cwiseAbs().maxCoeff() <= tol, name,
            "static_transform", "must give the shift matrix A_o of form (7) (columns 2..n)");
    detail::require_spr_error_system(so, k, gamma, "gamma", name);
  }

 private:
  static DynamicTransform<Scalar, D::nx, filter_rows> make_dynamic_transform(const StaticTransform<D>& transform,
                                                                             const Vector& gamma) {
    const Index r = detail::unmeasured_states(transform.T().rows(), 1, name, "transform"), n = r + 1;
    require_finite_shape(gamma, n, 1, name, "gamma");
    const Eigen::Matrix<Scalar, filter_rows, 1> g = gamma.tail(r);
    Eigen::Matrix<Scalar, filter_rows, filter_rows> f = Eigen::Matrix<Scalar, filter_rows, filter_rows>::Zero(r, r);
    f.col(0) = -g;
    if (r > 1) f.diagonal(1).setOnes();
    return detail::block_transform<Scalar, D::nx, filter_rows>(n, r, g, std::move(f));
  }
};

template <ContinuousModel Model>
using MarinoTomeiObserver = UnifiedAdaptiveObserver<Model, MarinoTomei<typename Model::Dims>>;

/// Builds the Marino–Tomei observer: transform to form (7), γ, gain k, adaptation gain Γ.
template <ContinuousModel Model>
[[nodiscard]] MarinoTomeiObserver<Model> make_marino_tomei_observer(
    Model model, StaticTransform<typename Model::Dims> transform,
    Eigen::Matrix<typename Model::Scalar, Model::Dims::nx, 1> gamma, typename Model::Dims::GainMatrix k,
    typename Model::Dims::ParameterMatrix adaptation_gain, typename Model::Dims::State eta0,
    typename Model::Dims::Parameters theta0, UnifiedObserverOptions options = {}) {
  return detail::make_gradient_observer(
      std::move(model), MarinoTomei<typename Model::Dims>(std::move(transform), std::move(gamma), std::move(k)),
      std::move(adaptation_gain), "adaptation_gain", std::move(eta0), std::move(theta0), options);
}

}  // namespace adaptobs
