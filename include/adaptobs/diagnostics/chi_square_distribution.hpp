#pragma once
/// \file
/// The χ² distribution's upper tail and quantile, for setting detector
/// thresholds from a false-alarm probability.
///
/// \f$\Pr[\chi^2_\nu > x] = Q(\nu/2, x/2)\f$, the regularized upper incomplete
/// gamma function. \f$Q\f$ is evaluated by its power series for \f$P = 1 - Q\f$
/// when \f$x < a + 1\f$ and by its continued fraction (modified Lentz) otherwise,
/// each the rapidly converging form on its side (Abramowitz & Stegun 6.5.29 and
/// 6.5.31), both until a term changes the result by less than the rounding
/// unit. The quantile inverts the tail by bisection on a bracket, which is
/// slow next to Newton's method but cannot fail, and runs once, at design time.
///
/// **Weighted sums.** A sum of squares of correlated Gaussian variables,
/// \f$Q = z^Tz\f$ with \f$z \sim N(0, \Sigma)\f$, is \f$\sum_i\lambda_i\chi^2_{1,i}\f$
/// over the eigenvalues \f$\lambda_i\f$ of Σ, independent terms. Its tail,
/// `weighted_chi_square_upper_tail`, is the inversion integral of its moment
/// generating function \f$M(s) = \prod_i(1 - 2\lambda_is)^{-1/2}\f$ (Imhof 1961
/// writes the same integral on the imaginary axis; Davies 1973 sums it by the
/// trapezoidal rule), here on a contour through the saddle point, where the
/// integrand is a positive bell without cancellation: the tail comes with a
/// relative error of about 1e-13 however far out it lies (the derivation is at
/// `detail::weighted_chi_square_contour`).

#include <adaptobs/core/detail/bisection.hpp>
#include <adaptobs/core/validation.hpp>

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <numbers>
#include <span>
#include <string_view>

