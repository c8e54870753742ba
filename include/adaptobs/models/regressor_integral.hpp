#pragma once
/// \file
/// The regressor of a continuous-time system over one sampling period.
///
/// For \f$\dot x = Ax + \varphi(t)\theta\f$ sampled at \f$t_k\f$ with period T,
/// \f[ x(t_k + T) = e^{AT}\big(x(t_k) + H_k\theta\big),\qquad
///     H_k = \int_{t_k}^{t_k+T} e^{(t_k - s)A}\varphi(s)\,ds, \f]
/// (Guiro et al. (2008), §2, with period T instead of 1), and the
/// discrete-time regressor is \f$\Psi_k = e^{AT}H_k = \int_{t_k}^{t_k+T}e^{(t_k+T-s)A}\varphi(s)\,ds\f$:
/// \f$x_{k+1} = e^{AT}x_k + \Psi_k\theta\f$ holds exactly. Two evaluations:
///
/// - `RegressorIntegral`: any φ (a callable \f$t\mapsto\varphi(t)\in\mathbb{R}^{n\times p}\f$),
///   by adaptive Gauss–Kronrod quadrature (7-point Gauss, 15-point Kronrod)
///   with bisection until the estimated error meets the requested tolerance.
///   The kernels \f$e^{-\sigma A}\f$ at the nodes of every bisection level are
///   matrix exponentials computed once at construction; a panel [a, a + h] is
///   integrated relative to its start and carried to \f$t_k\f$ by
///   \f$e^{-(a-t_k)A}\f$, itself built by products of the levels' half-steps
///   \f$e^{-(h/2)A}\f$, so an evaluation costs 15 products
///   \f$e^{-\sigma_iA}\varphi(\sigma_i)\f$ per panel and no exponential.
/// - `PolynomialRegressorIntegral`: φ polynomial on the period,
///   \f$\varphi(t_k+\tau) = \sum_{j\le d}P_j\tau^j\f$ (zero-order hold: d = 0,
///   linear interpolation: d = 1), exactly: the moments
///   \f$\int_0^Te^{(T-\tau)A}\tau^j/j!\,d\tau\f$ are the top block row of
///   \f$\exp\!\big(\begin{bmatrix}A & I & & \\ & 0 & I & \\ && \ddots & I\\ &&& 0\end{bmatrix}T\big)\f$
///   (C. F. Van Loan, "Computing integrals involving the matrix exponential",
///   IEEE TAC 23(3), 1978), computed once; an evaluation is d + 1 products.

#include <adaptobs/core/detail/max_abs.hpp>
#include <adaptobs/core/dimensions.hpp>
#include <adaptobs/core/matrix_exponential.hpp>
#include <adaptobs/core/validation.hpp>

#include <Eigen/Core>

#include <array>
#include <cmath>
#include <concepts>
#include <limits>
#include <span>
#include <vector>

