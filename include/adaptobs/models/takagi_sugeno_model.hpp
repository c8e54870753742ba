#pragma once
/// \file
/// Takagi–Sugeno (polytopic quasi-LPV) models with unknown parameters, built by
/// the sector-nonlinearity transformation (Srinivasarengan et al. (2018),
/// eq. (9)–(11), Remark 1, eq. (19) and (64)).
///
/// A quasi-LPV system \f$x_{k+1} = A(z_k,\theta)x_k + B(z_k,\theta)u_k\f$,
/// \f$y_k = Cx_k\f$, whose matrices are affine in each premise variable
/// \f$z_j \in [z_j^1, z_j^2]\f$ and in each parameter \f$\theta_l \in [\theta_l^1, \theta_l^2]\f$,
/// is exactly (inside the sectors) the convex blend of \f$r = 2^{n_z + n_\theta}\f$ vertices
/// \f[ x_{k+1} = \sum_{i=1}^{r} h_i(z_k,\theta)\,(A_i x_k + B_i u_k),\qquad y_k = Cx_k \qquad (64). \f]
/// Each premise variable or parameter \f$v \in [v^1, v^2]\f$ has the two memberships (10)
/// \f$\mu^1(v) = (v^2 - v)/(v^2 - v^1)\f$ (lower bound) and \f$\mu^2(v) = (v - v^1)/(v^2 - v^1)\f$
/// (upper bound), and the weight of a vertex is the product of one membership per
/// premise variable and per parameter (Remark 1).
///
/// **Vertex order.** The premise vector is \f$v = (z_1, \dots, z_{n_z}, \theta_1, \dots, \theta_{n_\theta})\f$
/// and vertex i (0-based) takes the upper bound of \f$v_j\f$ when bit \f$k - 1 - j\f$ of i is
/// set, \f$k = n_z + n_\theta\f$: \f$z_1\f$ is the most significant bit and the last parameter
/// the least significant. For the waste water plant of §6, \f$(z_1, z_2, \theta)\f$ gives
/// \f$i = 4j_{z_1} + 2j_{z_2} + j_\theta\f$ (0 = lower bound), the order of the printed
/// \f$A_1, \dots, A_8\f$.
///
/// **Convex sum.** Premise variables and parameters are clipped to their sectors
/// before the memberships are formed, so \f$h_i \ge 0\f$ and \f$\sum_i h_i = 1\f$ for
/// every finite input (11), also outside the sectors, where the blend is the
/// model at the nearest point of the box.

#include <adaptobs/core/detail/products.hpp>
#include <adaptobs/core/dimensions.hpp>
#include <adaptobs/core/validation.hpp>

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <concepts>
#include <cstdint>
#include <iterator>
#include <optional>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

namespace adaptobs {

/// Gains of `TakagiSugenoObserver` (declared here, below both the observer and
/// the LMI synthesis that produces them): one \f$L_i\f$ and one \f$K_{y,i}\f$ per vertex, in the
/// vertex order of the model, and the optional leakage \f$K_\theta\f$ of eq. (21).
template <StateSpace D>
struct TakagiSugenoGains {
  using ParameterGain = Eigen::Matrix<typename D::Scalar, D::np, D::ny>;
  std::vector<typename D::GainMatrix> L;  ///< \f$L_i \in \mathbb{R}^{n_x\times n_y}\f$
  std::vector<ParameterGain> K;           ///< \f$K_{y,i} \in \mathbb{R}^{n_\theta\times n_y}\f$
  /// \f$K_\theta \in \mathbb{R}^{n_\theta\times n_\theta}\f$: empty for constant parameters (eq. (65)),
  /// set for the time-varying-parameter observer (eq. (21)).
  std::optional<typename D::ParameterMatrix> K_theta;
};

/// Number of vertices \f$2^{n_z + n_\theta}\f$ known at compile time (or `Eigen::Dynamic`).
[[nodiscard]] constexpr int takagi_sugeno_vertex_count(int nz, int np) noexcept {
  return (nz == Eigen::Dynamic || np == Eigen::Dynamic) ? Eigen::Dynamic : (1 << (nz + np));
}

/// Sector \f$[v^1, v^2]\f$ of each of N premise variables or parameters (eq. (9), (74), (76)).
template <typename S, int N>
struct SectorBounds {
  Eigen::Matrix<S, N, 1> lower;
  Eigen::Matrix<S, N, 1> upper;

