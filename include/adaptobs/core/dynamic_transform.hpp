#pragma once
/// \file
/// Dynamic transformation of Zhang (2005, §II-B, eq. (3)–(4)).
///
/// \f[ \dot\Xi = F(t)\Xi + G\Psi(t) \quad (3a),\qquad \Omega = H\Xi \quad (3b),\qquad
///     z = x - \Omega\theta \quad (3c). \f]
/// Applied to system (2) (derivation: \f$\dot z = \dot x - H(F\Xi + G\Psi)\theta\f$):
/// \f[ \dot z = A_o z + \varphi + \big[A_oH\Xi + \Psi - HF\Xi - HG\Psi\big]\theta,\qquad
///     y = C_o z + C_o\Omega\theta \quad (4a). \f]
/// Ξ is r × p; F is r × r, G is r × n, H is n × r, with G and H constant.
///
/// The four algorithms of Zhang (2005) all take \f$F(t) = G A_o(t) H\f$ (the
/// *projected* filter): Alg. 1 and 3 with G = [0 I], H = [0; I] (F = A22),
/// Alg. 2 with G = [−g I], H = [0; I] (F = A22 − g a12, with A_o the shift),
/// Alg. 4 with G = H = I (F = A_o). A constant F may be given instead.

#include <adaptobs/core/detail/products.hpp>
#include <adaptobs/core/dimensions.hpp>
#include <adaptobs/core/validation.hpp>

#include <Eigen/Core>

#include <optional>
#include <string_view>
#include <utility>

namespace adaptobs {

/// The filter (F, G, H) of eq. (3): Ξ is `R` × np, the state has `N` entries.
template <typename S, int N, int R>
class DynamicTransform {
 public:
  using Scalar = S;
  using FilterMatrix = Eigen::Matrix<S, R, R>;     ///< F
  using InjectionMatrix = Eigen::Matrix<S, R, N>;  ///< G
  using OutputMatrix = Eigen::Matrix<S, N, R>;     ///< H
  using StateMatrix = Eigen::Matrix<S, N, N>;
  static constexpr int filter_rows = R;
  /// G = H = I is possible only when Ξ has as many rows as the state.
  static constexpr bool may_be_identity = N == R || N == Eigen::Dynamic || R == Eigen::Dynamic;

  /// F(t) = G A_o(t) H, recomputed whenever A_o changes.
  [[nodiscard]] static DynamicTransform projected(InjectionMatrix G, OutputMatrix H) {
    return DynamicTransform(std::nullopt, std::move(G), std::move(H));
  }

  /// Constant F.
  DynamicTransform(FilterMatrix F, InjectionMatrix G, OutputMatrix H)
      : DynamicTransform(std::optional<FilterMatrix>(std::move(F)), std::move(G), std::move(H)) {}

  [[nodiscard]] Index rows() const noexcept { return g_.rows(); }
  [[nodiscard]] Index state_size() const noexcept { return g_.cols(); }
  [[nodiscard]] const InjectionMatrix& G() const noexcept { return g_; }
  [[nodiscard]] const OutputMatrix& H() const noexcept { return h_; }
  [[nodiscard]] bool is_projected() const noexcept { return !f_.has_value(); }
  /// True when G = H = I (Algorithm 4): the products by G and H are skipped.
  [[nodiscard]] bool identity() const noexcept { return may_be_identity && identity_; }

  /// F at the instant where the transformed system has matrix \f$A_o\f$; `AoH`
  /// (n × r) is the caller's scratch for the projected \f$F = G(A_oH)\f$, which
  /// keeps this function free of stored state (and of allocation: the
  /// observers size it once).
  template <class DA>
  void filter_matrix(const Eigen::MatrixBase<DA>& Ao, FilterMatrix& F, OutputMatrix& AoH) const {
    if (f_) {
      F = *f_;
    } else if (identity()) {
      if constexpr (may_be_identity) F = Ao;
    } else {
      detail::set_product(AoH, Ao, h_);
      detail::set_product(F, g_, AoH);
    }
  }

  [[nodiscard]] FilterMatrix filter_matrix(const StateMatrix& Ao) const {
    FilterMatrix F(rows(), rows());
    OutputMatrix AoH(state_size(), rows());
    filter_matrix(Ao, F, AoH);
    return F;
  }

  /// (3a) \f$\dot\Xi = F\Xi + G\Psi\f$.
  template <class DXi, class DPsi, class DOut>
  void derivative(const FilterMatrix& F, const Eigen::MatrixBase<DXi>& Xi, const Eigen::MatrixBase<DPsi>& Psi,
                  Eigen::MatrixBase<DOut>& dXi) const {
    detail::set_product(dXi, F, Xi);
    if (identity()) {
      if constexpr (may_be_identity) dXi += Psi;
    } else {
      detail::add_product(dXi, g_, Psi);
    }
  }

