#pragma once
/// \file
/// Eigenvalue assignment by output injection (\f$A - LC\f$) or state feedback
/// (\f$A - BK\f$), for any number of outputs or inputs.
///
/// Method (Sylvester-equation placement; S. P. Bhattacharyya, E. de Souza,
/// "Pole assignment via Sylvester's equation", Systems & Control Letters 1(4),
/// 1982): choose a real matrix F whose spectrum is the requested one and a
/// free parameter \f$G \in \mathbb{R}^{N\times m}\f$, solve
/// \f[ XA - FX = GC \f]
/// and set \f$L = X^{-1}G\f$; then \f$A - LC = X^{-1}FX\f$ has the spectrum of F.
/// X is invertible for almost every G when (A, C) is observable and (F, G)
/// controllable. With one output L is unique; with m > 1 outputs the gains
/// that place a spectrum form a family of dimension N(m − 1), and the draw of G
/// whose X is best conditioned is kept (X⁻¹ maps the eigenvectors of F, which
/// are orthonormal for distinct poles, to those of \f$A - LC\f$, so cond(X)
/// bounds the sensitivity of the placed eigenvalues). C enters with its rows
/// scaled by powers of two to unit size, and L is returned in C's units, so
/// that outputs in other units get the same design, not one whose X leans on
/// the outputs with the larger numbers.
///
/// F is block diagonal: 1 × 1 blocks for real poles, \f$\begin{bmatrix}\alpha&\beta\\-\beta&\alpha\end{bmatrix}\f$
/// for pairs \f$\alpha\pm i\beta\f$; blocks of a repeated pole are chained by
/// a 1 on the superdiagonal so that F stays nonderogatory (one Jordan chain
/// per pole, as a single output requires). When a requested pole is close to
/// an eigenvalue of A, the Sylvester equation is ill conditioned; A is then
/// first moved by a random injection \f$L_0\f$.
///
/// The result is verified, not trusted. With \f$M = A - LC\f$, q the requested
/// characteristic polynomial and λ(M) the eigenvalues of M computed by the
/// QR algorithm (`dense_eigenvalues`), a gain is returned only if
/// 1. the normalized Cayley–Hamilton residual
///    \f$\|q(M)\|_F / \sum_i |q_i|\,\|M\|_F^{N-i}\f$ is at most
///    `verification_tolerance` (default \f$10^5\varepsilon\f$);
/// 2. the stability region of the request is kept: if every requested pole has
///    \f$|p_i| < 1\f$, then \f$\max|\lambda(M)| < 1\f$; if every requested pole has
///    \f$\operatorname{Re} p_i < 0\f$, then \f$\max\operatorname{Re}\lambda(M) < 0\f$;
/// 3. each requested pole \f$p_i\f$, matched greedily to a distinct computed
///    eigenvalue (`eigenvalue_mismatch`), lies within
///    \f$\tau^{1/k_i}\,\|M\|_F\f$ of it, where τ is `eigenvalue_tolerance`
///    (default \f$\sqrt\varepsilon\f$) and \f$k_i\f$ the multiplicity of
///    \f$p_i\f$ in the request: the number of requested poles within
///    \f$\sqrt\varepsilon\max(1, |p_i|)\f$ of it.
///
/// Test 1 alone is not enough: its normalizer grows like \f$\|M\|_F^N\f$,
/// and with \f$\|M\|_F\f$ far above the poles (a large gain, or a large A) it
/// reaches \f$10^{20}\f$ for N = 10: ten poles 0.90, 0.91, …, 0.99 requested
/// for a pair with \f$\|A\|_F \approx 100\f$ can pass it with a residual below
/// \f$10^{-20}\f$ while M has an eigenvalue 1.07. The roots of a polynomial are
/// that sensitive to its coefficients when they are clustered (J. H. Wilkinson,
/// *Rounding Errors in Algebraic Processes*, 1963, ch. 2). Equally, M has the
/// eigenvectors of F mapped by \f$X^{-1}\f$ (orthonormal ones for F, which is
/// normal when the poles are distinct), so a perturbation E of M moves its
/// eigenvalues by up to \f$\operatorname{cond}(X)\|E\|_2\f$ (F. L. Bauer,
/// C. T. Fike, "Norms and exclusion theorems", Numer. Math. 2, 1960), and
/// cond(X) grows without bound as the poles cluster; rounding L alone is such an E.
/// Test 3 states what can be asked: a simple eigenvalue to the relative
/// accuracy τ of \f$\|M\|_F\f$ (about half the digits by default), a k-fold
/// one to \f$\tau^{1/k}\|M\|_F\f$, since a Jordan block of size k perturbed by
/// δ in its corner has its eigenvalues at distance \f$\delta^{1/k}\f$
/// (J. H. Wilkinson, *The Algebraic Eigenvalue Problem*, 1965, ch. 2). For a
/// many-fold pole with \f$\|M\|_F\f$ large that bound is wide, and test 2 is
/// what keeps a stable request stable.
///
/// An unobservable pair, a singular transformation or a failed verification
/// throws `ConfigurationError` naming the argument: failing tests 2 or 3 means
/// that the requested poles are too clustered for the conditioning of the pair.
/// No gain is ever returned that does not do its job.