  [[nodiscard]] Index size() const noexcept { return lower.size(); }
  /// True when every \f$v_j \in [v_j^1, v_j^2]\f$.
  template <class Derived>
  [[nodiscard]] bool contains(const Eigen::MatrixBase<Derived>& v) const {
    for (Index j = 0; j < v.size(); ++j)
      if (!(v(j) >= lower(j) && v(j) <= upper(j))) return false;
    return true;
  }
  /// The point of the box nearest to v (each coordinate clipped to its sector).
  template <class Derived>
  [[nodiscard]] Eigen::Matrix<S, N, 1> clip(const Eigen::MatrixBase<Derived>& v) const {
    return v.cwiseMax(lower).cwiseMin(upper);
  }
};

namespace detail {

[[noreturn]] inline void fail_sector(Index entry, double lower, double upper, std::string_view who,
                                     std::string_view argument) {
  Message os;
  os << "must have lower < upper, with upper - lower finite, in every entry (entry " << entry << ": [" << lower << ", "
     << upper << "])";
  fail_argument(who, argument, os.str());
}

template <typename S, int N>
void validate_sectors(const SectorBounds<S, N>& bounds, Index expected_size, std::string_view who,
                      std::string_view argument) {
  require_finite_shape(bounds.lower, expected_size, 1, who, argument);
  require_finite_shape(bounds.upper, expected_size, 1, who, argument);
  for (Index j = 0; j < expected_size; ++j) {
    // The memberships divide by upper − lower, which must be representable.
    if (!(bounds.lower(j) < bounds.upper(j)) || !std::isfinite(bounds.upper(j) - bounds.lower(j)))
      fail_sector(j, double(bounds.lower(j)), double(bounds.upper(j)), who, argument);
  }
}

/// Multiplies the weights of the first `filled` vertices by the two memberships of
/// \f$v \in [lo, hi]\f$ (clipped), doubling the filled length: entry i becomes entries
/// 2i (lower bound, \f$\mu^1\f$) and 2i + 1 (upper bound, \f$\mu^2\f$). Run backwards, so
/// the expansion happens in place.
template <typename S, class Derived>
void expand_weights(Eigen::MatrixBase<Derived>& h, Index filled, S v, S lo, S hi) {
  // μ²(v) of eq. (10), exactly 0 and 1 at and beyond the sector's ends. The reciprocal
  // of the width does not depend on v, so its division stays off the critical path
  // of an update; min(·, 1) absorbs its rounding (and passes a NaN on).
  const S scaled = (v - lo) * (S(1) / (hi - lo));
  const S upper = v >= hi ? S(1) : (v <= lo ? S(0) : std::min(scaled, S(1)));
  const S lower = S(1) - upper;  // μ¹(v) = 1 − μ²(v) ∈ [0, 1]: the pair sums to 1 exactly
  for (Index i = filled - 1; i >= 0; --i) {
    const S hi_weight = h(i) * upper;
    h(2 * i) = h(i) * lower;
    h(2 * i + 1) = hi_weight;
  }
}

}  // namespace detail

/// Sector-nonlinearity weights \f$h_i(z, \theta)\f$ of all \f$2^{n_z+n_\theta}\f$ vertices
/// (eq. (10), Remark 1, (64)) into `h`, in the vertex order of this file.
///
/// Each premise variable and parameter is clipped to its sector first, so the
/// weights are non-negative and sum to 1 (11) for any finite arguments. `h`
/// must already have \f$2^{n_z+n_\theta}\f$ entries.
template <typename S, int NZ, int NP, class DZ, class DT, class DH>
void sector_weights(const Eigen::MatrixBase<DZ>& z, const SectorBounds<S, NZ>& premise_bounds,
                    const Eigen::MatrixBase<DT>& theta, const SectorBounds<S, NP>& parameter_bounds,
                    Eigen::MatrixBase<DH>& h) {
  // Every entry is written below; zeroing first lets compilers see it. A loop, not
  // setZero: Eigen's nullary assignment is a dozen instantiations per weight type.
  for (Index i = 0; i < h.size(); ++i) h(i) = S(0);
  h(0) = S(1);
  Index filled = 1;
  for (Index j = 0; j < z.size(); ++j, filled *= 2)
    detail::expand_weights(h, filled, S(z(j)), premise_bounds.lower(j), premise_bounds.upper(j));
  for (Index l = 0; l < theta.size(); ++l, filled *= 2)
    detail::expand_weights(h, filled, S(theta(l)), parameter_bounds.lower(l), parameter_bounds.upper(l));
}

/// Matrices of a quasi-LPV system at one point \f$(z, \theta)\f$, or of one vertex.
template <StateSpace D>
struct TakagiSugenoVertex {
  typename D::StateMatrix A;
  typename D::InputMatrix B;
};

/// The vertex values \f$(z^{(i)}, \theta^{(i)})\f$ of vertex i (0-based): each coordinate at the
/// lower or upper end of its sector according to the bits of i.
template <typename S, int NZ, int NP>
void vertex_point(Index i, const SectorBounds<S, NZ>& premise_bounds, const SectorBounds<S, NP>& parameter_bounds,
                  Eigen::Matrix<S, NZ, 1>& z, Eigen::Matrix<S, NP, 1>& theta) {
  const Index nz = premise_bounds.size();
  const Index k = nz + parameter_bounds.size();
  z.resize(nz);
  theta.resize(parameter_bounds.size());
  for (Index j = 0; j < k; ++j) {
    const bool upper = ((i >> (k - 1 - j)) & 1) != 0;
    if (j < nz) {
      z(j) = upper ? premise_bounds.upper(j) : premise_bounds.lower(j);
    } else {
      theta(j - nz) = upper ? parameter_bounds.upper(j - nz) : parameter_bounds.lower(j - nz);
    }
  }
}

/// The \f$2^{n_z+n_\theta}\f$ vertices \f$(A_i, B_i)\f$ of a quasi-LPV description
/// `matrices_at(z, θ) -> TakagiSugenoVertex<D>` by the sector-nonlinearity
/// transformation (eq. (16)–(20), (64)): \f$A_i = A(z^{(i)}, \theta^{(i)})\f$.
///
/// The polytopic model reproduces the quasi-LPV one exactly inside the sectors
/// when \f$A(z,\theta)\f$ and \f$B(z,\theta)\f$ are affine in each premise variable and
/// each parameter separately (e.g. \f$a\,z_2 = (a_0 + \theta)z_2\f$).
template <StateSpace D, int NZ, class F>
  requires std::invocable<const F&, const Eigen::Matrix<typename D::Scalar, NZ, 1>&, const typename D::Parameters&>
[[nodiscard]] std::vector<TakagiSugenoVertex<D>> sector_vertices(
    const F& matrices_at, const SectorBounds<typename D::Scalar, NZ>& premise_bounds,
    const SectorBounds<typename D::Scalar, D::np>& parameter_bounds) {
  constexpr std::string_view who = "sector_vertices";
  using S = typename D::Scalar;
  detail::validate_sectors(premise_bounds, premise_bounds.lower.size(), who, "premise_bounds");
  detail::validate_sectors(parameter_bounds, parameter_bounds.lower.size(), who, "parameter_bounds");
  const Index k = premise_bounds.size() + parameter_bounds.size();
  require(k <= 20, who, "premise_bounds", "with parameter_bounds gives more than 2^20 vertices");
  const Index r = Index(1) << k;
  std::vector<TakagiSugenoVertex<D>> vertices(static_cast<std::size_t>(r));
  Eigen::Matrix<S, NZ, 1> z;
  typename D::Parameters theta;
  for (Index i = 0; i < r; ++i) {
    vertex_point(i, premise_bounds, parameter_bounds, z, theta);
    vertices[static_cast<std::size_t>(i)] = matrices_at(std::as_const(z), std::as_const(theta));
  }
  return vertices;
}

/// Polytopic (Takagi–Sugeno) model (64) with unknown parameters: vertices
/// \f$(A_i, B_i)\f$, output matrix C, the premise variables as a user function of
/// \f$(x, u, \theta)\f$ and the sectors of premise variables and parameters.
///
/// The premise function may use states that are not measured (the plant of §6
/// has \f$z_2 = x_1/(x_2 + b)\f$); an observer then evaluates it at the estimates
/// \f$(\hat x, u, \hat\theta)\f$. It is called as `premises(x, u, theta)` and returns the
/// \f$n_z\f$ premise variables.
template <StateSpace D, int NZ, class PremiseFn>
class TakagiSugenoModel : public D {
 public:
  using typename D::Scalar, typename D::State, typename D::Input, typename D::Parameters, typename D::StateMatrix,
      typename D::InputMatrix, typename D::OutputMatrix;
  static constexpr int nz = NZ;
  static constexpr int vertices_at_compile_time = takagi_sugeno_vertex_count(NZ, D::np);
  using PremiseVector = Eigen::Matrix<Scalar, NZ, 1>;
  using Weights = Eigen::Matrix<Scalar, vertices_at_compile_time, 1>;
  using Vertex = TakagiSugenoVertex<D>;
  using PremiseSectors = SectorBounds<Scalar, NZ>;
  using ParameterSectors = SectorBounds<Scalar, D::np>;

