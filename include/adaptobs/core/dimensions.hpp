#pragma once
/// \file
/// Compile-time sizes and the Eigen types derived from them, in one place.
///
/// Every model and observer of adaptobs is parameterized by a `Dimensions`
/// type: the scalar and the four sizes `nx` (state), `nu` (input), `ny`
/// (output) and `np` (unknown parameters). Sizes are `int` as in Eigen and may
/// be `Eigen::Dynamic`, in which case the actual sizes are fixed at
/// construction and never change afterwards.

#include <Eigen/Core>

#include <concepts>
#include <type_traits>

namespace adaptobs {

using Index = Eigen::Index;

/// Size of a block made of two stacked parts (e.g. the augmented state [x; θ]).
[[nodiscard]] constexpr int sum_of_sizes(int a, int b) noexcept {
  return (a == Eigen::Dynamic || b == Eigen::Dynamic) ? Eigen::Dynamic : a + b;
}

/// Size of `a` minus `b` (e.g. the unmeasured part n − m of a state).
[[nodiscard]] constexpr int difference_of_sizes(int a, int b) noexcept {
  return (a == Eigen::Dynamic || b == Eigen::Dynamic) ? Eigen::Dynamic : a - b;
}

/// Product of two sizes (e.g. n·m entries of vec(B)).
[[nodiscard]] constexpr int product_of_sizes(int a, int b) noexcept {
  return (a == Eigen::Dynamic || b == Eigen::Dynamic) ? Eigen::Dynamic : a * b;
}

namespace detail {
[[nodiscard]] constexpr bool valid_size(int n) noexcept { return n == Eigen::Dynamic || n >= 0; }
}  // namespace detail

/// Scalar and sizes of a state-space system
/// \f$x^+ = A x + B u + f + \Psi\theta,\; y = C x\f$, with the Eigen types that follow.
template <typename S, int NX, int NU, int NY, int NP>
struct Dimensions {
  static_assert(std::is_floating_point_v<S>, "adaptobs: the scalar must be a floating-point type");
  static_assert(detail::valid_size(NX) && detail::valid_size(NU) && detail::valid_size(NY) && detail::valid_size(NP),
                "adaptobs: sizes must be non-negative or Eigen::Dynamic");

  /// The type itself: a model, observer or plant derives from its `Dimensions`,
  /// so that every such type `T` answers `T::Dims`, `T::nx`, `T::State`,
  /// `T::GainMatrix` and the rest alike. Inside a class template these are
  /// members of a dependent base, which unqualified names do not find: a class
  /// brings the ones its body uses into scope with one declaration,
  /// `using typename Dims::State, ...;`.
  using Dims = Dimensions;
  using Scalar = S;
  static constexpr int nx = NX;
  static constexpr int nu = NU;
  static constexpr int ny = NY;
  static constexpr int np = NP;
  /// True when every size is known at compile time (no heap use anywhere).
  static constexpr bool is_fixed =
      NX != Eigen::Dynamic && NU != Eigen::Dynamic && NY != Eigen::Dynamic && NP != Eigen::Dynamic;

  template <int Rows, int Cols>
  using Matrix = Eigen::Matrix<S, Rows, Cols>;
  template <int Rows>
  using Vector = Eigen::Matrix<S, Rows, 1>;

  using State = Vector<NX>;                   ///< x
  using Input = Vector<NU>;                   ///< u
  using Output = Vector<NY>;                  ///< y
  using Parameters = Vector<NP>;              ///< θ
  using StateMatrix = Matrix<NX, NX>;         ///< A
  using InputMatrix = Matrix<NX, NU>;         ///< B
  using OutputMatrix = Matrix<NY, NX>;        ///< C
  using RegressorMatrix = Matrix<NX, NP>;     ///< Ψ, and its filtered versions (Υ, Ω)
  using GainMatrix = Matrix<NX, NY>;          ///< output-injection gain K
  using OutputMatrixSquare = Matrix<NY, NY>;  ///< output covariances, innovation weights
  using OutputRegressor = Matrix<NY, NP>;     ///< C Υ
  using ParameterMatrix = Matrix<NP, NP>;     ///< parameter gains, excitation Gramians
  /// A known input term f_k: nx entries, or none for no such term. At most nx
  /// entries, stored in place for a fixed nx: an empty one costs no allocation.
  using KnownInput = Eigen::Matrix<S, Eigen::Dynamic, 1, Eigen::ColMajor, NX, 1>;
};

/// Sizes known only at run time (all of them `Eigen::Dynamic` at compile time).
template <typename S>
using DynamicDimensions = Dimensions<S, Eigen::Dynamic, Eigen::Dynamic, Eigen::Dynamic, Eigen::Dynamic>;

/// Actual sizes of a system, read at run time (equal to the compile-time ones when fixed).
struct Sizes {
  Index nx = 0;
  Index nu = 0;
  Index ny = 0;
  Index np = 0;
  friend bool operator==(const Sizes&, const Sizes&) = default;
};

/// A type that states its scalar and its compile-time sizes.
template <class T>
concept StateSpace = requires {
  typename T::Scalar;
  requires std::floating_point<typename T::Scalar>;
  { T::nx } -> std::convertible_to<int>;
  { T::nu } -> std::convertible_to<int>;
  { T::ny } -> std::convertible_to<int>;
  { T::np } -> std::convertible_to<int>;
};

/// The output channels a sample carries: entry i is true when \f$y_k(i)\f$ was
/// measured. An observer ignores the entries of y whose channel is absent:
/// they may hold NaN or Inf (they must still be initialized values). No
/// channel present is a time update: the model and the known input (and
/// regressor) move the estimates on, and the step counter advances, so
/// time-varying models and gain schedules stay in phase.
template <StateSpace D>
using OutputMask = Eigen::Array<bool, D::ny, 1>;

}  // namespace adaptobs