#include <adaptobs/core/detail/dynamic_copy.hpp>
#include <adaptobs/core/dimensions.hpp>
#include <adaptobs/core/precompiled.hpp>
#include <adaptobs/core/sylvester.hpp>
#include <adaptobs/core/validation.hpp>
#include <adaptobs/design/dense_eigenvalues.hpp>
#include <adaptobs/design/observability.hpp>

#include <Eigen/Core>
#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <Eigen/SVD>

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdint>
#include <limits>
#include <optional>
#include <random>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

namespace adaptobs {

struct PolePlacementOptions {
  /// Draws of the free parameter G when there are several outputs (one draw
  /// suffices for a single output: the gain is then unique). The draw with the
  /// best-conditioned transformation is kept.
  int tries = 20;
  /// Seed of those draws: designs are reproducible.
  std::uint64_t seed = 1;
  /// Relative rank tolerance of the observability staircase; 0 selects
  /// \f$\min(10^6\varepsilon, \sqrt\varepsilon)\f$ (`observability`).
  double observability_tolerance = 0;
  /// Largest accepted Cayley–Hamilton residual; 0 selects \f$10^5\varepsilon\f$.
  double verification_tolerance = 0;
  /// Relative accuracy τ of the placed eigenvalues, a value in (0, 1); 0 selects
  /// \f$\sqrt\varepsilon\f$. A requested pole of multiplicity k must be matched by
  /// an eigenvalue within \f$\tau^{1/k}\|A - LC\|_F\f$ (see the file comment).
  double eigenvalue_tolerance = 0;
};

namespace detail {

template <typename Scalar>
Scalar default_verification_tolerance(double requested) {
  return requested > 0 ? Scalar(requested) : Scalar(1e5) * std::numeric_limits<Scalar>::epsilon();
}

template <typename Scalar>
Scalar default_eigenvalue_tolerance(double requested) {
  return requested > 0 ? Scalar(requested) : std::sqrt(std::numeric_limits<Scalar>::epsilon());
}

/// For each pole, how many poles of the list (itself included) lie within
/// \f$\sqrt\varepsilon\max(1, |p_i|)\f$ of it: its multiplicity as a repeated pole.
template <typename Scalar>
std::vector<Index> pole_multiplicities(const ComplexVector<Scalar>& poles) {
  const Scalar tol = std::sqrt(std::numeric_limits<Scalar>::epsilon());
  std::vector<Index> k(std::size_t(poles.size()));
  for (Index i = 0; i < poles.size(); ++i)
    k[std::size_t(i)] = ((poles.array() - poles(i)).abs() <= tol * std::max(Scalar(1), std::abs(poles(i)))).count();
  return k;
}

/// For each pole, its distance to the nearest eigenvalue not taken by an
/// earlier pole (greedy matching, in the order of `poles`).
template <typename Scalar>
std::vector<Scalar> matched_eigenvalue_distances(const ComplexVector<Scalar>& eig, const ComplexVector<Scalar>& poles) {
  std::vector<bool> taken(std::size_t(eig.size()), false);
  std::vector<Scalar> distance(std::size_t(poles.size()), std::numeric_limits<Scalar>::infinity());
  for (Index i = 0; i < poles.size(); ++i) {
    Index best = -1;
    for (Index j = 0; j < eig.size(); ++j) {
      const Scalar d = std::abs(eig(j) - poles(i));
      if (!taken[std::size_t(j)] && d < distance[std::size_t(i)]) {
        distance[std::size_t(i)] = d;
        best = j;
      }
    }
    if (best >= 0) taken[std::size_t(best)] = true;
  }
  return distance;
}

template <typename Scalar>
std::string format_complex_list(const ComplexVector<Scalar>& values) {
  std::ostringstream os;
  os.precision(6);
  for (Index i = 0; i < values.size(); ++i) {
    if (i) os << ", ";
    const auto v = values(i);
    os << v.real();
    if (v.imag() != Scalar(0)) os << (v.imag() < 0 ? " - " : " + ") << std::abs(v.imag()) << "i";
  }
  return os.str();
}

/// Poles as a complex vector, checked finite.
template <typename Scalar, class DP>
ComplexVector<Scalar> complex_poles(const Eigen::MatrixBase<DP>& poles, std::string_view who) {
  require_vector(poles, who, "poles");
  const ComplexVector<Scalar> p = poles.derived().reshaped().template cast<std::complex<Scalar>>();
  if (!p.allFinite()) fail_argument(who, "poles", "must contain only finite numbers");
  return p;
}

}  // namespace detail

/// The real matrix F of the file comment whose spectrum is `poles`: block
/// diagonal, a 1 × 1 block per real pole and
/// \f$\begin{bmatrix}\alpha&\beta\\-\beta&\alpha\end{bmatrix}\f$ per pair \f$\alpha\pm i\beta\f$
/// (complex pairs first, then by real and imaginary part), with a 1 on the
/// superdiagonal between the blocks of a repeated pole (equal within
/// \f$\sqrt\varepsilon\max(1, |p|)\f$), so that F is nonderogatory. A pole is
/// real when its imaginary part is at most \f$100\varepsilon\max(1, |p|)\f$.
/// Refuses, naming `who` and `poles`, a list not closed under conjugation.
template <typename Scalar>
[[nodiscard]] Eigen::MatrixX<Scalar> real_matrix_with_spectrum(const ComplexVector<Scalar>& poles,
                                                               std::string_view who = "real_matrix_with_spectrum") {
  using std::abs;
  const Scalar pair_tol = std::sqrt(std::numeric_limits<Scalar>::epsilon());
  struct Block {
    Scalar re, im;  // im > 0 for a conjugate pair, 0 for a real pole
  };
  std::vector<Block> blocks;
  std::vector<bool> used(std::size_t(poles.size()), false);
  for (Index i = 0; i < poles.size(); ++i) {
    if (used[std::size_t(i)]) continue;
    const auto p = poles(i);
    const Scalar scale = std::max(Scalar(1), abs(p));
    used[std::size_t(i)] = true;
    if (abs(p.imag()) <= Scalar(100) * std::numeric_limits<Scalar>::epsilon() * scale) {
      blocks.push_back({p.real(), Scalar(0)});
      continue;
    }
    Index partner = -1;
    for (Index j = i + 1; j < poles.size() && partner < 0; ++j)
      if (!used[std::size_t(j)] && abs(poles(j) - std::conj(p)) <= pair_tol * scale) partner = j;
    if (partner < 0) fail_argument(who, "poles", "must be closed under complex conjugation (a real gain is sought)");
    used[std::size_t(partner)] = true;
    blocks.push_back({p.real(), abs(p.imag())});
  }
  std::sort(blocks.begin(), blocks.end(), [](const Block& a, const Block& b) {
    if ((a.im > 0) != (b.im > 0)) return a.im > 0;
    if (a.re != b.re) return a.re < b.re;
    return a.im < b.im;
  });
  const Index n = poles.size();
  Eigen::MatrixX<Scalar> f = Eigen::MatrixX<Scalar>::Zero(n, n);
  Index at = 0;
  for (std::size_t b = 0; b < blocks.size(); ++b) {
    const Block& blk = blocks[b];
    const Index d = blk.im > 0 ? 2 : 1;
    f(at, at) = blk.re;
    if (d == 2) {
      f(at + 1, at + 1) = blk.re;
      f(at, at + 1) = blk.im;
      f(at + 1, at) = -blk.im;
    }
    if (b + 1 < blocks.size()) {
      const Block& next = blocks[b + 1];
      const Scalar scale = std::max({Scalar(1), abs(blk.re), blk.im});
      const bool same = (next.im > 0) == (blk.im > 0) && abs(next.re - blk.re) <= pair_tol * scale &&
                        abs(next.im - blk.im) <= pair_tol * scale;
      if (same) f(at + d - 1, at + d) = Scalar(1);  // chain the Jordan blocks of a repeated pole
    }
    at += d;
  }
  return f;
}

/// Coefficients \f$(1, q_1, \dots, q_N)\f$ of the monic real polynomial
/// \f$q(z) = \prod_i (z - \lambda_i) = z^N + q_1 z^{N-1} + \dots + q_N\f$.
template <class DP>
[[nodiscard]] auto polynomial_from_roots(const Eigen::MatrixBase<DP>& poles) {
  using Scalar = typename Eigen::NumTraits<typename DP::Scalar>::Real;
  const ComplexVector<Scalar> p = detail::complex_poles<Scalar>(poles, "polynomial_from_roots");
  ComplexVector<Scalar> q = ComplexVector<Scalar>::Zero(p.size() + 1);
  q(0) = Scalar(1);
  for (Index i = 0; i < p.size(); ++i)
    for (Index j = i + 1; j >= 1; --j) q(j) -= p(i) * q(j - 1);
  return Eigen::Matrix<Scalar, Eigen::Dynamic, 1>(q.real());
}

/// Normalized Cayley–Hamilton residual \f$\|q(M)\|_F / \sum_i |q_i|\,\|M\|_F^{N-i}\f$
/// of the polynomial q with roots `poles`: a backward error, 0 when M has
/// exactly the spectrum `poles`. It bounds the eigenvalues only through the
/// sensitivity of the roots of q: when \f$\|M\|_F\f$ is much larger than the
/// poles, the normalizer is huge and a tiny residual allows clustered
/// eigenvalues to be far from `poles` (see the file comment; `eigenvalue_mismatch`
/// measures the eigenvalues themselves).
template <class DM, class DP>
[[nodiscard]] typename DM::Scalar cayley_hamilton_residual(const Eigen::MatrixBase<DM>& M,
                                                           const Eigen::MatrixBase<DP>& poles) {
  using Scalar = typename DM::Scalar;
  using Matrix = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;
  require_square(M, "cayley_hamilton_residual", "M");
  require(poles.size() == M.rows(), "cayley_hamilton_residual", "poles", "must have one pole per row of M");
  const Eigen::Matrix<Scalar, Eigen::Dynamic, 1> q = polynomial_from_roots(poles);
  const Index n = M.rows();
  const Matrix m = detail::dynamic_copy(M);
  const Scalar norm = m.norm();
  Matrix r = Matrix::Zero(n, n);
  Scalar scale = 0;
  for (Index i = 0; i <= n; ++i) {
    r = (r * m).eval();
    r.diagonal().array() += q(i);
    scale += std::abs(q(i)) * std::pow(norm, Scalar(n - i));
  }
  if (!std::isfinite(scale)) return std::numeric_limits<Scalar>::infinity();  // M or the poles not finite
  return scale > 0 ? r.norm() / scale : Scalar(0);
}

/// `count` distinct real poles spread over (0, radius]: radius·(count − i)/count.
/// A simple target when only a stability margin (spectral radius ≤ radius) is wanted.
template <typename Scalar>
[[nodiscard]] Eigen::Matrix<Scalar, Eigen::Dynamic, 1> spread_poles(Index count, Scalar radius) {
  require(count >= 0, "spread_poles", "count", "must be non-negative");
  require(radius >= Scalar(0) && radius < std::numeric_limits<Scalar>::infinity(), "spread_poles", "radius",
          "must be non-negative and finite");
  Eigen::Matrix<Scalar, Eigen::Dynamic, 1> p(count);
  for (Index i = 0; i < count; ++i) p(i) = radius * Scalar(count - i) / Scalar(count);
  return p;
}

/// Largest distance between the eigenvalues of M and the requested poles,
/// matched greedily (each pole to the nearest eigenvalue not yet taken).
template <class DM>
[[nodiscard]] typename DM::Scalar eigenvalue_mismatch(const Eigen::MatrixBase<DM>& M,
                                                      const ComplexVector<typename DM::Scalar>& poles) {
  using Scalar = typename DM::Scalar;
  if (M.rows() == 0) return Scalar(0);
  const ComplexVector<Scalar> eig = detail::dense_eigenvalues(detail::dynamic_copy(M));
  Scalar worst = 0;
  for (const Scalar d : detail::matched_eigenvalue_distances(eig, poles)) worst = std::max(worst, d);
  return worst;
}

/// The Sylvester placement machinery for one pair (A, C) and one spectrum:
/// candidates \f$L\f$ for given free parameters G. `place_output_injection`
/// uses it with its default choice of G; designs with constraints on L (such as
/// `design_guiro_gains`) draw candidates and score them themselves.
template <typename Scalar>
class PolePlacer {
 public:
  using Matrix = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;