  static_assert(std::is_invocable_v<const PremiseFn&, const State&, const Input&, const Parameters&>,
                "TakagiSugenoModel: the premise function must be callable as premises(x, u, theta)");

  /// \param vertices \f$(A_i, B_i)\f$ in the vertex order of this file (see `sector_vertices`);
  /// \param C output matrix; \param premises `premises(x, u, theta)` → \f$z\f$;
  /// \param premise_bounds, parameter_bounds the sectors of \f$z\f$ and \f$\theta\f$.
  TakagiSugenoModel(const std::vector<TakagiSugenoVertex<D>>& vertices, OutputMatrix C, PremiseFn premises,
                    PremiseSectors premise_bounds, ParameterSectors parameter_bounds)
      : vertices_(vertices),
        C_(std::move(C)),
        premises_(std::move(premises)),
        premise_bounds_(std::move(premise_bounds)),
        parameter_bounds_(std::move(parameter_bounds)) {
    constexpr std::string_view who = "TakagiSugenoModel";
    detail::validate_sectors(premise_bounds_, premise_bounds_.lower.size(), who, "premise_bounds");
    detail::validate_sectors(parameter_bounds_, parameter_bounds_.lower.size(), who, "parameter_bounds");
    const Index k = premise_bounds_.size() + parameter_bounds_.size();
    require(k <= 20, who, "premise_bounds", "with parameter_bounds gives more than 2^20 vertices");
    const Index r = Index(1) << k;
    if (std::ssize(vertices) != r) detail::fail_count(r, vertices.size(), "2^(nz + np) vertices", who, "vertices");
    const Index nx = vertices_.front().A.rows();
    const Index nu = vertices_.front().B.cols();
    for (const Vertex& v : vertices_) {
      require_finite_shape(v.A, nx, nx, who, "vertices[i].A");
      require_finite_shape(v.B, nx, nu, who, "vertices[i].B");
    }
    require_finite_shape(C_, C_.rows(), nx, who, "C");
  }

