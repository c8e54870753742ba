#pragma once
/// \file
/// Static transformation of Zhang (2005, §II-A, eq. (2)): a coordinate change
/// \f$x = T\eta\f$ and an output injection K.
///
/// Applied to system (1) it gives
/// \f[ \dot x = A_o x + \varphi + \Psi\theta,\qquad y = C_o x, \f]
/// \f[ C_o = C T^{-1},\quad A_o = T A T^{-1} - K C_o,\quad \Psi = T\Phi,\quad \varphi = T B u + K y. \f]
/// T is constant; K may be changed between samples (a time-varying K(t), e.g.
/// from a Riccati differential equation, is then piecewise constant).

#include <adaptobs/core/continuous_model.hpp>
#include <adaptobs/core/detail/dynamic_copy.hpp>
#include <adaptobs/core/detail/products.hpp>
#include <adaptobs/core/dimensions.hpp>
#include <adaptobs/core/precompiled.hpp>
#include <adaptobs/core/validation.hpp>

#include <Eigen/Core>
#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string_view>
#include <utility>

namespace adaptobs {

/// The matrices of system (2) at one instant.
template <StateSpace D>
struct TransformedSystem {
  typename D::StateMatrix Ao;   ///< \f$A_o = TAT^{-1} - KC_o\f$
  typename D::OutputMatrix Co;  ///< \f$C_o = CT^{-1}\f$
  typename D::InputMatrix TB;   ///< \f$TB\f$, so that \f$\varphi = TBu + Ky\f$
  typename D::GainMatrix K;     ///< output injection K

  void resize(const Sizes& s) {
    Ao.setZero(s.nx, s.nx);
    Co.setZero(s.ny, s.nx);
    TB.setZero(s.nx, s.nu);
    K.setZero(s.nx, s.ny);
  }
};

namespace detail {

/// \f$T^{-1}\f$ from a partial-pivoting LU (`Eigen::PartialPivLU`), or nothing when T
/// is singular to working precision: its condition number
/// \f$\kappa_1(T) = \|T\|_1\|T^{-1}\|_1\f$, taken exactly from the computed inverse, at
/// least 1/(nε), the rank threshold of a pivoted LU. On a dynamic-size copy: one
/// instance per scalar type, whatever fixed sizes T comes in.
template <typename Scalar>
[[nodiscard]] std::optional<DynamicMatrix<Scalar>> well_conditioned_inverse(const DynamicMatrix<Scalar>& t) {
  if (t.size() == 0) return t;
  DynamicMatrix<Scalar> inverse = Eigen::PartialPivLU<DynamicMatrix<Scalar>>(t).inverse();
  const auto norm_1 = [](const DynamicMatrix<Scalar>& m) { return m.cwiseAbs().colwise().sum().maxCoeff(); };
  const Scalar condition = norm_1(t) * norm_1(inverse);
  if (!(Scalar(t.rows()) * std::numeric_limits<Scalar>::epsilon() * condition < Scalar(1))) return std::nullopt;
  return inverse;
}
#ifdef ADAPTOBS_PRECOMPILED
ADAPTOBS_INSTANTIATE std::optional<DynamicMatrix<double>> well_conditioned_inverse<double>(
    const DynamicMatrix<double>&);
#endif

/// c_o = e1ᵀ (or C_o = [I 0]) to a relative tolerance: the output matrix the
/// forms of Algorithms 1–3 ask of the static transform.
template <class DC>
bool is_leading_identity(const Eigen::MatrixBase<DC>& co) {
  using Scalar = typename DC::Scalar;
  Scalar largest = 1, deviation = 0;
  for (Index j = 0; j < co.cols(); ++j)
    for (Index i = 0; i < co.rows(); ++i) {
      largest = std::max(largest, std::abs(co(i, j)));
      deviation = std::max(deviation, std::abs(co(i, j) - (i == j ? Scalar(1) : Scalar(0))));
    }
  return deviation <= Scalar(1e3) * std::numeric_limits<Scalar>::epsilon() * largest;
}

}  // namespace detail

/// Coordinate change T and output injection K (eq. (2)).
template <StateSpace D>
class StaticTransform : public D {
 public:
  using typename D::Scalar, typename D::StateMatrix, typename D::GainMatrix;

  /// \param T invertible coordinate change \f$x = T\eta\f$; \param K output injection (n × m).
  StaticTransform(StateMatrix T, GainMatrix K) : t_(std::move(T)), k_(std::move(K)) {
    constexpr std::string_view who = "StaticTransform";
    require_square(t_, who, "T");
    require_finite(t_, who, "T");
    require_finite_shape(k_, t_.rows(), k_.cols(), who, "K");
    const auto inverse = detail::well_conditioned_inverse(detail::dynamic_copy(t_));
    require(inverse.has_value(), who, "T", "must be invertible (condition number below 1/(n eps))");
    t_inverse_ = *inverse;
    identity_ = (t_.array() == StateMatrix::Identity(t_.rows(), t_.cols()).array()).all();
  }