namespace adaptobs {

/// \f$H_k\f$ and \f$\Psi_k = e^{AT}H_k\f$ over one period, with the quadrature's error estimate.
template <typename Scalar, int NX, int NP>
struct SampledRegressor {
  Eigen::Matrix<Scalar, NX, NP> H;    ///< \f$\int_{t_k}^{t_k+T}e^{(t_k-s)A}\varphi(s)ds\f$
  Eigen::Matrix<Scalar, NX, NP> Psi;  ///< \f$e^{AT}H_k\f$, the discrete-time regressor
  /// Estimated largest entry error of H: the sum over panels of \f$|K_{15} - G_7|\f$,
  /// a conservative bound for the 15-point result (0 for the exact polynomial form).
  Scalar error_estimate = 0;
  bool converged = true;  ///< the requested tolerance was met within the allowed bisections
  int panels = 1;         ///< panels the period was split into (1 for the exact polynomial form)
};

struct RegressorIntegralOptions {
  /// Requested bound on the error estimate relative to the largest entry of H;
  /// 0 selects \f$\varepsilon^{3/4}\f$ (1.8e-12 in double, 6.4e-6 in float).
  double relative_tolerance = 0;
  /// Absolute bound on the error estimate (for an H that may vanish).
  double absolute_tolerance = 0;
  /// Deepest bisection: no panel narrower than \f$T/2^{\text{max\_depth}}\f$
  /// (the kernels of every level are matrix exponentials computed at construction).
  int max_depth = 20;
  /// Most panels per period (the workspace is allocated once).
  int max_panels = 100;
};

namespace detail {
/// Gauss–Kronrod 7/15 rule on [−1, 1], nodes in increasing order; the Gauss
/// nodes are those of odd index (R. Piessens et al., QUADPACK, 1983).
struct GaussKronrod15 {
  static constexpr std::array<double, 15> nodes{
      -0.991455371120812639206854697526329, -0.949107912342758524526189684047851,
      -0.864864423359769072789712788640926, -0.741531185599394439863864773280788,
      -0.586087235467691130294144845693013, -0.405845151377397166906606412076961,
      -0.207784955007898467600689403773245, 0.0,
      0.207784955007898467600689403773245,  0.405845151377397166906606412076961,
      0.586087235467691130294144845693013,  0.741531185599394439863864773280788,
      0.864864423359769072789712788640926,  0.949107912342758524526189684047851,
      0.991455371120812639206854697526329};
  static constexpr std::array<double, 15> kronrod_weights{
      0.022935322010529224963732008058970, 0.063092092629978553290700663189204, 0.104790010322250183839876322541518,
      0.140653259715525918745189590510238, 0.169004726639267902826583426598550, 0.190350578064785409913256402421014,
      0.204432940075298892414161999234649, 0.209482141084727828012999174891714, 0.204432940075298892414161999234649,
      0.190350578064785409913256402421014, 0.169004726639267902826583426598550, 0.140653259715525918745189590510238,
      0.104790010322250183839876322541518, 0.063092092629978553290700663189204, 0.022935322010529224963732008058970};
  /// Weights of the 7 Gauss nodes, at indices 1, 3, ..., 13.
  static constexpr std::array<double, 7> gauss_weights{
      0.129484966168869693270611432679082, 0.279705391489276667901467771423780, 0.381830050505118944950369775488975,
      0.417959183673469387755102040816327, 0.381830050505118944950369775488975, 0.279705391489276667901467771423780,
      0.129484966168869693270611432679082};
};

}  // namespace detail

/// Base of both regressor integrals, not used on its own: the types of their
/// results, the period T and the transition \f$e^{AT}\f$ each computes, with the
/// checks of (A, T) they share.
template <typename Scalar, int NX, int NP>
class RegressorIntegralBase {
 public:
  using StateMatrix = Eigen::Matrix<Scalar, NX, NX>;
  using Regressor = Eigen::Matrix<Scalar, NX, NP>;
  using Result = SampledRegressor<Scalar, NX, NP>;

  /// \f$e^{AT}\f$.
  [[nodiscard]] const StateMatrix& transition() const noexcept { return transition_; }
  [[nodiscard]] Scalar period() const noexcept { return period_; }

 protected:
  /// A square and finite, T > 0; `who` names the integral in the errors.
  RegressorIntegralBase(const StateMatrix& A, Scalar period, std::string_view who) : period_(period) {
    require_square(A, who, "A");
    require_finite(A, who, "A");
    require_positive(period, who, "period");
  }

  /// e^M of one of the integral's exponentials (of ±σA with σ up to T): an
  /// overflow is refused naming what the caller gave, (A, period), not M.
  static Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic> exponential(
      const Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>& m, std::string_view who) {
    try {
      return matrix_exponential(m);
    } catch (const ConfigurationError&) {  // the only refusal left for a finite square argument: overflow
      fail_argument(who, "A, period",
                    "give exponentials e^{±A t}, 0 <= t <= period, beyond the floating-point range: shorten "
                    "period");
    }
  }

  Scalar period_;
  StateMatrix transition_;  // computed by the integral's constructor
};

/// \f$H_k\f$ and \f$\Psi_k\f$ of any regressor φ by adaptive Gauss–Kronrod quadrature (see file comment).
///
/// Error control is global, as in QUADPACK's QAG: the panel with the largest
/// error estimate is bisected until the sum of the estimates meets the
/// tolerance, so a kink or a jump of φ inside the period costs a few panels
/// per bisection level around it and nothing elsewhere. The panels live in a
/// workspace allocated at construction (first use for dynamic sizes), hence
/// `integrate` is not const and one object must not be used by two threads at once.
template <typename Scalar, int NX, int NP>
class RegressorIntegral : public RegressorIntegralBase<Scalar, NX, NP> {
  using Base = RegressorIntegralBase<Scalar, NX, NP>;