  [[nodiscard]] Sizes sizes() const noexcept {
    return {vertices_.front().A.rows(), vertices_.front().B.cols(), C_.rows(), parameter_bounds_.size()};
  }
  [[nodiscard]] Index premise_count() const noexcept { return premise_bounds_.size(); }
  /// \f$r = 2^{n_z + n_\theta}\f$.
  [[nodiscard]] Index vertex_count() const noexcept {
    return Index(1) << (premise_bounds_.size() + parameter_bounds_.size());
  }

  /// Vertex matrices \f$A_i\f$, \f$B_i\f$ of (64) (0-based i) and the output matrix C.
  [[nodiscard]] const StateMatrix& A(Index i) const { return vertices_[static_cast<std::size_t>(i)].A; }
  [[nodiscard]] const InputMatrix& B(Index i) const { return vertices_[static_cast<std::size_t>(i)].B; }
  [[nodiscard]] const OutputMatrix& C() const noexcept { return C_; }
  [[nodiscard]] const PremiseSectors& premise_bounds() const noexcept { return premise_bounds_; }
  [[nodiscard]] const ParameterSectors& parameter_bounds() const noexcept { return parameter_bounds_; }
  [[nodiscard]] const PremiseFn& premise_function() const noexcept { return premises_; }

  /// Premise variables \f$z = z(x, u, \theta)\f$ (unclipped).
  /// A result of the wrong run-time size throws a `ConfigurationError` naming the
  /// premise function, before it is copied: with `Eigen::Dynamic` sizes nothing
  /// else would stop the weights from reading past its end.
  [[nodiscard]] PremiseVector premises(const State& x, const Input& u, const Parameters& theta) const {
    PremiseVector z(premise_count());
    premises(x, u, theta, z);
    return z;
  }
  /// The same, written into `z` of the right size, e.g. an observer's
  /// workspace: with a run-time \f$n_z\f$ a returned vector would be allocated at
  /// every call (a premise function returning a fixed-size vector allocates nothing).
  void premises(const State& x, const Input& u, const Parameters& theta, PremiseVector& z) const {
    decltype(auto) value = premises_(x, u, theta);
    if constexpr (requires {
                    value.rows();
                    value.cols();
                  }) {
      require_shape(value, premise_count(), 1, "TakagiSugenoModel", "premises(x, u, theta)");
      z = value;
    } else {
      z = PremiseVector(value);
    }
  }

