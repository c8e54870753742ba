#pragma once
/// \file
/// Matrix exponential by scaling and squaring with diagonal Padé approximants,
/// with the scaling chosen from ‖Aᵏ‖^{1/k} rather than ‖A‖.
///
/// A. H. Al-Mohy and N. J. Higham, "A new scaling and squaring algorithm for
/// the matrix exponential", SIAM J. Matrix Anal. Appl. 31(3), 2009 (AMH),
/// Algorithm 5.1, built on the Padé bounds θ_m of N. J. Higham, SIAM J. Matrix
/// Anal. Appl. 26(4), 2005, Table 2.3 (single-precision bounds for `float`).
/// Three of its ideas, and the Schur form, make the result accurate where
/// bounding by ‖A‖ is not:
///
/// - **Scaling from ‖Aᵏ‖^{1/k}.** The backward error of r_m(A) is h(A) with
///   h(x) = log(e^{−x} r_m(x)) odd, since r_m(x) r_m(−x) = 1; so h(x) = x g(x²)
///   with g's series starting at y^m, and AMH Theorem 4.2 bounds the relative
///   backward error by g̃ at max(d_{2p}, d_{2p+2})² for any p with p(p−1) ≤ m,
///   where d_k = ‖Aᵏ‖₁^{1/k}. For a nonnormal A, d_k can be far below ‖A‖₁
///   ([[0, 10¹⁰], [0, 0]] has d_k = 0 for k ≥ 2), and scaling by ‖A‖₁ then
///   squares a rounding error 2^s times. Here the powers are formed rather
///   than estimated: design-time sizes are small.
/// - **ℓ(A, m)** (AMH §5, eq. (5.1)): extra squarings when the leading term
///   |c_{2m+1}| ‖|A|^{2m+1}‖₁ / ‖A‖₁ of the backward error, evaluated in
///   floating point, would exceed the unit roundoff u; c_{2m+1} =
///   (m!)² / ((2m)! (2m+1)!) is the error constant of the [m/m] approximant.
/// - **Triangular A** (AMH Code Fragment 2.1): after every squaring the
///   diagonal is set to exp(2^{−j} a_ii) and the first superdiagonal to its
///   closed form, so neither suffers from the squarings. A lower-triangular A
///   goes through its transpose.
/// - **The Schur form** (Higham, Functions of Matrices, SIAM 2008, §9.1; Moler
///   and Van Loan, SIAM Rev. 45(1), 2003, §6): a dense A that needs squarings is
///   reduced to A = Q T Qᴴ, and e^T goes through the triangular case above. The
///   squarings of r_m(2^{−s}A) multiply rounding errors by the departure of A from
///   normality; on T they reach only the entries above the superdiagonal, and the
///   unitary Q carries only the Schur form's backward error O(u‖A‖): an error of
///   order κ_exp(A)·u (docs/design_routines.md has the measured table).
///
/// A nilpotent A (A^k = 0 exactly for some k ≤ 10) gets its finite series. An A
/// that is block-diagonal up to a permutation is exponentiated block by block,
/// so that a stiff block's squarings leave the others alone. Before all this A
/// is balanced, B = D⁻¹ A D with D a diagonal of powers of
/// two (Parlett–Reinsch), when that lowers ‖A‖₁; e^A = D e^B D⁻¹ is then
/// exact scaling. A result beyond the floating-point range is refused.

#include <adaptobs/core/detail/dynamic_copy.hpp>
#include <adaptobs/core/precompiled.hpp>
#include <adaptobs/core/validation.hpp>

#include <Eigen/Core>
#include <Eigen/Eigenvalues>
#include <Eigen/LU>

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <limits>
#include <sstream>
#include <type_traits>
#include <vector>