  /// One placing gain: \f$A - LC = X^{-1}(F + \dots)X\f$ with F the target matrix.
  struct Candidate {
    Matrix L;                ///< N × m gain
    Matrix X;                ///< transformation of the Sylvester equation
    Scalar x_condition = 0;  ///< cond₂(X)
  };

  /// \param who, pair, property: names used in error messages ("<who>: argument '<pair>' is not <property>").
  PolePlacer(const Matrix& A, const Matrix& C, const ComplexVector<Scalar>& poles, const PolePlacementOptions& options,
             std::string_view who = "PolePlacer", std::string_view pair = "A, C",
             std::string_view property = "observable")
      : options_(options), rng_(options.seed) {
    require_square(A, who, "A");
    require_finite(A, who, "A");
    require_finite_shape(C, C.rows(), A.rows(), who, "C");
    require(poles.size() == A.rows(), who, "poles", "must hold one pole per state");
    require(options.tries >= 1, who, "options.tries", "must be at least 1");
    const Index n = A.rows();
    outputs_ = C.rows();
    require(outputs_ >= 1 || n == 0, who, pair, "has no output to inject");

    const auto report = observability(A, C, Scalar(options.observability_tolerance));
    if (!report.observable()) {
      fail_argument(who, pair,
                    "is not " + std::string(property) + ": its mode(s) " +
                        detail::format_complex_list(report.unobservable_modes) + " cannot be moved");
    }
    f_ = real_matrix_with_spectrum(poles, who);
    // The placement works with C's rows scaled by powers of two to unit size, as
    // the observability staircase does, and returns L in C's units: outputs in
    // other units (C scaled row by row) then get the same design, with L's
    // columns scaled back, instead of one that leans on the larger outputs.
    output_exponents_ = detail::row_exponents<Scalar>(C);
    c_ = detail::scaled_by_powers_of_two<Scalar>(C, output_exponents_, true);
    l0_ = Matrix::Zero(n, outputs_);
    Matrix a0 = A;
    // Keep the requested poles away from the eigenvalues of the matrix the Sylvester equation sees.
    const Scalar scale = std::max(Scalar(1), Scalar(A.norm()));
    const auto separation = [&](const Matrix& m) {
      if (n == 0) return std::numeric_limits<Scalar>::infinity();
      const ComplexVector<Scalar> e = detail::dense_eigenvalues(m);
      Scalar gap = std::numeric_limits<Scalar>::infinity();
      for (Index i = 0; i < e.size(); ++i) gap = std::min(gap, (poles.array() - e(i)).abs().minCoeff());
      return gap / scale;
    };
    Scalar gap = separation(a0);
    if (gap < Scalar(1e-3)) {
      const Scalar gain_scale = scale / std::max(Scalar(c_.norm()), std::numeric_limits<Scalar>::min());
      Matrix best_l0 = l0_;
      for (int attempt = 0; attempt < 50 && gap < Scalar(1e-2); ++attempt) {
        const Matrix l0 = gaussian(n, outputs_) * gain_scale;
        const Scalar g = separation(Matrix(A - l0 * c_));
        if (g > gap) {
          gap = g;
          best_l0 = l0;
        }
      }
      l0_ = best_l0;
      a0 = A - l0_ * c_;
    }
    solver_.emplace(Matrix(-f_), a0);
  }

