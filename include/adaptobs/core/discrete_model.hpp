#pragma once
/// \file
/// Discrete-time linear models \f$x_{k+1} = A_k x_k + B_k u_k + f_k + \Psi_k\theta,\; y_k = C_k x_k\f$.
///
/// A model supplies the known matrices \f$(A_k, B_k, C_k)\f$ of step k. The
/// regressor \f$\Psi_k\f$ and the known input term \f$f_k\f$ are measured
/// signals and travel with the sample (`DiscreteSample`), not with the model.

#include <adaptobs/core/detail/commit.hpp>
#include <adaptobs/core/detail/message.hpp>
#include <adaptobs/core/detail/update_workspace.hpp>
#include <adaptobs/core/dimensions.hpp>
#include <adaptobs/core/time_invariance.hpp>
#include <adaptobs/core/validation.hpp>

#include <cmath>
#include <concepts>
#include <string_view>
#include <utility>

namespace adaptobs {

/// The known matrices of one step of a discrete-time linear system.
template <StateSpace D>
struct DiscreteSystem {
  typename D::StateMatrix A;
  typename D::InputMatrix B;
  typename D::OutputMatrix C;
};

/// One measured sample of a discrete-time system with unknown parameters:
/// input \f$u_k\f$, output \f$y_k\f$, known regressor \f$\Psi_k\f$ and, optionally,
/// a known input term \f$f_k\f$.
///
/// `f` is Remark 1 of Guyader & Zhang (2003): in eq. (1b), \f$B_ku_k\f$ may be
/// joined by any known function of measured data, \f$x_{k+1} = A_kx_k + B_ku_k +
/// f_k + \Psi_k\theta\f$, with \f$f_k\f$ computed at step k from \f$u_k\f$, \f$y_k\f$ or
/// other measured signals, never from the unmeasured state. It is known, so it
/// enters the estimate as it enters the state and cancels in the state error:
/// the observers' error recursions hold unchanged (docs/readings/guyader_zhang.md).
/// Empty (the default) means \f$f_k = 0\f$, and the step is then the one
/// without the term, bit for bit; otherwise it has nx entries. It is stored in
/// place for a fixed nx (`Dims::KnownInput`), so an empty term costs no allocation.
template <StateSpace D>
struct DiscreteSample {
  typename D::Input u;
  typename D::Output y;
  typename D::RegressorMatrix Psi;
  typename D::KnownInput f{};  ///< \f$f_k\f$: nx entries, or none for \f$f_k = 0\f$
};

/// One measured sample of a system with no separately measured regressor:
/// input \f$u_k\f$ and output \f$y_k\f$ (e.g. a Takagi–Sugeno model, where the
/// parameters act through the model's weights).
template <StateSpace D>
struct InputOutputSample {
  typename D::Input u;
  typename D::Output y;
};

namespace detail {

/// Throws `ConfigurationError` naming the first entry of a run-time-sized sample
/// whose shape disagrees with the model's sizes `s`, before anything reads it.
template <StateSpace D>
void require_sample_sizes(const InputOutputSample<D>& sample, const Sizes& s, std::string_view who) {
  require_shape(sample.u, s.nu, 1, who, "sample.u");
  require_shape(sample.y, s.ny, 1, who, "sample.y");
}

/// The same for a sample with a regressor, which must be nx × np.
template <StateSpace D>
void require_sample_sizes(const DiscreteSample<D>& sample, const Sizes& s, std::string_view who) {
  require_shape(sample.u, s.nu, 1, who, "sample.u");
  require_shape(sample.y, s.ny, 1, who, "sample.y");
  require_shape(sample.Psi, s.nx, s.np, who, "sample.Psi");
}

[[noreturn]] inline void fail_known_input_size(Index nx, Index got, std::string_view who) {
  Message os;
  os << "must have nx = " << nx << " entries, or none for no known input term (got " << got << ")";
  fail_argument(who, "sample.f", os.str());
}

/// Throws `ConfigurationError` naming `sample.f` when the known input term of a
/// sample has neither nx entries nor none. Its size is a run-time one even for
/// a fixed nx, so it is checked whatever the sizes; a sample without the term
/// has nothing to check.
template <StateSpace D>
void require_known_input_size(const DiscreteSample<D>& sample, Index nx, std::string_view who) {
  if (sample.f.size() != 0 && sample.f.size() != nx) fail_known_input_size(nx, sample.f.size(), who);
}
template <StateSpace D>
void require_known_input_size(const InputOutputSample<D>& /*sample*/, Index /*nx*/, std::string_view /*who*/) {}

/// `x += f` for a known input term f of nx entries; nothing for an empty one (\f$f = 0\f$).
template <class X, class F>
void add_known_input(X& x, const F& f) {
  if (f.size() != 0) x += f;
}

/// True when u, Ψ, f and the entries of y whose channel is present (all of them
/// for a null mask) are finite. An empty f is not looked at: a sample without
/// the term is checked as it is without the field.
template <StateSpace D>
[[nodiscard]] bool finite_sample(const DiscreteSample<D>& sample, const OutputMask<D>* present) {
  return finite_measured(sample.y, present, sample.u, sample.Psi) && (sample.f.size() == 0 || all_finite(sample.f));
}

/// True when u and the entries of y whose channel is present are finite.
template <StateSpace D>
[[nodiscard]] bool finite_sample(const InputOutputSample<D>& sample, const OutputMask<D>* present) {
  return finite_measured(sample.y, present, sample.u);
}

}  // namespace detail

/// A discrete-time model: `at(k)` gives the matrices of step k.
template <class M>
concept DiscreteModel = StateSpace<typename M::Dims> && requires(const M& m, Index k) {
  { m.at(k) } -> std::convertible_to<const DiscreteSystem<typename M::Dims>&>;
  { M::time_invariant } -> std::convertible_to<bool>;
  { m.sizes() } -> std::same_as<Sizes>;
};

namespace detail {
template <StateSpace D>
void validate_system(const DiscreteSystem<D>& s, Index np, std::string_view who, std::string_view np_name) {
  validate_state_space(s, who);
  require_size<D::np>(np, who, np_name);
}
}  // namespace detail

/// Time-invariant discrete model: the same \f$(A, B, C)\f$ at every step.
template <StateSpace D>
class DiscreteLtiModel : public D {
 public:
  static constexpr bool time_invariant = true;