  /// No coordinate change (T = I), output injection K — the choice of Algorithm 4.
  [[nodiscard]] static StaticTransform output_injection(GainMatrix K) {
    const Index n = K.rows();
    return StaticTransform(StateMatrix::Identity(n, n), std::move(K));
  }

  /// T = I, K = 0: the system is used as it is.
  [[nodiscard]] static StaticTransform identity(Index nx = D::nx, Index ny = D::ny) {
    return StaticTransform(StateMatrix::Identity(nx, nx), GainMatrix::Zero(nx, ny));
  }

  [[nodiscard]] const StateMatrix& T() const noexcept { return t_; }
  [[nodiscard]] const StateMatrix& T_inverse() const noexcept { return t_inverse_; }
  [[nodiscard]] const GainMatrix& K() const noexcept { return k_; }
  /// True when T is exactly the identity (the products by T are then skipped).
  [[nodiscard]] bool is_identity() const noexcept { return identity_; }

  /// Replaces K (e.g. the gain of a Riccati differential equation at the current sample).
  void set_output_injection(const GainMatrix& K) {
    require_finite_shape(K, k_.rows(), k_.cols(), "StaticTransform::set_output_injection", "K");
    k_ = K;
  }

  /// Matrices of (2) for the system (A, B, C) at one instant.
  void apply(const ContinuousSystem<D>& s, TransformedSystem<D>& out) const {
    if (identity_) {
      out.Ao = s.A;
      out.Co = s.C;
      out.TB = s.B;
    } else {
      detail::set_product(out.Co, s.C, t_inverse_);
      detail::set_product(out.TB, t_, s.B);
      // T (A T⁻¹) as two products of one type: a nested product instantiates a
      // kernel of its own; both forms evaluate A T⁻¹ into a temporary.
      StateMatrix a_t_inverse(s.A.rows(), t_inverse_.cols());
      detail::set_product(a_t_inverse, s.A, t_inverse_);
      detail::set_product(out.Ao, t_, a_t_inverse);
    }
    detail::subtract_product(out.Ao, k_, out.Co);
    out.K = k_;
  }

  [[nodiscard]] TransformedSystem<D> apply(const ContinuousSystem<D>& s) const {
    TransformedSystem<D> out;
    out.resize({s.A.rows(), s.B.cols(), s.C.rows(), 0});
    apply(s, out);
    return out;
  }

  /// \f$\Psi = T\Phi\f$.
  template <class DPhi, class DPsi>
  void regressor(const Eigen::MatrixBase<DPhi>& Phi, Eigen::MatrixBase<DPsi>& Psi) const {
    multiply_unless_identity(t_, Phi, Psi);
  }

  /// \f$\varphi = TBu + Ky\f$.
  template <class DPhi>
  void drive(const TransformedSystem<D>& s, const typename D::Input& u, const typename D::Output& y,
             Eigen::MatrixBase<DPhi>& phi) const {
    detail::set_product(phi, s.TB, u);
    detail::add_product(phi, s.K, y);
  }

  /// \f$x = T\eta\f$.
  [[nodiscard]] typename D::State to_transformed(const typename D::State& eta) const {
    return identity_ ? eta : typename D::State(t_ * eta);
  }
  /// \f$\eta = T^{-1}x\f$.
  template <class DX, class DEta>
  void to_original(const Eigen::MatrixBase<DX>& x, Eigen::MatrixBase<DEta>& eta) const {
    multiply_unless_identity(t_inverse_, x, eta);
  }

  /// Its fields for `snapshot` and `restore` (core/snapshot.hpp): T, its inverse and K.
  template <class Self, class Archive>
  static void visit_state(Self& self, Archive& archive) {
    archive("T", self.t_);
    archive("T_inverse", self.t_inverse_);
    archive("K", self.k_);
    archive("identity", self.identity_);
  }

 private:
  /// `out = m * in` with m either T or \f$T^{-1}\f$, a plain copy when T = I: the
  /// one place where the products by T are skipped.
  template <class DIn, class DOut>
  void multiply_unless_identity(const StateMatrix& m, const Eigen::MatrixBase<DIn>& in,
                                Eigen::MatrixBase<DOut>& out) const {
    if (identity_) {
      out = in;
    } else {
      detail::set_product(out, m, in);
    }
  }

  StateMatrix t_;
  StateMatrix t_inverse_;
  GainMatrix k_;
  bool identity_ = false;
};

}  // namespace adaptobs