 public:
  using typename Base::StateMatrix, typename Base::Regressor, typename Base::Result;

  /// \param A continuous-time dynamics (n × n), \param period sampling period T > 0.
  RegressorIntegral(const StateMatrix& A, Scalar period, RegressorIntegralOptions options = {})
      : Base(A, period, "RegressorIntegral"), options_(options) {
    constexpr std::string_view who = "RegressorIntegral";
    require(options.max_depth >= 0 && options.max_depth <= 40, who, "options.max_depth", "must be in [0, 40]");
    require(options.max_panels >= 1, who, "options.max_panels", "must be at least 1");
    require(options.relative_tolerance >= 0 && options.absolute_tolerance >= 0, who, "options",
            "tolerances must be non-negative");
    relative_tolerance_ = options.relative_tolerance > 0
                              ? Scalar(options.relative_tolerance)
                              : std::pow(std::numeric_limits<Scalar>::epsilon(), Scalar(0.75));
    using Dynamic = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;
    const Dynamic a = A;
    n_ = A.rows();
    this->transition_ = Base::exponential(a * period, who);
    levels_.resize(std::size_t(options.max_depth) + 1);
    Scalar h = period;
    for (Level& level : levels_) {
      for (std::size_t i = 0; i < 15; ++i) {
        const Scalar sigma = h / 2 * (Scalar(1) + Scalar(detail::GaussKronrod15::nodes[i]));
        level.kernel[i] = Base::exponential(-sigma * a, who);
      }
      level.half = Base::exponential(-h / 2 * a, who);
      h /= 2;
    }
    panels_.resize(std::size_t(options.max_panels));
    for (Panel& panel : panels_) panel.shift.setIdentity(n_, n_);
  }

  /// \f$H_k\f$ and \f$\Psi_k\f$ over \f$[t_0, t_0 + T]\f$; `phi(t)` returns \f$\varphi(t)\f$ (n × p).
  /// A φ of other than n rows, or (p of run-time size) of columns that change
  /// within the call, throws a `ConfigurationError` naming `phi(t)`.
  template <class Phi>
    requires std::invocable<const Phi&, Scalar>
  [[nodiscard]] Result integrate(const Phi& phi, Scalar t0) {
    Result result;
    integrate(phi, t0, result);
    return result;
  }

  /// As above, into `out` (no allocation for fixed sizes); returns `out.converged`.
  template <class Phi>
    requires std::invocable<const Phi&, Scalar>
  bool integrate(const Phi& phi, Scalar t0, Result& out) {
    columns_ = NP;  // with a run-time p, set by the first value of φ
    Regressor gauss;
    Panel& first = panels_[0];
    first.shift.setIdentity(n_, n_);
    first.start = t0;
    first.depth = 0;
    first.shift_norm = Scalar(1);
    evaluate(phi, first, gauss);
    const Scalar tolerance =
        std::max(Scalar(options_.absolute_tolerance), relative_tolerance_ * detail::max_abs(first.integral));
    std::size_t count = 1;
    Scalar error = first.error;
    while (error > std::max(tolerance, roundoff_floor(count)) && count < panels_.size()) {
      // Bisect the panel with the largest error that can still be bisected.
      std::size_t worst = count;
      for (std::size_t i = 0; i < count; ++i)
        if (!panels_[i].frozen && (worst == count || panels_[i].error > panels_[worst].error)) worst = i;
      if (worst == count) break;
      Panel& left = panels_[worst];
      Panel& right = panels_[count++];
      const Level& parent = levels_[std::size_t(left.depth)];
      ++left.depth;
      right.depth = left.depth;
      right.start = left.start + std::ldexp(this->period_, -left.depth);
      right.shift.noalias() = left.shift * parent.half;  // e^{−(a + h/2 − t₀)A}
      right.shift_norm = right.shift.cwiseAbs().rowwise().sum().maxCoeff();
      evaluate(phi, left, gauss);
      evaluate(phi, right, gauss);
      error = 0;
      for (std::size_t i = 0; i < count; ++i) error += panels_[i].error;
    }
    out.H.noalias() = first.shift * first.integral;
    for (std::size_t i = 1; i < count; ++i) out.H.noalias() += panels_[i].shift * panels_[i].integral;
    out.Psi.noalias() = this->transition_ * out.H;
    out.error_estimate = error;
    out.converged = error <= std::max(tolerance, roundoff_floor(count));
    out.panels = int(count);
    return out.converged;
  }