  /// Weights \f$h_i(z, \theta)\f$ of every vertex (clipped to the sectors; Remark 1).
  template <class DZ, class DT, class DH>
  void weights(const Eigen::MatrixBase<DZ>& z, const Eigen::MatrixBase<DT>& theta, Eigen::MatrixBase<DH>& h) const {
    sector_weights(z, premise_bounds_, theta, parameter_bounds_, h);
  }
  [[nodiscard]] Weights weights(const PremiseVector& z, const Parameters& theta) const {
    Weights h(vertex_count());
    weights(z, theta, h);
    return h;
  }

  /// \f$\sum_i h_i A_i\f$ and \f$\sum_i h_i B_i\f$ for given weights.
  template <class DH>
  [[nodiscard]] StateMatrix blended_A(const Eigen::MatrixBase<DH>& h) const {
    const Index nx = sizes().nx;
    StateMatrix a = StateMatrix::Zero(nx, nx);
    for (Index i = 0; i < vertex_count(); ++i) a += h(i) * A(i);
    return a;
  }
  template <class DH>
  [[nodiscard]] InputMatrix blended_B(const Eigen::MatrixBase<DH>& h) const {
    const Sizes s = sizes();
    InputMatrix b = InputMatrix::Zero(s.nx, s.nu);
    for (Index i = 0; i < vertex_count(); ++i) b += h(i) * B(i);
    return b;
  }

  /// Its fields for `snapshot` and `restore` (core/snapshot.hpp): the vertex
  /// matrices side by side as \f$\mathcal{A} = [A_1 \cdots A_r]\f$ and
  /// \f$\mathcal{B} = [B_1 \cdots B_r]\f$ (24)–(25), C and the sectors (9). The premise
  /// function is code, not state: a restored model keeps its own. The values read
  /// are checked as the constructor checks them, so that a damaged snapshot cannot
  /// give weights that do not sum to 1 (11).
  static constexpr std::string_view snapshot_type = "TakagiSugenoModel";
  static constexpr int snapshot_version = 1;
  template <class Self, class Archive>
  static void visit_state(Self& self, Archive& archive) {
    const Sizes s = self.sizes();
    const Index r = self.vertex_count();
    Eigen::Matrix<Scalar, D::nx, product_of_sizes(D::nx, vertices_at_compile_time)> A(s.nx, s.nx * r);
    Eigen::Matrix<Scalar, D::nx, product_of_sizes(D::nu, vertices_at_compile_time)> B(s.nx, s.nu * r);
    for (Index i = 0; i < r; ++i) {
      A.middleCols(i * s.nx, s.nx) = self.A(i);
      B.middleCols(i * s.nu, s.nu) = self.B(i);
    }
    archive("A", A);
    archive("B", B);
    archive("C", self.C_);
    archive("premise_bounds.lower", self.premise_bounds_.lower);
    archive("premise_bounds.upper", self.premise_bounds_.upper);
    archive("parameter_bounds.lower", self.parameter_bounds_.lower);
    archive("parameter_bounds.upper", self.parameter_bounds_.upper);
    if constexpr (Archive::reading) {
      constexpr std::string_view who = "restore";
      require_finite(A, who, "snapshot field 'A'");
      require_finite(B, who, "snapshot field 'B'");
      require_finite(self.C_, who, "snapshot field 'C'");
      detail::validate_sectors(self.premise_bounds_, self.premise_bounds_.size(), who,
                               "snapshot field 'premise_bounds'");
      detail::validate_sectors(self.parameter_bounds_, self.parameter_bounds_.size(), who,
                               "snapshot field 'parameter_bounds'");
      for (Index i = 0; i < r; ++i) {
        Vertex& v = self.vertices_[static_cast<std::size_t>(i)];
        v.A = A.middleCols(i * s.nx, s.nx);
        v.B = B.middleCols(i * s.nu, s.nu);
      }
    }
  }