  /// Candidate for the free parameter G (N × m), or none when X is singular.
  [[nodiscard]] std::optional<Candidate> candidate(const Matrix& G) const {
    Candidate c;
    c.X = solver_->solve(G * c_);  // X A0 − F X = G C_s, C_s the row-scaled C
    if (!c.X.allFinite()) return std::nullopt;
    if (c.X.rows() == 0) {
      c.L = Matrix::Zero(0, outputs_);
      c.x_condition = Scalar(1);
      return c;
    }
    const Eigen::JacobiSVD<Matrix> svd(c.X, Eigen::ComputeFullU | Eigen::ComputeFullV);
    const auto& sigma = svd.singularValues();
    if (!(sigma(sigma.size() - 1) > Scalar(100) * std::numeric_limits<Scalar>::epsilon() * sigma(0)))
      return std::nullopt;
    c.x_condition = sigma(0) / sigma(sigma.size() - 1);
    c.L = detail::scaled_by_powers_of_two<Scalar>(l0_ + svd.solve(G), output_exponents_, false);
    if (!c.L.allFinite()) return std::nullopt;
    return c;
  }

  /// A fresh standard-normal draw of G (N × m) from the seeded generator.
  [[nodiscard]] Matrix draw_parameter() { return gaussian(f_.rows(), outputs_); }