 private:
  struct Level {
    std::array<StateMatrix, 15> kernel;  // e^{-σ_i A} at the nodes of a panel of this level
    StateMatrix half;                    // e^{-(h/2) A}: from a panel's start to its midpoint
  };
  struct Panel {
    StateMatrix shift;      // e^{-(a − t₀)A}: carries the panel's integral to t₀
    Regressor integral;     // ∫₀^h e^{-σA} φ(a + σ) dσ, 15-point Kronrod
    Scalar start = 0;       // a
    Scalar shift_norm = 1;  // ‖shift‖∞
    Scalar error = 0;       // ‖shift‖∞ · max|K₁₅ − G₇|
    Scalar magnitude = 0;   // ‖shift‖∞ · Σ wᵢ max|termᵢ| · h/2: the round-off scale
    int depth = 0;          // the panel is T / 2^depth wide
    bool frozen = false;    // at the round-off level or at the deepest level
  };

  // Round-off floor of the sum of `count` panels.
  Scalar roundoff_floor(std::size_t count) const {
    Scalar magnitude = 0;
    for (std::size_t i = 0; i < count; ++i) magnitude += panels_[i].magnitude;
    return Scalar(50) * std::numeric_limits<Scalar>::epsilon() * magnitude;
  }

  // 15-point Kronrod and 7-point Gauss sums over the panel, relative to its start.
  template <class Phi>
  void evaluate(const Phi& phi, Panel& panel, Regressor& gauss) {
    using Rule = detail::GaussKronrod15;
    const Level& level = levels_[std::size_t(panel.depth)];
    const Scalar half_width = std::ldexp(this->period_, -panel.depth) / 2;
    Regressor term;
    Scalar magnitude = 0;
    for (std::size_t i = 0; i < 15; ++i) {
      const Scalar sigma = half_width * (Scalar(1) + Scalar(Rule::nodes[i]));
      decltype(auto) value = phi(panel.start + sigma);
      if (columns_ == Eigen::Dynamic) columns_ = value.cols();
      require_finite_shape(value, n_, columns_, "RegressorIntegral::integrate", "phi(t)");
      term.noalias() = level.kernel[i] * value;
      if (i == 0) {
        panel.integral = Scalar(Rule::kronrod_weights[i]) * term;
        gauss.setZero(term.rows(), term.cols());
      } else {
        panel.integral += Scalar(Rule::kronrod_weights[i]) * term;
      }
      if (i % 2 == 1) gauss += Scalar(Rule::gauss_weights[i / 2]) * term;
      magnitude += Scalar(Rule::kronrod_weights[i]) * detail::max_abs(term);
    }
    panel.integral *= half_width;
    gauss *= half_width;
    const Scalar difference = detail::max_abs(panel.integral - gauss);
    panel.magnitude = panel.shift_norm * magnitude * half_width;
    panel.error = panel.shift_norm * difference;
    panel.frozen = panel.depth >= options_.max_depth ||
                   difference <= Scalar(50) * std::numeric_limits<Scalar>::epsilon() * magnitude * half_width;
  }

  RegressorIntegralOptions options_;
  Scalar relative_tolerance_ = 0;
  Index n_ = 0;
  Index columns_ = NP;  ///< p, of the current call's φ when NP is dynamic
  std::vector<Level> levels_;
  std::vector<Panel> panels_;
};

/// \f$H_k\f$ and \f$\Psi_k\f$, exactly, for φ polynomial on each period (see file comment).
template <typename Scalar, int NX, int NP>
class PolynomialRegressorIntegral : public RegressorIntegralBase<Scalar, NX, NP> {
  using Base = RegressorIntegralBase<Scalar, NX, NP>;

 public:
  using typename Base::StateMatrix, typename Base::Regressor, typename Base::Result;