namespace adaptobs {

namespace detail {

/// \f$\ln\Gamma(x)\f$ for x > 0 by Lanczos' approximation (g = 7, nine terms;
/// relative error about 1e-15), with the reflection formula below 1/2. Used
/// instead of `std::lgamma`, which writes the global `signgam` and so may not
/// run on several threads at once (detectors are built inside the concurrent
/// scenarios of `evaluate_detection`).
inline double log_gamma(double x) {
  constexpr double pi = 3.141592653589793238462643;
  if (x < 0.5) return std::log(pi / std::sin(pi * x)) - log_gamma(1 - x);
  constexpr double c[9] = {0.99999999999980993,  676.5203681218851,     -1259.1392167224028,
                           771.32342877765313,   -176.61502916214059,   12.507343278686905,
                           -0.13857109526572012, 9.9843695780195716e-6, 1.5056327351493116e-7};
  const double z = x - 1;
  double series = c[0];
  for (int i = 1; i < 9; ++i) series += c[i] / (z + i);
  const double t = z + 7.5;
  return 0.5 * std::log(2 * pi) + (z + 0.5) * std::log(t) - t + std::log(series);
}

/// Iterations after which the series and the continued fraction stop: both need
/// O(√a) terms near x ≈ a.
inline int gamma_iterations(double a) { return 1000 + static_cast<int>(100 * std::sqrt(a)); }

/// \f$P(a, x)\f$ by its series \f$e^{-x}x^a\sum_n x^n/\Gamma(a+n+1)\f$, for \f$x < a + 1\f$.
inline double lower_gamma_series(double a, double x) {
  constexpr double eps = std::numeric_limits<double>::epsilon();
  double term = 1.0 / a;
  double sum = term;
  for (int n = 1, last = gamma_iterations(a); n < last; ++n) {
    term *= x / (a + n);
    sum += term;
    if (std::abs(term) < std::abs(sum) * eps) break;
  }
  return sum * std::exp(-x + a * std::log(x) - log_gamma(a));
}

/// \f$Q(a, x)\f$ by its continued fraction, for \f$x \ge a + 1\f$.
inline double upper_gamma_fraction(double a, double x) {
  constexpr double tiny = 1e-300;
  constexpr double eps = std::numeric_limits<double>::epsilon();
  double b = x + 1.0 - a;
  double c = 1.0 / tiny;
  double d = 1.0 / b;
  double h = d;
  for (int i = 1, last = gamma_iterations(a); i < last; ++i) {
    const double an = -i * (i - a);
    b += 2.0;
    d = an * d + b;
    if (std::abs(d) < tiny) d = tiny;
    c = b + an / c;
    if (std::abs(c) < tiny) c = tiny;
    d = 1.0 / d;
    const double delta = d * c;
    h *= delta;
    if (std::abs(delta - 1.0) < eps) break;
  }
  return std::exp(-x + a * std::log(x) - log_gamma(a)) * h;
}

}  // namespace detail

/// Most degrees of freedom the tail is computed for. The prefactor
/// \f$e^{-x}x^a/\Gamma(a)\f$ is formed from terms of size \f$a\log x\f$, whose rounding
/// leaves a relative error of about \f$10^{-8}\f$ at \f$\nu = 10^7\f$ (\f$10^{-10}\f$ at
/// \f$10^6\f$) and grows with ν; beyond, the distribution functions refuse.
inline constexpr double chi_square_max_degrees_of_freedom = 1e7;
/// Fewest degrees of freedom the tail is computed for. Below 1/2 the series
/// gives \f$Q = 1 - P\f$ with P near 1, and the cancellation costs
/// \f$\log_{10}(1/\nu)\f$ digits more than elsewhere (the term 1/a overflows at
/// \f$\nu \approx 10^{-308}\f$); at \f$\nu = 10^{-2}\f$ the relative error is
/// still about \f$10^{-13}\f$. A χ² test's ν, W n_y or Satterthwaite's
/// \f$2(\mathrm{E}\,T)^2/\mathrm{Var}\,T\f$ of a sum of squares, is at least 1.
inline constexpr double chi_square_min_degrees_of_freedom = 1e-2;

namespace detail {
inline void require_chi_square_degrees_of_freedom(double degrees_of_freedom, std::string_view who,
                                                  std::string_view argument) {
  require(degrees_of_freedom >= chi_square_min_degrees_of_freedom, who, argument,
          "must be at least 1e-2 (chi_square_min_degrees_of_freedom): below, the tail loses its accuracy");
  require(degrees_of_freedom <= chi_square_max_degrees_of_freedom, who, argument,
          "must be at most 1e7 (chi_square_max_degrees_of_freedom): beyond, the tail loses its accuracy");
}
}  // namespace detail

/// \f$\Pr[\chi^2_\nu > x]\f$ for `chi_square_min_degrees_of_freedom`
/// \f$\le \nu \le\f$ `chi_square_max_degrees_of_freedom`.
[[nodiscard]] inline double chi_square_upper_tail(double degrees_of_freedom, double x) {
  detail::require_chi_square_degrees_of_freedom(degrees_of_freedom, "chi_square_upper_tail", "degrees_of_freedom");
  require(!std::isnan(x), "chi_square_upper_tail", "x", "must not be NaN");
  if (x <= 0) return 1.0;
  if (std::isinf(x)) return 0.0;
  const double a = degrees_of_freedom / 2, half = x / 2;
  return half < a + 1 ? 1.0 - detail::lower_gamma_series(a, half) : detail::upper_gamma_fraction(a, half);
}

/// The x with \f$\Pr[\chi^2_\nu > x] = p\f$, for \f$0 < p < 1\f$ (the threshold
/// a χ² test with false-alarm probability p compares its statistic to).
/// The bisection stops within a relative 1e-13 of x; the tests check the result
/// against tabulated and closed-form quantiles to 1e-10, down to p = 1e-200.
[[nodiscard]] inline double chi_square_upper_quantile(double degrees_of_freedom, double p) {
  constexpr std::string_view who = "chi_square_upper_quantile";
  detail::require_chi_square_degrees_of_freedom(degrees_of_freedom, who, "degrees_of_freedom");
  require(p > 0 && p < 1, who, "p", "must lie in (0, 1)");
  // The tail falls from 1 to 0 as x grows.
  const double x = detail::boundary_by_bisection(
      [&](double x) { return chi_square_upper_tail(degrees_of_freedom, x) > p; }, degrees_of_freedom + 10);
  // With few degrees of freedom and p near 1 the quantile, about
  // \f$2(\Gamma(\nu/2+1)(1-p))^{2/\nu}\f$, can fall below the normal doubles.
  require(x >= std::numeric_limits<double>::min(), who, "p",
          "is so close to 1 that the quantile at these degrees of freedom is below the smallest normal double");
  return x;
}

namespace detail {

inline void require_chi_square_weights(std::span<const double> weights, std::string_view who,
                                       std::string_view argument) {
  require(!weights.empty(), who, argument, "must hold at least one weight");
  double largest = 0;
  for (const double w : weights) {
    require(std::isfinite(w) && w >= 0, who, argument, "must hold finite, non-negative weights");
    largest = std::max(largest, w);
  }
  require(largest > 0, who, argument, "must hold a positive weight");
}

/// The inversion integral of \f$G(x) = \Pr[Q > x]\f$, \f$Q = \sum_i\lambda_i\chi^2_{1,i}\f$,
/// along a parabola through a saddle point c, for x > 0:
/// \f$I(c) = \frac{1}{2\pi i}\int F(s)\,ds\f$ with \f$F(s) = M(s)e^{-sx}/s\f$.
///
/// **The integral.** \f$1\{q > x\} = \frac{1}{2\pi i}\int_{c-i\infty}^{c+i\infty}
/// e^{s(q-x)}\frac{ds}{s}\f$ for c > 0 (close the line to the left for q > x,
/// enclosing the residue 1 at s = 0, to the right otherwise); its mean over Q
/// is \f$G(x) = I(c)\f$ for \f$0 < c < s^* = 1/(2\lambda_{max})\f$, where M is finite.
/// For c < 0 the line passes left of the pole, and \f$I(c) = G(x) - 1\f$.
/// F is analytic off the pole and the cuts \f$[1/(2\lambda_i), \infty)\f$, and
/// \f$|F| \le |M|e^{-x\,\mathrm{Re}\,s}/|s| \to 0\f$ as Re s → +∞, so the line
/// may be bent to the right into \f$s(t) = c + \beta t^2 + it\f$: the region between
/// them meets the real axis only at c. With \f$ds = (1 - 2i\beta t)\,i\,dt\f$ and
/// \f$F(\bar s) = \overline{F(s)}\f$,
/// \f[ I(c) = \frac1\pi\int_0^\infty \mathrm{Re}\big[F(s(t))(1 - 2i\beta t)\big]\,dt. \f]
///
/// **The contour.** c is the saddle point of \f$\log F = K(s) - sx - \log s\f$,
/// \f$K(s) = -\frac12\sum_i\log(1 - 2\lambda_is)\f$, on the real axis:
/// \f$K'(c) = \sum_i\lambda_i/(1 - 2\lambda_ic) = x + 1/c\f$, one root in \f$(0, s^*)\f$
/// (the upper tail, taken for x at or above the mean \f$\sum_i\lambda_i\f$) and one in
/// \f$(-\infty, 0)\f$ (the lower tail, \f$G = 1 + I\f$, below the mean), as
/// \f$K' - x - 1/s\f$ increases on each. There the vertical is the direction of
/// steepest descent to second order, so the integrand is a positive bell of
/// width \f$1/\sigma\f$, \f$\sigma^2 = (\log F)''(c) = \sum_i 2\lambda_i^2/(1 - 2\lambda_ic)^2 + 1/c^2\f$,
/// and the integral carries no cancellation: its relative error is that of the
/// rule. \f$\beta = \sigma^2/(2x)\f$ makes \f$|e^{-sx}| = e^{-cx}e^{-\sigma^2t^2/2}\f$:
/// a Gaussian decay on the bell's own scale, where on the line |F| falls only
/// as \f$t^{-1-m/2}\f$ for m weights (\f$t^{-3/2}\f$ for one).
///
/// **The rule.** The trapezoidal rule of step h on an integrand analytic in the
/// strip \f$|\mathrm{Im}\,t| < d\f$ errs by about \f$e^{-2\pi y/h}\f$ times the integrand's
/// size on the line \f$\mathrm{Im}\,t = -y\f$, any y < d (Poisson's summation formula: on
/// the vertical line it adds exactly \f$\sum_{k \ne 0}G(x + 2\pi k/h)e^{2\pi ck/h}\f$, Davies
/// 1973). F's singularities nearest the contour, s = 0 and \f$s = s^*\f$, lie at the
/// roots t of \f$\beta t^2 + it + c - s_0 = 0\f$; d is the least |Im t| of them. Off
/// the axis the bell grows as \f$e^{\sigma^2y^2/2}\f$, so the error is about
/// \f$e^{\sigma^2y^2/2 - 2\pi y/h}\f$: h = 2πy/(60 + σ²y²/2) makes it e^{-60} at
/// \f$y = \min(d, \sqrt{120}/\sigma)\f$, where the step is largest. The sum stops once
/// five terms in a row are below 1e-17 of it, about 9/σ from 0 by the Gaussian
/// decay: 20 to 200 terms whatever x and the weights. Against the same sum at a
/// third of the step, 1400 random cases (1 to 400 weights, tails from 1/2 to
/// 1e-185) agree to 2.4e-14.
inline double weighted_chi_square_contour(std::span<const double> weights, double x, bool upper) {
  double largest = 0;
  for (const double w : weights) largest = std::max(largest, w);
  const double cut = 1 / (2 * largest);  // s*
  const auto slope = [&](double s) {     // K'(s) - x - 1/s, increasing on (-inf, 0) and on (0, s*)
    double sum = 0;
    for (const double w : weights) sum += w / (1 - 2 * w * s);
    return sum - x - 1 / s;
  };
  double low = 0, high = cut;
  if (!upper) {
    // The root lies where K'(s) - 1/s has fallen to x: at s ≈ -(m/2 + 1)/x for
    // s → -∞, where K'(s) ≈ m/(2|s|); the bracket doubles from there.
    high = 0;
    low = -(static_cast<double>(weights.size()) / 2 + 1) / x;
    while (slope(low) > 0) low *= 2;
  }
  for (;;) {
    const double mid = 0.5 * (low + high);
    if (mid <= low || mid >= high) break;
    (slope(mid) > 0 ? high : low) = mid;
  }
  const double c = 0.5 * (low + high);
  double k = 0, curvature = 1 / (c * c);  // K(c), then σ²
  for (const double w : weights) {
    const double r = 1 - 2 * w * c;
    k -= 0.5 * std::log(r);
    curvature += 2 * w * w / (r * r);
  }
  const double beta = curvature / (2 * x);
  // The least |Im t| of the roots of βt² + it + (c - s₀) = 0, t = (-i ± √(-1 - 4β(c - s₀)))/(2β).
  const auto distance = [&](double s0) {
    const double discriminant = 1 + 4 * beta * (c - s0);
    return discriminant >= 0 ? std::abs(1 - std::sqrt(discriminant)) / (2 * beta) : 1 / (2 * beta);
  };
  const double y = std::min({distance(0), distance(cut), std::sqrt(120.0 / curvature)});
  const double h = 2 * std::numbers::pi * y / (60 + curvature * y * y / 2);
  // F(s(t))(1 - 2iβt) relative to the real e^{K(c) - cx}, which factors out.
  const double origin = k - c * x;
  double sum = 0.5 / c;
  for (int n = 1, small = 0; small < 5; ++n) {
    const double t = n * h;
    const std::complex<double> s(c + beta * t * t, t);
    std::complex<double> log_f = -s * x - origin;
    for (const double w : weights) log_f -= 0.5 * std::log(1.0 - 2 * w * s);
    const std::complex<double> term = std::exp(log_f) / s * std::complex<double>(1, -2 * beta * t);
    sum += term.real();
    small = std::abs(term) < 1e-17 * std::abs(sum) ? small + 1 : 0;
  }
  return h / std::numbers::pi * std::exp(origin) * sum;
}

}  // namespace detail

/// \f$\Pr[\sum_i\lambda_i\chi^2_{1,i} > x]\f$ for independent \f$\chi^2_1\f$ terms with
/// weights \f$\lambda_i \ge 0\f$ (at least one positive): the tail of a sum of
/// squares of correlated Gaussian variables, the \f$\lambda_i\f$ the eigenvalues of
/// their covariance (file comment, "Weighted sums"). Relative error about 1e-13
/// (the tests: within 1e-12 of \f$\chi^2\f$ tails for equal weights and of the closed
/// form for weights in pairs, down to 1e-100), at a cost of 20 to 200 complex
/// logarithms per weight.
[[nodiscard]] inline double weighted_chi_square_upper_tail(std::span<const double> weights, double x) {
  constexpr std::string_view who = "weighted_chi_square_upper_tail";
  detail::require_chi_square_weights(weights, who, "weights");
  require(!std::isnan(x), who, "x", "must not be NaN");
  if (x <= 0) return 1.0;
  if (std::isinf(x)) return 0.0;
  double mean = 0;
  for (const double w : weights) mean += w;
  // Each side of the mean its own tail, computed with relative accuracy.
  return x >= mean ? detail::weighted_chi_square_contour(weights, x, true)
                   : 1 + detail::weighted_chi_square_contour(weights, x, false);
}

/// The x with \f$\Pr[\sum_i\lambda_i\chi^2_{1,i} > x] = p\f$, for \f$0 < p < 1\f$ (the
/// threshold of a sum of correlated squares with false-alarm probability p), by
/// bisection to a relative 1e-13 of x (about 50 evaluations of the tail).
[[nodiscard]] inline double weighted_chi_square_upper_quantile(std::span<const double> weights, double p) {
  constexpr std::string_view who = "weighted_chi_square_upper_quantile";
  detail::require_chi_square_weights(weights, who, "weights");
  require(p > 0 && p < 1, who, "p", "must lie in (0, 1)");
  double mean = 0;
  for (const double w : weights) mean += w;
  const double x =
      detail::boundary_by_bisection([&](double x) { return weighted_chi_square_upper_tail(weights, x) > p; }, mean);
  require(x >= std::numeric_limits<double>::min(), who, "p",
          "is so close to 1 that the quantile at these weights is below the smallest normal double");
  return x;
}

}  // namespace adaptobs
