#pragma once
/// \file
/// Algorithm 3 of Zhang (2005), §III-C: the adaptive
/// observer of Besançon (Systems & Control Letters 41(4), 2000), MIMO and time varying.
///
/// Static transform: form (8), \f$C_o = [I_m\ 0]\f$,
/// \f$A_o(t) = \begin{bmatrix} A_{11} & A_{12}\\ A_{21} & A_{22}\end{bmatrix}\f$ (`besancon_form`
/// for a constant (A, C); a time-varying system is given in that form, with a
/// constant T). Dynamic transform: \f$F(t) = A_{22}(t)\f$, \f$G = [0\ I]\f$, \f$H = [0; I]\f$,
/// so that (4a) becomes (9a)–(9c), θ entering only the measured block through
/// \f$\Lambda = A_{12}\Xi + \Psi_1\f$. Observer (§III-C; the dot on \f$\hat z_1\f$ is lost in the text):
/// \f[ \dot{\hat z}_1 = A_{11}\hat z_1 + A_{12}\hat z_2 + \varphi_1 + \Lambda\hat\theta + K_1(y - \hat z_1),\quad
///     \dot{\hat z}_2 = A_{21}y + A_{22}\hat z_2 + \varphi_2,\quad \dot{\hat\theta} = \Gamma\Lambda^T(y - \hat z_1). \f]
/// In the unified form the gain is \f$L = [K_1; A_{21}(t)]\f$: the measured y
/// replaces \f$\hat z_1\f$ in the second block, which makes the error a cascade
/// \f$\dot e_2 = A_{22}(t)e_2\f$, \f$\dot e_1 = (A_{11} - K_1)e_1 + A_{12}e_2 + \Lambda\tilde\theta\f$,
/// \f$\dot{\tilde\theta} = -\Gamma\Lambda^Te_1\f$; with \f$\dot P_2 + A_{22}^TP_2 + P_2A_{22} \le -I\f$,
/// \f$V = |e_1|^2 + \tilde\theta^T\Gamma^{-1}\tilde\theta + c\,e_2^TP_2e_2\f$ decreases when
/// \f$\mathrm{sym}(A_{11} - K_1) < 0\f$ and c is large enough. Conditions: \f$C_o = [I\ 0]\f$
/// (checked), \f$\dot e_2 = A_{22}(t)e_2\f$ exponentially stable (checked as A22 Hurwitz
/// for a constant model; for a periodic one use `floquet_exponents` — frozen-time
/// eigenvalues are not enough), \f$\mathrm{sym}(A_{11} - K_1) < 0\f$ (checked for a
/// constant model; this is the library's own sufficient condition for the V above,
/// not one the paper states), Λ persistently exciting (`excitation_level()`).

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

/// Algorithm 3 (§III-C) as an algorithm of the unified formulation.
///
/// \copydoc besancon.hpp
template <StateSpace D>
struct Besancon {
  using Scalar = typename D::Scalar;
  using OutputSquare = typename D::OutputMatrixSquare;
  static constexpr std::string_view name = "BesanconObserver";
  static constexpr int filter_rows = difference_of_sizes(D::nx, D::ny);

  StaticTransform<D> static_transform;  ///< (T, K) giving the form (8)
  /// \f$F(t) = A_{22}(t)\f$ (\f$= GA_o(t)H\f$), \f$G = [0\ I]\f$, \f$H = [0; I]\f$.
  DynamicTransform<Scalar, D::nx, filter_rows> dynamic_transform;
  OutputSquare K1;  ///< gain \f$K_1\f$ of the measured block (m × m)

  Besancon(StaticTransform<D> transform, OutputSquare gain)
      : static_transform(std::move(transform)),
        dynamic_transform(make_dynamic_transform(static_transform)),
        K1(std::move(gain)) {
    const Index m = static_transform.K().cols();
    require_finite_shape(K1, m, m, name, "K1");
  }