  /// \param degree highest power d of τ in \f$\varphi(t_k+\tau) = \sum_{j\le d}P_j\tau^j\f$.
  PolynomialRegressorIntegral(const StateMatrix& A, Scalar period, int degree)
      : Base(A, period, "PolynomialRegressorIntegral") {
    constexpr std::string_view who = "PolynomialRegressorIntegral";
    require(degree >= 0 && degree <= 16, who, "degree", "must be in [0, 16]");
    using Dynamic = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;
    const Index n = A.rows();
    const Index blocks = degree + 2;
    // Z = [A I 0 …; 0 0 I …; …; 0 … 0] T: the top block row of e^Z holds
    // e^{AT} and the moments ∫₀ᵀ e^{±(T−s)A} s^j/j! ds (sign of A).
    const auto moments = [&](Scalar sign) {
      Dynamic z = Dynamic::Zero(n * blocks, n * blocks);
      z.topLeftCorner(n, n) = sign * period * A;
      for (Index b = 0; b + 1 < blocks; ++b) z.block(b * n, (b + 1) * n, n, n).setIdentity() *= period;
      return Dynamic(Base::exponential(z, who).topRows(n));
    };
    const Dynamic forward = moments(Scalar(1));
    const Dynamic backward = moments(Scalar(-1));
    this->transition_ = forward.leftCols(n);
    psi_moments_.resize(std::size_t(degree) + 1);
    h_moments_.resize(std::size_t(degree) + 1);
    // Ψ: ∫₀ᵀ e^{(T−τ)A} τ^j dτ = j!·(block j+1 of the forward row).
    // H: ∫₀ᵀ e^{−uA} u^i du with u^i = Σ_l C(i,l) T^{i−l} (−1)^l (T−u)^l and
    //    ∫₀ᵀ e^{−uA}(T−u)^l/l! du = block l+1 of the backward row.
    for (int i = 0; i <= degree; ++i) {
      Scalar factorial = 1;
      for (int j = 2; j <= i; ++j) factorial *= Scalar(j);
      psi_moments_[std::size_t(i)] = factorial * forward.middleCols((i + 1) * n, n);
      Dynamic h = Dynamic::Zero(n, n);
      Scalar binomial = 1;  // C(i, l)
      Scalar l_factorial = 1;
      for (int l = 0; l <= i; ++l) {
        if (l > 0) {
          binomial = binomial * Scalar(i - l + 1) / Scalar(l);
          l_factorial *= Scalar(l);
        }
        const Scalar sign = (l % 2 == 0) ? Scalar(1) : Scalar(-1);
        h += (binomial * std::pow(period, Scalar(i - l)) * sign * l_factorial) * backward.middleCols((l + 1) * n, n);
      }
      h_moments_[std::size_t(i)] = h;
    }
  }

  /// \f$H_k\f$ and \f$\Psi_k\f$ for \f$\varphi(t_k+\tau) = \sum_j P_j\tau^j\f$,
  /// `coefficients` = \f$(P_0, \dots, P_j)\f$, at most `degree() + 1` of them.
  [[nodiscard]] Result integrate(std::span<const Regressor> coefficients) const {
    Result result;
    integrate(coefficients, result);
    return result;
  }

  void integrate(std::span<const Regressor> coefficients, Result& out) const {
    constexpr std::string_view who = "PolynomialRegressorIntegral::integrate";
    require(!coefficients.empty() && coefficients.size() <= psi_moments_.size(), who, "coefficients",
            "must hold 1 to degree + 1 matrices");
    for (const Regressor& p : coefficients)
      require_finite_shape(p, this->transition_.rows(), coefficients[0].cols(), who, "coefficients");
    out.H.noalias() = h_moments_[0] * coefficients[0];
    out.Psi.noalias() = psi_moments_[0] * coefficients[0];
    for (std::size_t j = 1; j < coefficients.size(); ++j) {
      out.H.noalias() += h_moments_[j] * coefficients[j];
      out.Psi.noalias() += psi_moments_[j] * coefficients[j];
    }
    out.error_estimate = 0;
    out.converged = true;
  }

  [[nodiscard]] int degree() const noexcept { return int(psi_moments_.size()) - 1; }

 private:
  std::vector<StateMatrix> psi_moments_;  // ∫₀ᵀ e^{(T−τ)A} τ^j dτ
  std::vector<StateMatrix> h_moments_;    // ∫₀ᵀ e^{−τA} τ^j dτ
};

}  // namespace adaptobs