  /// How many draws are worth making: 1 with a single output (L is unique), else `options.tries`.
  [[nodiscard]] int draws() const noexcept { return outputs_ == 1 ? 1 : options_.tries; }

  /// The real matrix F carrying the requested spectrum.
  [[nodiscard]] const Matrix& target_matrix() const noexcept { return f_; }

 private:
  Matrix gaussian(Index rows, Index cols) {
    std::normal_distribution<double> normal(0.0, 1.0);
    Matrix g(rows, cols);
    for (Index j = 0; j < cols; ++j)
      for (Index i = 0; i < rows; ++i) g(i, j) = Scalar(normal(rng_));
    return g;
  }

  PolePlacementOptions options_;
  std::mt19937_64 rng_;
  Index outputs_ = 0;
  Eigen::Matrix<int, Eigen::Dynamic, 1> output_exponents_;  // row k of c_ is row k of C times 2^-e_k
  Matrix f_, c_, l0_;
  std::optional<SylvesterSolver<Scalar>> solver_;
};

/// Output-injection gain L with the certificate of its placement.
template <typename Scalar, int N, int M>
struct OutputInjectionGain {
  Eigen::Matrix<Scalar, N, M> L;        ///< \f$A - LC\f$ has the requested spectrum (file comment: tests 1–3)
  Scalar cayley_hamilton_residual = 0;  ///< verified below `verification_tolerance`
  Scalar transformation_condition = 0;  ///< cond₂(X): sensitivity of the placed eigenvalues
  Scalar eigenvalue_mismatch = 0;       ///< largest |computed − requested| eigenvalue (greedy matching; tests 2–3)
};

/// The names the refusals of `place_output_injection_dynamic` use:
/// "<who>: argument '<pair>' is not <property>", and `closed_loop` for the
/// placed matrix. `place_state_feedback_dynamic` passes those of the problem
/// it dualizes.
struct PlacementNames {
  std::string_view who = "place_output_injection";
  std::string_view pair = "A, C";
  std::string_view property = "observable";
  std::string_view closed_loop = "A - LC";
};

/// Gain L (N × m) such that \f$A - LC\f$ has the spectrum `poles` (closed
/// under conjugation), on run-time sizes: the Sylvester placement of the file
/// comment (Bhattacharyya and de Souza 1982: \f$XA_0 - FX = GC\f$,
/// \f$L = L_0 + X^{-1}G\f$ by `PolePlacer`), keeping among `options.tries` draws
/// of G (one for a single output) the one whose X is best conditioned, then
/// verified by the three tests of the file comment. One instance per scalar
/// type serves every size (compiled once in `adaptobs::precompiled`);
/// `place_output_injection` is the same for fixed-size arguments.
///
/// Refusals (`ConfigurationError` naming `names.who`): A not square or not
/// finite, C not finite or without A's columns, not one pole per state, a
/// pair that is not observable (naming its unobservable modes), an
/// `options.eigenvalue_tolerance` outside [0, 1), a transformation X singular
/// in every draw, and a placement that fails test 1 (the pair nearly not
/// observable) or tests 2–3 (the poles too clustered for the pair's conditioning).
template <typename Scalar>
[[nodiscard]] OutputInjectionGain<Scalar, Eigen::Dynamic, Eigen::Dynamic> place_output_injection_dynamic(
    const Eigen::MatrixX<Scalar>& A, const Eigen::MatrixX<Scalar>& C, const ComplexVector<Scalar>& poles,
    const PolePlacementOptions& options = {}, const PlacementNames& names = {}) {
  using Matrix = Eigen::MatrixX<Scalar>;
  const std::string_view who = names.who, pair = names.pair, property = names.property, closed_loop = names.closed_loop;
  const Scalar eig_tol = detail::default_eigenvalue_tolerance<Scalar>(options.eigenvalue_tolerance);
  if (!(options.eigenvalue_tolerance >= 0 && eig_tol < Scalar(1)))
    fail_argument(who, "options.eigenvalue_tolerance", "must be in [0, 1) (0 selects the default)");
  PolePlacer<Scalar> placer(A, C, poles, options, who, pair, property);
  std::optional<typename PolePlacer<Scalar>::Candidate> best;
  for (int t = 0; t < placer.draws(); ++t) {
    auto c = placer.candidate(placer.draw_parameter());
    if (c && (!best || c->x_condition < best->x_condition)) best = std::move(c);
  }
  if (!best)
    fail_argument(who, "poles", "could not be placed: the Sylvester transformation was singular in every draw");
  const Matrix closed = A - best->L * C;
  OutputInjectionGain<Scalar, Eigen::Dynamic, Eigen::Dynamic> result;
  result.L = best->L;
  result.transformation_condition = best->x_condition;
  result.cayley_hamilton_residual = cayley_hamilton_residual(closed, poles);
  const Scalar tol = detail::default_verification_tolerance<Scalar>(options.verification_tolerance);
  if (!(result.cayley_hamilton_residual <= tol)) {
    std::ostringstream os;
    os << "could not be placed to the required accuracy (Cayley-Hamilton residual " << result.cayley_hamilton_residual
       << " > " << tol << "): the pair is nearly not " << property;
    fail_argument(who, "poles", os.str());
  }
  const Index n = A.rows();
  if (n == 0) return result;
  const auto too_clustered = [&](std::ostringstream& os) {
    os << ": the requested poles are too clustered for the conditioning of the pair '" << pair
       << "' (the transformation that places them has condition number " << result.transformation_condition << ")";
    fail_argument(who, "poles", os.str());
  };
  const ComplexVector<Scalar> eig = detail::dense_eigenvalues(closed);
  // Test 2: the stability region of the request is kept.
  if ((poles.array().abs() < Scalar(1)).all() && !(eig.array().abs().maxCoeff() < Scalar(1))) {
    std::ostringstream os;
    os << "could not be placed: every requested pole lies inside the unit circle, but " << closed_loop
       << " has spectral radius " << eig.array().abs().maxCoeff();
    too_clustered(os);
  }
  if ((poles.array().real() < Scalar(0)).all() && !(eig.array().real().maxCoeff() < Scalar(0))) {
    std::ostringstream os;
    os << "could not be placed: every requested pole lies in the open left half-plane, but " << closed_loop
       << " has an eigenvalue with real part " << eig.array().real().maxCoeff();
    too_clustered(os);
  }
  // Test 3: each pole of multiplicity k within τ^(1/k)‖A − LC‖_F of its matched eigenvalue.
  const Scalar scale = closed.norm();
  const std::vector<Scalar> distance = detail::matched_eigenvalue_distances(eig, poles);
  const std::vector<Index> multiplicity = detail::pole_multiplicities(poles);
  Scalar worst = 0;
  for (const Scalar d : distance) worst = std::max(worst, d);
  result.eigenvalue_mismatch = worst;
  Index violated = -1;  // the pole farthest beyond its bound, relative to it
  Scalar violated_ratio = 0;
  for (Index i = 0; i < n; ++i) {
    const Scalar bound = std::pow(eig_tol, Scalar(1) / Scalar(multiplicity[std::size_t(i)])) * scale;
    const Scalar ratio = distance[std::size_t(i)] / bound;
    if (!(distance[std::size_t(i)] <= bound) && (violated < 0 || !(ratio <= violated_ratio))) {
      violated = i;
      violated_ratio = ratio;
    }
  }
  if (violated >= 0) {
    const Index i = violated;
    const Index k = multiplicity[std::size_t(i)];
    std::ostringstream os;
    os << "could not be placed to the required accuracy: the eigenvalue of " << closed_loop
       << " matched to the requested pole "
       << detail::format_complex_list<Scalar>(ComplexVector<Scalar>::Constant(1, poles(i))) << " (multiplicity " << k
       << ") is " << distance[std::size_t(i)] << " away, beyond the tolerance "
       << std::pow(eig_tol, Scalar(1) / Scalar(k)) * scale << " (eigenvalue tolerance " << eig_tol << " to the power 1/"
       << k << ", times ||" << closed_loop << "||_F)";
    too_clustered(os);
  }
  return result;
}
#ifdef ADAPTOBS_PRECOMPILED
ADAPTOBS_INSTANTIATE OutputInjectionGain<double, Eigen::Dynamic, Eigen::Dynamic> place_output_injection_dynamic<double>(
    const Eigen::MatrixXd&, const Eigen::MatrixXd&, const ComplexVector<double>&, const PolePlacementOptions&,
    const PlacementNames&);
#endif

/// Gain L (N × m) such that \f$A - LC\f$ has the spectrum `poles` (real or
/// complex vector, closed under conjugation). Throws `ConfigurationError` when
/// (A, C) is not observable or the placement cannot be verified: a returned L
/// passes the three tests of the file comment (Cayley–Hamilton residual, the
/// requested stability region kept, each pole of multiplicity k placed within
/// \f$\tau^{1/k}\|A - LC\|_F\f$).
template <class DA, class DC, class DP>
[[nodiscard]] auto place_output_injection(const Eigen::MatrixBase<DA>& A, const Eigen::MatrixBase<DC>& C,
                                          const Eigen::MatrixBase<DP>& poles, PolePlacementOptions options = {}) {
  using Scalar = typename DA::Scalar;
  const auto d =
      place_output_injection_dynamic<Scalar>(detail::dynamic_copy(A), detail::dynamic_copy(C),
                                             detail::complex_poles<Scalar>(poles, "place_output_injection"), options);
  return OutputInjectionGain<Scalar, DA::RowsAtCompileTime, DC::RowsAtCompileTime>{
      d.L, d.cayley_hamilton_residual, d.transformation_condition, d.eigenvalue_mismatch};
}

/// State-feedback gain K (m × N) with the certificate of its placement.
template <typename Scalar, int N, int M>
struct StateFeedbackGain {
  Eigen::Matrix<Scalar, M, N> K;  ///< \f$A - BK\f$ has the requested spectrum
  Scalar cayley_hamilton_residual = 0;
  Scalar transformation_condition = 0;
  Scalar eigenvalue_mismatch = 0;
};

/// Gain K (m × N) such that \f$A - BK\f$ has the spectrum `poles`, on
/// run-time sizes, by duality: \f$K^T\f$ is `place_output_injection_dynamic`
/// for \f$(A^T, B^T)\f$, since \f$A^T - K^TB^T\f$ has the spectrum of A − BK.
/// Its refusals, in the terms of (A, B): A not square or not finite, B not
/// finite or without A's rows, (A, B) not controllable, and a placement
/// failing the tests of the file comment.
template <typename Scalar>
[[nodiscard]] StateFeedbackGain<Scalar, Eigen::Dynamic, Eigen::Dynamic> place_state_feedback_dynamic(
    const Eigen::MatrixX<Scalar>& A, const Eigen::MatrixX<Scalar>& B, const ComplexVector<Scalar>& poles,
    const PolePlacementOptions& options = {}) {
  constexpr std::string_view who = "place_state_feedback";
  require_square(A, who, "A");
  require_finite(A, who, "A");
  // Checked before the dual problem, which would name Bᵀ as its C.
  require_finite_shape(B, A.rows(), B.cols(), who, "B");
  const auto dual = place_output_injection_dynamic<Scalar>(A.transpose(), B.transpose(), poles, options,
                                                           {who, "A, B", "controllable", "A - BK"});
  return {dual.L.transpose(), dual.cayley_hamilton_residual, dual.transformation_condition, dual.eigenvalue_mismatch};
}

/// Gain K (m × N) such that \f$A - BK\f$ has the spectrum `poles`:
/// `place_state_feedback_dynamic` on copies, sized as A and B. Throws
/// `ConfigurationError` when (A, B) is not controllable or the placement
/// cannot be verified (the tests of the file comment, applied to
/// \f$A^T - K^TB^T\f$, whose spectrum is that of A − BK).
template <class DA, class DB, class DP>
[[nodiscard]] auto place_state_feedback(const Eigen::MatrixBase<DA>& A, const Eigen::MatrixBase<DB>& B,
                                        const Eigen::MatrixBase<DP>& poles, PolePlacementOptions options = {}) {
  using Scalar = typename DA::Scalar;
  constexpr std::string_view who = "place_state_feedback";
  require_square(A, who, "A");
  require_finite(A, who, "A");
  require_finite_shape(B, A.rows(), B.cols(), who, "B");
  const auto d = place_state_feedback_dynamic<Scalar>(detail::dynamic_copy(A), detail::dynamic_copy(B),
                                                      detail::complex_poles<Scalar>(poles, who), options);
  return StateFeedbackGain<Scalar, DA::RowsAtCompileTime, DB::ColsAtCompileTime>{
      d.K, d.cayley_hamilton_residual, d.transformation_condition, d.eigenvalue_mismatch};
}

#ifdef ADAPTOBS_PRECOMPILED
ADAPTOBS_INSTANTIATE StateFeedbackGain<double, Eigen::Dynamic, Eigen::Dynamic> place_state_feedback_dynamic<double>(
    const Eigen::MatrixXd&, const Eigen::MatrixXd&, const ComplexVector<double>&, const PolePlacementOptions&);
#endif

}  // namespace adaptobs
