#pragma once
/// \file
/// Matrix exponential by scaling and squaring with diagonal Padé approximants.
///
/// Algorithm 2.3 of N. J. Higham, "The scaling and squaring method for the
/// matrix exponential revisited", SIAM J. Matrix Anal. Appl. 26(4), 2005: the
/// Padé degree m ∈ {3, 5, 7, 9, 13} is the smallest whose backward-error bound
/// θ_m covers ‖A‖₁; above θ₁₃ the matrix is scaled by 2^{-s}, the degree-13
/// approximant is evaluated, and the result squared s times. For `float` the
/// single-precision bounds of the same paper are used.

#include <adaptobs/core/validation.hpp>

#include <Eigen/Core>
#include <Eigen/LU>

#include <algorithm>
#include <array>
#include <cmath>
#include <type_traits>

namespace adaptobs {
namespace detail {

template <typename Scalar>
struct PadeBounds;

template <>
struct PadeBounds<float> {
  static constexpr std::array<int, 3> degrees{3, 5, 7};
  static constexpr std::array<double, 3> theta{4.258730016922831e-1, 1.880152677804762e0,
                                               3.925724783138660e0};
};

template <>
struct PadeBounds<double> {
  static constexpr std::array<int, 5> degrees{3, 5, 7, 9, 13};
  static constexpr std::array<double, 5> theta{1.495585217958292e-2, 2.539398330063230e-1,
                                               9.504178996162932e-1, 2.097847961257068e0,
                                               5.371920351148152e0};
};

template <>
struct PadeBounds<long double> : PadeBounds<double> {};

/// Coefficients b_0..b_m of the [m/m] Padé approximant of exp.
template <int M>
constexpr auto pade_coefficients() {
  if constexpr (M == 3) {
    return std::array<double, 4>{120., 60., 12., 1.};
  } else if constexpr (M == 5) {
    return std::array<double, 6>{30240., 15120., 3360., 420., 30., 1.};
  } else if constexpr (M == 7) {
    return std::array<double, 8>{17297280., 8648640., 1995840., 277200., 25200., 1512., 56., 1.};
  } else if constexpr (M == 9) {
    return std::array<double, 10>{17643225600., 8821612800., 2075673600., 302702400., 30270240.,
                                  2162160.,     110880.,     3960.,       90.,        1.};
  } else {
    static_assert(M == 13);
    return std::array<double, 14>{64764752532480000., 32382376266240000., 7771770303897600.,
                                  1187353796428800.,  129060195264000.,   10559470521600.,
                                  670442572800.,      33522128640.,       1323241920.,
                                  40840800.,          960960.,            16380.,
                                  182.,               1.};
  }
}

template <class Plain>
[[nodiscard]] typename Plain::Scalar one_norm(const Plain& a) {
  return a.cwiseAbs().colwise().sum().maxCoeff();
}

/// r_m(A) = (V − U)⁻¹ (V + U), U the odd part and V the even part of p_m(A).
template <int M, class Plain>
Plain pade_approximant(const Plain& a) {
  using Scalar = typename Plain::Scalar;
  constexpr auto b = pade_coefficients<M>();
  const Index n = a.rows();
  const Plain identity = Plain::Identity(n, n);
  const Plain a2 = a * a;
  Plain u(n, n);
  Plain v(n, n);
  if constexpr (M == 13) {
    const Plain a4 = a2 * a2;
    const Plain a6 = a4 * a2;
    const Plain uh = Scalar(b[13]) * a6 + Scalar(b[11]) * a4 + Scalar(b[9]) * a2;
    const Plain uw = a6 * uh + Scalar(b[7]) * a6 + Scalar(b[5]) * a4 + Scalar(b[3]) * a2 + Scalar(b[1]) * identity;
    u.noalias() = a * uw;
    const Plain vh = Scalar(b[12]) * a6 + Scalar(b[10]) * a4 + Scalar(b[8]) * a2;
    v.noalias() = a6 * vh;
    v += Scalar(b[6]) * a6 + Scalar(b[4]) * a4 + Scalar(b[2]) * a2 + Scalar(b[0]) * identity;
  } else {
    // Horner-free evaluation with the even powers A^0, A^2, ..., A^{M-1}.
    Plain power = identity;
    Plain uw = Scalar(b[1]) * identity;
    v = Scalar(b[0]) * identity;
    for (int j = 2; j <= M; j += 2) {
      power = (power * a2).eval();
      v += Scalar(b[j]) * power;
      if (j + 1 <= M) uw += Scalar(b[j + 1]) * power;
    }
    u.noalias() = a * uw;
  }
  return (v - u).partialPivLu().solve(v + u);
}

}  // namespace detail

/// \f$e^{A}\f$ of a square matrix (fixed or dynamic size). Throws
/// `ConfigurationError` when A is not square or holds NaN/Inf.
template <class Derived>
[[nodiscard]] typename Derived::PlainObject matrix_exponential(const Eigen::MatrixBase<Derived>& a_in) {
  using Plain = typename Derived::PlainObject;
  using Scalar = typename Derived::Scalar;
  using Bounds = detail::PadeBounds<std::remove_cv_t<Scalar>>;
  detail::require_square(a_in, "matrix_exponential", "A");
  detail::require_finite(a_in, "matrix_exponential", "A");
  const Plain a = a_in;
  if (a.size() == 0) return a;
  const Scalar norm = detail::one_norm(a);

  // Smallest Padé degree whose bound covers ‖A‖₁ without scaling.
  for (std::size_t i = 0; i + 1 < Bounds::degrees.size(); ++i) {
    if (norm <= Scalar(Bounds::theta[i])) {
      switch (Bounds::degrees[i]) {
        case 3: return detail::pade_approximant<3>(a);
        case 5: return detail::pade_approximant<5>(a);
        case 7: return detail::pade_approximant<7>(a);
        default: return detail::pade_approximant<9>(a);
      }
    }
  }
  constexpr int top_degree = Bounds::degrees.back();
  const Scalar top_theta = Scalar(Bounds::theta.back());
  int squarings = 0;
  if (norm > top_theta) squarings = std::max(0, static_cast<int>(std::ceil(std::log2(norm / top_theta))));
  const Plain scaled = a * std::ldexp(Scalar(1), -squarings);
  Plain result = detail::pade_approximant<top_degree>(scaled);
  for (int i = 0; i < squarings; ++i) result = (result * result).eval();
  return result;
}

}  // namespace adaptobs