  /// (3b) \f$\Omega = H\Xi\f$.
  template <class DXi, class DOmega>
  void output(const Eigen::MatrixBase<DXi>& Xi, Eigen::MatrixBase<DOmega>& Omega) const {
    if (identity()) {
      if constexpr (may_be_identity) Omega = Xi;
    } else {
      detail::set_product(Omega, h_, Xi);
    }
  }

  /// The bracket of (4a): \f$A_oH\Xi + \Psi - HF\Xi - HG\Psi\f$ (n × p), the
  /// coefficient of θ in the equation of z. It is \f$\gamma\xi^T\f$ for Alg. 1–2,
  /// \f$[I; 0](A_{12}\Xi + \Psi_1)\f$ for Alg. 3 and 0 for Alg. 4.
  template <class DA, class DXi, class DPsi>
  [[nodiscard]] auto bracket(const Eigen::MatrixBase<DA>& Ao, const FilterMatrix& F, const Eigen::MatrixBase<DXi>& Xi,
                             const Eigen::MatrixBase<DPsi>& Psi) const {
    using Result = Eigen::Matrix<S, N, DPsi::ColsAtCompileTime>;
    Result omega = h_ * Xi;
    Result m = Ao * omega + Psi;
    m.noalias() -= h_ * (F * Xi);
    m.noalias() -= h_ * (g_ * Psi);
    return m;
  }

  /// Its fields for `snapshot` and `restore` (core/snapshot.hpp): F (when not
  /// projected), G and H; whether F is given is a setting.
  template <class Self, class Archive>
  static void visit_state(Self& self, Archive& archive) {
    archive.setting("projected", !self.f_.has_value());
    if (self.f_) archive("F", *self.f_);
    archive("G", self.g_);
    archive("H", self.h_);
    archive("identity", self.identity_);
  }

 private:
  DynamicTransform(std::optional<FilterMatrix> F, InjectionMatrix G, OutputMatrix H)
      : f_(std::move(F)), g_(std::move(G)), h_(std::move(H)) {
    constexpr std::string_view who = "DynamicTransform";
    require_finite(g_, who, "G");
    require_finite_shape(h_, g_.cols(), g_.rows(), who, "H");
    if (f_) {
      require_finite_shape(*f_, g_.rows(), g_.rows(), who, "F");
    }
    if constexpr (may_be_identity) {
      identity_ = g_.rows() == g_.cols() &&
                  (g_.array() == InjectionMatrix::Identity(g_.rows(), g_.cols()).array()).all() &&
                  (h_.array() == OutputMatrix::Identity(h_.rows(), h_.cols()).array()).all();
    }
  }

  std::optional<FilterMatrix> f_;
  InjectionMatrix g_;
  OutputMatrix h_;
  bool identity_ = false;
};

namespace detail {
/// r = n − m, the unmeasured states of the block forms (5), (7), (8) of
/// Algorithms 1–3 for a transform of n states with m measured ones. Refuses,
/// naming `argument`, a transform without states or measuring more states than
/// it has, before any block of size r is formed.
inline Index unmeasured_states(Index n, Index m, std::string_view who, std::string_view argument) {
  require(n >= 1, who, argument, "must have at least one state (T at least 1 x 1)");
  require(m <= n, who, argument, "must measure no more states than it has (K with at most as many columns as T rows)");
  return n - m;
}

/// G = [−g I_r] and H = [0; I_r] for a state of size n = m + r: the dynamic
/// transform shared by Algorithms 1–3, with F given or projected.
template <typename Scalar, int N, int R, class DG>
DynamicTransform<Scalar, N, R> block_transform(Index n, Index r, const Eigen::MatrixBase<DG>& g,
                                               std::optional<Eigen::Matrix<Scalar, R, R>> f = std::nullopt) {
  Eigen::Matrix<Scalar, R, N> gm = Eigen::Matrix<Scalar, R, N>::Zero(r, n);
  // Element by element: GCC 12 built for AVX reports a false -Warray-bounds on
  // Eigen's packet copy of a small fixed g into this runtime-width block.
  for (Index j = 0; j < n - r; ++j)
    for (Index i = 0; i < r; ++i) gm(i, j) = -g(i, j);
  gm.rightCols(r).setIdentity();
  Eigen::Matrix<Scalar, N, R> hm = Eigen::Matrix<Scalar, N, R>::Zero(n, r);
  hm.bottomRows(r).setIdentity();
  if (f) return DynamicTransform<Scalar, N, R>(std::move(*f), std::move(gm), std::move(hm));
  return DynamicTransform<Scalar, N, R>::projected(std::move(gm), std::move(hm));
}
}  // namespace detail

}  // namespace adaptobs