  /// \param np number of unknown parameters (`D::np` itself when that is fixed).
  /// Compile-time sizes that disagree with D's are refused by a `static_assert`
  /// naming the matrix; run-time sizes are checked against the order of A.
  template <class DA, class DB, class DC>
  DiscreteLtiModel(const Eigen::MatrixBase<DA>& A, const Eigen::MatrixBase<DB>& B, const Eigen::MatrixBase<DC>& C,
                   Index np = D::np)
      : system_{detail::fitted<typename D::StateMatrix>(A), detail::fitted<typename D::InputMatrix>(B),
                detail::fitted<typename D::OutputMatrix>(C)},
        np_(np) {
    static_assert(detail::fits_size<DA, D::nx, D::nx>, "DiscreteLtiModel: A must be nx x nx");
    static_assert(detail::fits_size<DB, D::nx, D::nu>, "DiscreteLtiModel: B must be nx x nu");
    static_assert(detail::fits_size<DC, D::ny, D::nx>, "DiscreteLtiModel: C must be ny x nx");
    detail::validate_system(system_, np_, "DiscreteLtiModel", "np");
  }

  [[nodiscard]] const DiscreteSystem<D>& at(Index /*k*/) const noexcept { return system_; }
  [[nodiscard]] const DiscreteSystem<D>& system() const noexcept { return system_; }
  [[nodiscard]] Sizes sizes() const noexcept { return {system_.A.rows(), system_.B.cols(), system_.C.rows(), np_}; }

  /// Its fields for `snapshot` and `restore` (core/snapshot.hpp): A, B, C; np a setting.
  static constexpr std::string_view snapshot_type = "DiscreteLtiModel";
  static constexpr int snapshot_version = 1;
  template <class Self, class Archive>
  static void visit_state(Self& self, Archive& archive) {
    archive("A", self.system_.A);
    archive("B", self.system_.B);
    archive("C", self.system_.C);
    archive.setting("np", self.np_);
  }

 private:
  DiscreteSystem<D> system_;
  Index np_;
};

/// Time-varying discrete model: a callable `k -> DiscreteSystem<D>` gives the
/// matrices of each step. Sizes are stated once at construction.
template <StateSpace D, std::invocable<Index> F>
  requires std::convertible_to<std::invoke_result_t<const F&, Index>, DiscreteSystem<D>>
class DiscreteLtvModel : public D {
 public:
  static constexpr bool time_invariant = false;

  explicit DiscreteLtvModel(F matrices_at, Sizes sizes = {D::nx, D::nu, D::ny, D::np})
      : matrices_at_(std::move(matrices_at)), sizes_(sizes) {
    constexpr std::string_view who = "DiscreteLtvModel";
    require(sizes_.nx >= 0 && sizes_.nu >= 0 && sizes_.ny >= 0 && sizes_.np >= 0, who, "sizes",
            "must be non-negative (dynamic dimensions need explicit sizes)");
    const DiscreteSystem<D> first = matrices_at_(Index{0});
    detail::validate_system(first, sizes_.np, who, "sizes.np");
    require(first.A.rows() == sizes_.nx && first.B.cols() == sizes_.nu && first.C.rows() == sizes_.ny, who,
            "matrices_at", "returns matrices whose sizes differ from 'sizes'");
  }

  /// \f$(A_k, B_k, C_k)\f$; with dynamic sizes, matrices of other sizes than
  /// `sizes` throw a `ConfigurationError` naming `matrices_at(k)`, at any k.
  [[nodiscard]] DiscreteSystem<D> at(Index k) const {
    DiscreteSystem<D> system = matrices_at_(k);
    if constexpr (!D::is_fixed) require_system_sizes(system, sizes_, "DiscreteLtvModel", "matrices_at(k)");
    return system;
  }
  [[nodiscard]] Sizes sizes() const noexcept { return sizes_; }

 private:
  F matrices_at_;
  Sizes sizes_;
};

/// Deduces the dimensions from the callable's result: `make_discrete_ltv_model<D>(f)`.
template <StateSpace D, class F>
[[nodiscard]] auto make_discrete_ltv_model(F matrices_at, Sizes sizes = {D::nx, D::nu, D::ny, D::np}) {
  return DiscreteLtvModel<D, F>(std::move(matrices_at), sizes);
}

}  // namespace adaptobs