  /// One step of the polytopic model (64):
  /// \f$x_{k+1} = \sum_i h_i(z(x_k, u_k, \theta), \theta)(A_i x_k + B_i u_k)\f$.
  [[nodiscard]] State step(const State& x, const Input& u, const Parameters& theta) const {
    const Weights h = weights(premises(x, u, theta), theta);
    State next = blended_A(h) * x;
    detail::add_product(next, blended_B(h), u);
    return next;
  }

 private:
  std::vector<Vertex> vertices_;  // (A_i, B_i), i = 0..r−1, in the vertex order of this file
  OutputMatrix C_;
  PremiseFn premises_;
  PremiseSectors premise_bounds_;
  ParameterSectors parameter_bounds_;
};

/// A polytopic model (64) as a Takagi–Sugeno observer and its LMI design read
/// it: its sizes and number of vertices \f$r\f$, the matrices \f$A_i\f$, \f$B_i\f$ of
/// vertex i and C, the premise variables \f$z(x, u, \theta)\f$, their weights
/// \f$h_i(z, \theta)\f$ and the sectors of z and θ (`TakagiSugenoModel` is one).
/// A model that also writes the premise variables into a given vector,
/// `premises(x, u, theta, z)`, is called so by the observer, whose update then
/// allocates nothing with a run-time \f$n_z\f$.
template <class M>
concept TakagiSugenoSystem =
    StateSpace<typename M::Dims> &&
    requires(const M& m, Index i, const typename M::Dims::State& x, const typename M::Dims::Input& u,
             const typename M::Dims::Parameters& theta, const typename M::PremiseVector& z, typename M::Weights& h) {
      { M::vertices_at_compile_time } -> std::convertible_to<int>;
      { m.sizes() } -> std::same_as<Sizes>;
      { m.vertex_count() } -> std::convertible_to<Index>;
      { m.premise_count() } -> std::convertible_to<Index>;
      { m.A(i) } -> std::convertible_to<const typename M::Dims::StateMatrix&>;
      { m.B(i) } -> std::convertible_to<const typename M::Dims::InputMatrix&>;
      { m.C() } -> std::convertible_to<const typename M::Dims::OutputMatrix&>;
      { m.premises(x, u, theta) } -> std::convertible_to<typename M::PremiseVector>;
      m.weights(z, theta, h);
      m.premise_bounds();
      m.parameter_bounds();
    };

/// Builds the polytopic model of a quasi-LPV description in one call: the vertices
/// come from `sector_vertices(matrices_at, premise_bounds, parameter_bounds)`.
template <StateSpace D, int NZ, class F, class PremiseFn>
[[nodiscard]] TakagiSugenoModel<D, NZ, PremiseFn> make_takagi_sugeno_model(
    const F& matrices_at, typename D::OutputMatrix C, PremiseFn premises,
    SectorBounds<typename D::Scalar, NZ> premise_bounds, SectorBounds<typename D::Scalar, D::np> parameter_bounds) {
  return TakagiSugenoModel<D, NZ, PremiseFn>(sector_vertices<D, NZ>(matrices_at, premise_bounds, parameter_bounds),
                                             std::move(C), std::move(premises), std::move(premise_bounds),
                                             std::move(parameter_bounds));
}

}  // namespace adaptobs