  /// \f$L = [K_1; A_{21}(t)]\f$: \f$K_1(y - \hat z_1)\f$ in the first block, \f$A_{21}y\f$ in the second.
  /// Its fields for `snapshot` and `restore` (core/snapshot.hpp).
  template <class Self, class Archive>
  static void visit_state(Self& self, Archive& archive) {
    archive.object("static_transform", self.static_transform);
    archive.object("dynamic_transform", self.dynamic_transform);
    archive("K1", self.K1);
  }

  void injection_gain(const TransformedSystem<D>& so, Scalar /*t*/, typename D::GainMatrix& L) const {
    const Index m = K1.rows(), r = so.Ao.rows() - m;
    L.topRows(m) = K1;
    L.bottomRows(r) = so.Ao.bottomLeftCorner(r, m);
  }

  /// \f$\Lambda = A_{12}(t)\Xi + \Psi_1\f$ (first m rows of Ψ).
  template <class DXi, class DOmega, class DPsi, class DR>
  void regressor(const TransformedSystem<D>& so, const Eigen::MatrixBase<DXi>& Xi,
                 const Eigen::MatrixBase<DOmega>& /*Omega*/, const Eigen::MatrixBase<DPsi>& Psi,
                 Eigen::MatrixBase<DR>& R) const {
    const Index m = K1.rows(), r = Xi.rows();
    detail::set_product(R, so.Ao.template topRightCorner<D::ny, filter_rows>(m, r), Xi);
    R += Psi.template topRows<D::ny>(m);
  }

  void check(const TransformedSystem<D>& so, const Sizes& sizes, bool time_invariant) const {
    require(detail::is_leading_identity(so.Co), name, "static_transform", "must give C_o = C T^-1 = [I 0]");
    if (!time_invariant) return;
    const Index m = sizes.ny, r = sizes.nx - sizes.ny;
    using Dense = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;  // one instantiation per scalar
    require(r == 0 || has_hurwitz_characteristic_polynomial(so.Ao.bottomRightCorner(r, r)), name, "static_transform",
            "must give a Hurwitz A22 (form (8))");
    const Dense a11 = so.Ao.topLeftCorner(m, m) - K1;
    const Dense sym = Scalar(0.5) * (a11 + a11.transpose());
    require(symmetric_eigenvalues(sym)(m - 1) < 0, name, "K1",
            "must make A11 - K1 + (A11 - K1)^T negative definite (the library's sufficient condition "
            "for the Lyapunov function above, not a condition of the paper)");
  }

 private:
  // G = [0 I], H = [0; I] around the n − m unmeasured states of form (8).
  static DynamicTransform<Scalar, D::nx, filter_rows> make_dynamic_transform(const StaticTransform<D>& transform) {
    const Index m = transform.K().cols();
    const Index r = detail::unmeasured_states(transform.T().rows(), m, name, "transform");
    return detail::block_transform<Scalar, D::nx, filter_rows>(r + m, r,
                                                               Eigen::Matrix<Scalar, filter_rows, D::ny>::Zero(r, m));
  }
};

template <ContinuousModel Model>
using BesanconObserver = UnifiedAdaptiveObserver<Model, Besancon<typename Model::Dims>>;

/// Builds the Besançon observer: transform to form (8), gain K1, adaptation gain Γ.
template <ContinuousModel Model>
[[nodiscard]] BesanconObserver<Model> make_besancon_observer(
    Model model, StaticTransform<typename Model::Dims> transform, typename Model::Dims::OutputMatrixSquare K1,
    typename Model::Dims::ParameterMatrix gamma, typename Model::Dims::State eta0,
    typename Model::Dims::Parameters theta0, UnifiedObserverOptions options = {}) {
  return detail::make_gradient_observer(std::move(model),
                                        Besancon<typename Model::Dims>(std::move(transform), std::move(K1)),
                                        std::move(gamma), "gamma", std::move(eta0), std::move(theta0), options);
}

}  // namespace adaptobs