namespace adaptobs {
namespace detail {

/// Padé degrees m and the bounds θ_m on 2^{−s}‖·‖ below which r_m is accurate to
/// the unit roundoff (Higham 2005, Table 2.3; AMH Table 3.1).
template <typename Scalar>
struct PadeBounds;

template <>
struct PadeBounds<float> {
  static constexpr std::array<int, 3> degrees{3, 5, 7};
  static constexpr std::array<double, 3> theta{4.258730016922831e-1, 1.880152677804762e0, 3.925724783138660e0};
};

template <>
struct PadeBounds<double> {
  static constexpr std::array<int, 5> degrees{3, 5, 7, 9, 13};
  static constexpr std::array<double, 5> theta{1.495585217958292e-2, 2.539398330063230e-1, 9.504178996162932e-1,
                                               2.097847961257068e0, 5.371920351148152e0};
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
    return std::array<double, 14>{64764752532480000.,
                                  32382376266240000.,
                                  7771770303897600.,
                                  1187353796428800.,
                                  129060195264000.,
                                  10559470521600.,
                                  670442572800.,
                                  33522128640.,
                                  1323241920.,
                                  40840800.,
                                  960960.,
                                  16380.,
                                  182.,
                                  1.};
  }
}

/// The real type of a real or complex scalar.
template <typename Scalar>
using RealOf = typename Eigen::NumTraits<Scalar>::Real;

template <typename Scalar>
[[nodiscard]] RealOf<Scalar> one_norm(const DynamicMatrix<Scalar>& a) {
  return a.cols() == 0 ? RealOf<Scalar>(0) : a.cwiseAbs().colwise().sum().maxCoeff();
}

/// r_m(A) = (V − U)⁻¹ (V + U), U the odd part and V the even part of p_m(A)
/// (Higham 2005, eqs. (2.2) and (2.3) for m = 13).
template <int M, typename Scalar>
[[nodiscard]] DynamicMatrix<Scalar> pade_approximant(const DynamicMatrix<Scalar>& a) {
  using Matrix = DynamicMatrix<Scalar>;
  constexpr auto b = pade_coefficients<M>();
  const Index n = a.rows();
  const Matrix identity = Matrix::Identity(n, n);
  const Matrix a2 = a * a;
  Matrix u(n, n);
  Matrix v(n, n);
  if constexpr (M == 13) {
    const Matrix a4 = a2 * a2;
    const Matrix a6 = a4 * a2;
    const Matrix uh = Scalar(b[13]) * a6 + Scalar(b[11]) * a4 + Scalar(b[9]) * a2;
    const Matrix uw = a6 * uh + Scalar(b[7]) * a6 + Scalar(b[5]) * a4 + Scalar(b[3]) * a2 + Scalar(b[1]) * identity;
    u.noalias() = a * uw;
    const Matrix vh = Scalar(b[12]) * a6 + Scalar(b[10]) * a4 + Scalar(b[8]) * a2;
    v.noalias() = a6 * vh;
    v += Scalar(b[6]) * a6 + Scalar(b[4]) * a4 + Scalar(b[2]) * a2 + Scalar(b[0]) * identity;
  } else {
    // The even powers A^0, A^2, ..., A^{M-1} serve both parts.
    Matrix power = identity;
    Matrix uw = Scalar(b[1]) * identity;
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

template <typename Scalar>
[[nodiscard]] DynamicMatrix<Scalar> pade_approximant(int degree, const DynamicMatrix<Scalar>& a) {
  switch (degree) {
    case 3: return pade_approximant<3>(a);
    case 5: return pade_approximant<5>(a);
    case 7: return pade_approximant<7>(a);
    case 9: return pade_approximant<9>(a);
    default: return pade_approximant<13>(a);
  }
}

/// e with x = f·2^e, 1/2 ≤ f < 1: dividing by 2^e brings x near 1 without rounding.
template <typename Scalar>
[[nodiscard]] int binary_exponent(Scalar x) {
  int e = 0;
  (void)std::frexp(x, &e);
  return e;
}

/// log₂ of the error constant (m!)² / ((2m)! (2m+1)!) of the [m/m] Padé approximant,
/// as the sum of log₂ of its factors: m!/(2m)! = 1/((m+1)(m+2)⋯(2m)) and
/// m!/(2m+1)! = 1/((m+1)(m+2)⋯(2m+1)). Not through std::lgamma, which writes
/// the global signgam and so may not run on several threads at once (models
/// are built inside the concurrent scenarios of evaluate_detection).
inline double log2_pade_error_constant(int m) {
  double sum = 0;
  for (int k = m + 1; k <= 2 * m; ++k) sum -= 2 * std::log2(double(k));
  return sum - std::log2(double(2 * m + 1));
}

/// Diagonal similarity by powers of two that makes each row's and column's
/// off-diagonal 1-norms nearly equal (Parlett–Reinsch balancing, without
/// permutations): on return a holds D⁻¹ A D and d the diagonal of D. Powers of
/// two keep the similarity free of rounding.
template <typename Scalar>
void balance(DynamicMatrix<Scalar>& a, Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& d) {
  const Index n = a.rows();
  d.setOnes(n);
  for (int sweep = 0; sweep < 64; ++sweep) {
    bool changed = false;
    for (Index i = 0; i < n; ++i) {
      // Off-diagonal sums formed without the diagonal, which could absorb them.
      Scalar c(0), r(0);
      for (Index j = 0; j < n; ++j) {
        if (j == i) continue;
        c += std::abs(a(j, i));
        r += std::abs(a(i, j));
      }
      if (!(c > Scalar(0)) || !(r > Scalar(0))) continue;
      // f = 2^k with f² ≈ r / c balances c f against r / f.
      const int k = static_cast<int>(std::lround(0.5 * (std::log2(double(r)) - std::log2(double(c)))));
      if (k == 0) continue;
      const Scalar f = std::ldexp(Scalar(1), k);
      if (!(c * f + r / f < Scalar(0.95) * (c + r))) continue;
      a.col(i) *= f;
      a.row(i) /= f;
      d(i) *= f;
      changed = true;
    }
    if (!changed) break;
  }
}

/// log₂ d_k = log₂ ‖Aᵏ‖₁^{1/k} for k = 4, 6, 8, 10 (−∞ for a zero power).
///
/// The powers are formed as they are, which keeps every entry a nonnormal A
/// needs (for [[−1, b], [0, −1]], A⁴ = [[1, −4b], [0, 1]]). A power that
/// overflows is formed again from A / 2^e, ‖A / 2^e‖₁ ≈ 1, with 2^{ke} taken
/// out; if that one underflows to zero, the safe bound d_k ≤ ‖A‖₁ is used.
template <typename Scalar>
[[nodiscard]] std::array<double, 4> log2_power_roots(const DynamicMatrix<Scalar>& a) {
  using Matrix = DynamicMatrix<Scalar>;
  using Real = RealOf<Scalar>;
  const auto log2_root = [](const Matrix& power, int k, double exponent) {
    const Real norm = one_norm(power);
    return norm > Real(0) ? (std::log2(double(norm)) + exponent) / k : -std::numeric_limits<double>::infinity();
  };
  const auto roots = [&](const Matrix& base, double exponent) {
    const Matrix p2 = base * base;
    const Matrix p4 = p2 * p2;
    const Matrix p6 = p4 * p2;
    const std::array<const Matrix, 4> powers{p4, p6, p4 * p4, p4 * p6};
    std::array<double, 4> out{};
    for (std::size_t i = 0; i < 4; ++i) {
      const int k = 4 + 2 * int(i);
      out[i] = powers[i].allFinite() ? log2_root(powers[i], k, k * exponent) : std::numeric_limits<double>::quiet_NaN();
    }
    return out;
  };
  const double log2_norm = std::log2(double(one_norm(a)));
  std::array<double, 4> plain = roots(a, 0);
  if (std::none_of(plain.begin(), plain.end(), [](double x) { return std::isnan(x); })) return plain;
  const int e = binary_exponent(one_norm(a));
  const std::array<double, 4> normalized = roots(Matrix(a * std::ldexp(Real(1), -e)), e);
  for (std::size_t i = 0; i < 4; ++i) {
    if (!std::isnan(plain[i])) continue;
    plain[i] = std::isfinite(normalized[i]) ? normalized[i] : log2_norm;
  }
  return plain;
}

/// log₂ ‖|A|ᵏ‖₁ for the ℓ(A, m) term: 1ᵀ|A|ᵏ is formed row by row, renormalized
/// by powers of two, and its largest entry is the 1-norm of the nonnegative |A|ᵏ.
template <typename Scalar>
[[nodiscard]] double log2_abs_power_norm(const DynamicMatrix<Scalar>& a, int k) {
  using Real = RealOf<Scalar>;
  const DynamicMatrix<Real> abs_a = a.cwiseAbs();
  Eigen::Matrix<Real, 1, Eigen::Dynamic> row = Eigen::Matrix<Real, 1, Eigen::Dynamic>::Ones(a.cols());
  double exponent = 0;
  for (int i = 0; i < k; ++i) {
    row = (row * abs_a).eval();
    const Real top = row.maxCoeff();
    if (!(top > Real(0))) return -std::numeric_limits<double>::infinity();
    const int e = binary_exponent(top);
    row *= std::ldexp(Real(1), -e);
    exponent += e;
  }
  return std::log2(double(row.maxCoeff())) + exponent;
}

/// e^{(λ₁ + λ₂)/2} sinh((λ₁ − λ₂)/2) / ((λ₁ − λ₂)/2) = (e^{λ₁} − e^{λ₂}) / (λ₁ − λ₂): the
/// (1, 2) entry of exp([[λ₁, 1], [0, λ₂]]) (Higham, Functions of Matrices, eq. (10.42)).
/// The sinh form avoids cancellation for close λ; the difference quotient, free of
/// cancellation once |λ₁ − λ₂| ≥ 2, avoids 0·∞ when they are far apart. Real or
/// complex λ (the Schur route below has complex eigenvalues on its diagonal).
template <typename Scalar>
[[nodiscard]] Scalar exp_divided_difference(Scalar l1, Scalar l2) {
  const Scalar half = (l1 - l2) / Scalar(2);
  if (std::abs(half) >= RealOf<Scalar>(1)) return (std::exp(l1) - std::exp(l2)) / (l1 - l2);
  const Scalar sinhc = half == Scalar(0) ? Scalar(1) : std::sinh(half) / half;
  return std::exp((l1 + l2) / Scalar(2)) * sinhc;
}

/// Diagonal and first superdiagonal of e^{2^{−j}T} for upper-triangular T, in place in x
/// (AMH Code Fragment 2.1).
template <typename Scalar>
void set_exact_triangular_bands(DynamicMatrix<Scalar>& x, const DynamicMatrix<Scalar>& t, int j) {
  const Index n = t.rows();
  const Scalar scale(std::ldexp(RealOf<Scalar>(1), -j));
  for (Index i = 0; i < n; ++i) x(i, i) = std::exp(scale * t(i, i));
  for (Index i = 0; i + 1 < n; ++i)
    x(i, i + 1) = scale * t(i, i + 1) * exp_divided_difference(scale * t(i, i), scale * t(i + 1, i + 1));
}

/// Labels of the decoupled blocks of A: i and j share a label when a path of nonzero
/// entries joins them, so that a permutation makes A block-diagonal by label.
template <typename Scalar>
[[nodiscard]] std::vector<Index> decoupled_blocks(const DynamicMatrix<Scalar>& a) {
  const Index n = a.rows();
  std::vector<Index> label(static_cast<std::size_t>(n));
  for (Index i = 0; i < n; ++i) label[std::size_t(i)] = i;
  const auto root = [&label](Index i) {
    while (label[std::size_t(i)] != i) i = label[std::size_t(i)] = label[std::size_t(label[std::size_t(i)])];
    return i;
  };
  for (Index j = 0; j < n; ++j)
    for (Index i = 0; i < n; ++i)
      if (i != j && a(i, j) != Scalar(0)) label[std::size_t(root(i))] = root(j);
  for (Index i = 0; i < n; ++i) label[std::size_t(i)] = root(i);
  return label;
}

template <typename Scalar>
[[nodiscard]] DynamicMatrix<Scalar> matrix_exponential_dense(const DynamicMatrix<Scalar>& a_in);

/// e^A block by block when A is block-diagonal up to a permutation: the squarings a
/// stiff block needs would otherwise cost the other blocks ‖A‖·u of their accuracy.
/// Returns false, doing nothing, when A is one block.
template <typename Scalar>
bool exponentiate_decoupled_blocks(const DynamicMatrix<Scalar>& a, DynamicMatrix<Scalar>& out) {
  const Index n = a.rows();
  const std::vector<Index> label = decoupled_blocks(a);
  if (std::all_of(label.begin(), label.end(), [&](Index l) { return l == label.front(); })) return false;
  out.setZero(n, n);
  std::vector<Index> members;
  for (Index block = 0; block < n; ++block) {
    members.clear();
    for (Index i = 0; i < n; ++i)
      if (label[std::size_t(i)] == block) members.push_back(i);
    if (members.empty()) continue;
    const auto size = static_cast<Index>(members.size());
    DynamicMatrix<Scalar> sub(size, size);
    for (Index j = 0; j < size; ++j)
      for (Index i = 0; i < size; ++i) sub(i, j) = a(members[std::size_t(i)], members[std::size_t(j)]);
    const DynamicMatrix<Scalar> e = matrix_exponential_dense(sub);
    for (Index j = 0; j < size; ++j)
      for (Index i = 0; i < size; ++i) out(members[std::size_t(i)], members[std::size_t(j)]) = e(i, j);
  }
  return true;
}

/// The Padé degree m and the number s of squarings for r_m(2^{−s}A)^{2^s}.
struct PadeChoice {
  int degree;
  int squarings;
};

/// m and s as in AMH Algorithm 5.1, for an A of finite ‖A‖₁.
template <typename Scalar>
[[nodiscard]] PadeChoice choose_pade(const DynamicMatrix<Scalar>& a) {
  using Real = RealOf<Scalar>;
  using Bounds = PadeBounds<Real>;
  const std::array<double, 4> log_d = log2_power_roots(a);  // log₂ d_4, d_6, d_8, d_10
  // AMH Theorem 4.2 with p(p − 1) ≤ m: η for p = 2 serves m ≥ 2, p = 3 serves m ≥ 6, p = 4 serves m ≥ 12.
  const auto log2_eta = [&](int m) {
    double eta = std::max(log_d[0], log_d[1]);
    if (m >= 6) eta = std::min(eta, std::max(log_d[1], log_d[2]));
    if (m >= 12) eta = std::min(eta, std::max(log_d[2], log_d[3]));
    return eta;
  };
  // ℓ(2^{−s}A, m) = max(⌈log₂(α/u) / (2m)⌉, 0), α = |c_{2m+1}| ‖|A|^{2m+1}‖₁ / ‖A‖₁ (AMH eq. (5.1)),
  // using α(2^{−s}A) = 2^{−2ms} α(A).
  const double log2_u = std::log2(double(std::numeric_limits<Real>::epsilon()) / 2);
  const double log2_norm = std::log2(double(one_norm(a)));
  const auto extra_squarings = [&](int m, int s) {
    const double log2_alpha = log2_pade_error_constant(m) + log2_abs_power_norm(a, 2 * m + 1) - log2_norm - 2.0 * m * s;
    return std::max(0, static_cast<int>(std::ceil((log2_alpha - log2_u) / (2 * m))));
  };

  for (std::size_t i = 0; i + 1 < Bounds::degrees.size(); ++i) {
    const int m = Bounds::degrees[i];
    if (log2_eta(m) <= std::log2(Bounds::theta[i]) && extra_squarings(m, 0) == 0) return {m, 0};
  }
  const int degree = Bounds::degrees.back();
  const double log2_excess = log2_eta(degree) - std::log2(Bounds::theta.back());
  const int squarings = log2_excess > 0 ? static_cast<int>(std::ceil(log2_excess)) : 0;
  return {degree, squarings + extra_squarings(degree, squarings)};
}

/// r_m(2^{−s}A)^{2^s}, and for an upper-triangular A the diagonal and superdiagonal
/// set exactly at every step (AMH Code Fragment 2.1).
template <typename Scalar>
[[nodiscard]] DynamicMatrix<Scalar> scaling_and_squaring(const DynamicMatrix<Scalar>& a, bool triangular,
                                                         PadeChoice choice) {
  using Real = RealOf<Scalar>;
  DynamicMatrix<Scalar> x =
      pade_approximant(choice.degree, DynamicMatrix<Scalar>(a * std::ldexp(Real(1), -choice.squarings)));
  if (triangular) set_exact_triangular_bands(x, a, choice.squarings);
  for (int j = choice.squarings - 1; j >= 0; --j) {
    x = (x * x).eval();
    if (triangular) set_exact_triangular_bands(x, a, j);
  }
  return x;
}

/// r_m(2^{−s}A)^{2^s} with m and s chosen as in AMH Algorithm 5.1.
template <typename Scalar>
[[nodiscard]] DynamicMatrix<Scalar> scaling_and_squaring(const DynamicMatrix<Scalar>& a, bool triangular) {
  using Real = RealOf<Scalar>;
  if (!std::isfinite(one_norm(a))) {
    // Finite entries whose column sums overflow (‖A‖₁ ≤ n · the largest number):
    // e^A = (e^{A/2})², halving until the norm is finite, at most log₂ n + 1 times.
    // The choice of m and s would otherwise run on infinities.
    DynamicMatrix<Scalar> x = scaling_and_squaring(DynamicMatrix<Scalar>(a / Real(2)), triangular);
    x = (x * x).eval();
    if (triangular) set_exact_triangular_bands(x, a, 0);
    return x;
  }
  return scaling_and_squaring(a, triangular, choose_pade(a));
}

/// e^A = Q e^T Q* from the Schur form A = Q T Q*, Q unitary and T upper triangular
/// (N. J. Higham, Functions of Matrices, SIAM 2008, §9.1 with Theorem 1.13(c);
/// the Schur method of C. Moler and C. Van Loan, "Nineteen dubious ways to compute
/// the exponential of a matrix, twenty-five years later", SIAM Rev. 45(1), 2003, §6),
/// with e^T by scaling and squaring whose diagonal and first superdiagonal are set
/// from their closed forms after every squaring (AMH Code Fragment 2.1).
///
/// Why: the s squarings of r_m(2^{−s}A) carry the rounding errors of every
/// intermediate power into e^A, and for a nonnormal A the intermediate powers
/// are far larger than e^A (A = S [[−1, b], [0, −2]] S⁻¹ loses all accuracy by
/// b = 2²⁰ that way). On T the closed forms leave to the squarings only the entries
/// above the first superdiagonal (none for n = 2), and Q, unitary, passes on only the
/// backward error O(u‖A‖) of the Schur form: an error of order κ_exp(A)·u
/// (Higham 2008, §3.1 and eq. (10.22)).
///
/// The real Schur form A = Q T Qᵀ is computed; when all eigenvalues are real, T is
/// triangular. Otherwise each 2 × 2 block B of T, of eigenvalues λ and λ̄, is made
/// triangular by the unitary G = [x, Jx̄] whose first column is the unit
/// eigenvector x = (b₁₂, λ − b₁₁) of B (Gᴴ B G = [[λ, ·], [0, λ̄]]; Golub and
/// Van Loan, Matrix Computations, 4th ed., §7.4.1), which gives the complex Schur
/// form without a second QR iteration; e^A is then the real part of Q e^T Qᴴ.
/// Returns false when the QR iteration does not converge.
template <typename Scalar>
bool schur_exponential(const DynamicMatrix<Scalar>& a, DynamicMatrix<Scalar>& out) {
  using Matrix = DynamicMatrix<Scalar>;
  const Index n = a.rows();
  const Eigen::RealSchur<Matrix> real_schur(a);
  if (real_schur.info() != Eigen::Success) return false;
  const Matrix& t = real_schur.matrixT();
  const Matrix& q = real_schur.matrixU();
  bool triangular = true;
  for (Index i = 0; i + 1 < n; ++i) triangular = triangular && t(i + 1, i) == Scalar(0);
  if (triangular) {
    out.noalias() = q * scaling_and_squaring(t, true) * q.transpose();
    return true;
  }
  using Complex = std::complex<Scalar>;
  using ComplexMatrix = DynamicMatrix<Complex>;
  ComplexMatrix tc = t.template cast<Complex>();
  ComplexMatrix qc = q.template cast<Complex>();
  Eigen::Matrix<Complex, 2, 2> g;
  for (Index k = 0; k + 1 < n; ++k) {
    if (t(k + 1, k) == Scalar(0)) continue;
    // λ = (b₁₁ + b₂₂)/2 + i √(−((b₁₁ − b₂₂)/2)² − b₁₂ b₂₁), the root of positive imaginary part.
    const Scalar half_difference = (t(k, k) - t(k + 1, k + 1)) / 2;
    const Scalar imaginary = std::sqrt(std::abs(half_difference * half_difference + t(k, k + 1) * t(k + 1, k)));
    const Complex x1(t(k, k + 1), Scalar(0));
    const Complex x2(-half_difference, imaginary);  // λ − b₁₁
    const Scalar norm = std::hypot(std::abs(x1), std::abs(x2));
    g << x1 / norm, -std::conj(x2) / norm, x2 / norm, std::conj(x1) / norm;
    tc.middleRows(k, 2) = (g.adjoint() * tc.middleRows(k, 2)).eval();
    tc.middleCols(k, 2) = (tc.middleCols(k, 2) * g).eval();
    qc.middleCols(k, 2) = (qc.middleCols(k, 2) * g).eval();
    tc(k + 1, k) = Complex(0);
    ++k;  // the block's second row
  }
  out = (qc * scaling_and_squaring(tc, true) * qc.adjoint()).real();
  return true;
}

/// pq, and whether a product of two nonzero entries fell below the normal
/// range on the way: a zero entry of pq then need not be a true zero.
template <typename Scalar>
bool multiply_noting_underflow(const DynamicMatrix<Scalar>& p, const DynamicMatrix<Scalar>& q,
                               DynamicMatrix<Scalar>& pq) {
  constexpr Scalar smallest_normal = std::numeric_limits<Scalar>::min();
  bool underflow = false;
  pq.setZero(p.rows(), q.cols());
  for (Index j = 0; j < q.cols(); ++j)
    for (Index k = 0; k < p.cols(); ++k) {
      const Scalar qkj = q(k, j);
      if (qkj == Scalar(0)) continue;
      for (Index i = 0; i < p.rows(); ++i) {
        const Scalar term = p(i, k) * qkj;
        underflow = underflow || (p(i, k) != Scalar(0) && std::abs(term) < smallest_normal);
        pq(i, j) += term;
      }
    }
  return underflow;
}

/// I + A + … + A^{k−1}/(k−1)! when A^k = 0 exactly in floating point for some k ≤ 10;
/// false otherwise. A nilpotent A has this finite series as its exponential, while
/// scaling and squaring, for a nonnormal nilpotent A such as [[b, −b], [b, −b]],
/// loses ‖A‖·u of accuracy that the series keeps. Where A^k overflows, the test for
/// zero uses (A / 2^e)^k, 2^e ≈ ‖A‖₁, instead (a power of two keeps it exact). A
/// zero reached through an underflowing product proves nothing (the powers of
/// [[−10, 10³⁰⁰], [0, −10]] / 2^e underflow to zero long before A^k overflows),
/// so the series is then not used.
template <typename Scalar>
bool nilpotent_series(const DynamicMatrix<Scalar>& a, DynamicMatrix<Scalar>& out) {
  const Index n = a.rows();
  const int e = binary_exponent(one_norm(a));
  const DynamicMatrix<Scalar> normalized = a * std::ldexp(Scalar(1), -e);
  DynamicMatrix<Scalar> power = a;
  DynamicMatrix<Scalar> normalized_power = normalized;
  DynamicMatrix<Scalar> product;
  DynamicMatrix<Scalar> sum = DynamicMatrix<Scalar>::Identity(n, n) + a;
  bool power_underflowed = false, normalized_underflowed = false;
  Scalar factorial(1);
  for (int k = 2; k <= 10; ++k) {
    power_underflowed = multiply_noting_underflow(power, a, product) || power_underflowed;
    power.swap(product);
    normalized_underflowed = multiply_noting_underflow(normalized_power, normalized, product) || normalized_underflowed;
    normalized_power.swap(product);
    const bool finite = power.allFinite();
    const bool zero = finite ? power.isZero(Scalar(0)) && !power_underflowed
                             : normalized_power.isZero(Scalar(0)) && !normalized_underflowed;
    if (zero) {
      out = std::move(sum);
      return true;
    }
    if (!finite) return false;
    factorial *= Scalar(k);
    sum += power / factorial;
  }
  return false;
}

/// e^A of a finite square matrix: the scaling and squaring core (AMH Algorithm 5.1).
/// Throws `ConfigurationError` naming `A` when e^A is beyond the range of `Scalar`.
template <typename Scalar>
[[nodiscard]] DynamicMatrix<Scalar> matrix_exponential_dense(const DynamicMatrix<Scalar>& a_in) {
  using Matrix = DynamicMatrix<Scalar>;
  const Index n = a_in.rows();
  if (n == 0 || a_in.isZero(Scalar(0))) return Matrix::Identity(n, n);
  if (Matrix blocks; n > 1 && exponentiate_decoupled_blocks(a_in, blocks)) return blocks;

  // Lower-triangular A: e^A = (e^{Aᵀ})ᵀ, so only the upper case is special below.
  const auto strictly_lower_is_zero = [n](const Matrix& m) {
    for (Index j = 0; j < n; ++j)
      for (Index i = j + 1; i < n; ++i)
        if (m(i, j) != Scalar(0)) return false;
    return true;
  };
  const bool upper = strictly_lower_is_zero(a_in);
  const bool lower = !upper && strictly_lower_is_zero(a_in.transpose());
  Matrix a = lower ? Matrix(a_in.transpose()) : a_in;
  const bool triangular = upper || lower;

  Eigen::Matrix<Scalar, Eigen::Dynamic, 1> d = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>::Ones(n);
  {
    Matrix balanced = a;
    balance(balanced, d);
    if (one_norm(balanced) < one_norm(a)) {
      a = std::move(balanced);
    } else {
      d.setOnes();
    }
  }

  Matrix x;
  if (!nilpotent_series(a, x)) {
    // A dense A that needs no squaring keeps r_m(A), a few products and one solve
    // (AMH Algorithm 5.1); one that does goes through its Schur form, where the
    // squarings cannot amplify its departure from normality.
    if (triangular || !std::isfinite(one_norm(a))) {
      x = scaling_and_squaring(a, triangular);
    } else if (const PadeChoice choice = choose_pade(a); choice.squarings == 0 || !schur_exponential(a, x)) {
      x = scaling_and_squaring(a, false, choice);
    }
  }

  // Undo the balancing: e^A = D e^B D⁻¹, exact with powers of two. By their
  // exponents: d(row)/d(col) itself may be out of range while the entry is not.
  for (Index col = 0; col < n; ++col)
    for (Index row = 0; row < n; ++row) x(row, col) = std::ldexp(x(row, col), std::ilogb(d(row)) - std::ilogb(d(col)));
  if (!x.allFinite()) {
    std::ostringstream os;
    os << "has an exponential beyond the floating-point range (‖A‖₁ = " << one_norm(a_in)
       << "; the largest representable entry is " << std::numeric_limits<Scalar>::max() << ")";
    fail_argument("matrix_exponential", "A", os.str());
  }
  if (lower) x.transposeInPlace();
  return x;
}
#ifdef ADAPTOBS_PRECOMPILED
ADAPTOBS_INSTANTIATE DynamicMatrix<double> matrix_exponential_dense<double>(const DynamicMatrix<double>&);
ADAPTOBS_INSTANTIATE DynamicMatrix<float> matrix_exponential_dense<float>(const DynamicMatrix<float>&);
#endif

}  // namespace detail

/// \f$e^{A}\f$ of a square matrix (fixed or dynamic size), accurate for large,
/// stiff, nonnormal and badly scaled A (see the file comment). Throws
/// `ConfigurationError` naming `A` when A is not square, holds NaN/Inf, or has
/// an exponential beyond the floating-point range.
template <class Derived>
[[nodiscard]] typename Derived::PlainObject matrix_exponential(const Eigen::MatrixBase<Derived>& a) {
  using Plain = typename Derived::PlainObject;
  using Scalar = std::remove_cv_t<typename Derived::Scalar>;
  require_square(a, "matrix_exponential", "A");
  require_finite(a, "matrix_exponential", "A");
  const detail::DynamicMatrix<Scalar> e = detail::matrix_exponential_dense<Scalar>(detail::dynamic_copy(a));
  Plain out(a.rows(), a.cols());
  for (Index j = 0; j < a.cols(); ++j)
    for (Index i = 0; i < a.rows(); ++i) out(i, j) = e(i, j);
  return out;
}

}  // namespace adaptobs
