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

#include <adaptobs/core/detail/bisection.hpp>
#include <adaptobs/core/validation.hpp>

#include <cmath>
#include <limits>

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

}  // namespace adaptobs
