#pragma once
/// \file
/// The χ² distribution's upper tail and quantile, for setting detector
/// thresholds from a false-alarm probability.
///
/// \f$\Pr[\chi^2_\nu > x] = Q(\nu/2, x/2)\f$, the regularized upper incomplete
/// gamma function. \f$Q\f$ is evaluated by its power series for \f$P = 1 - Q\f$
/// when \f$x < a + 1\f$ and by its continued fraction (modified Lentz) otherwise,
/// each the rapidly converging form on its side (Abramowitz & Stegun 6.5.29 and
/// 6.5.31). The quantile inverts the tail by bisection on a bracket, which is
/// slow next to Newton's method but cannot fail, and runs once, at design time.

#include <adaptobs/core/validation.hpp>

#include <cmath>
#include <limits>

namespace adaptobs {

namespace detail {

/// \f$P(a, x)\f$ by its series \f$e^{-x}x^a\sum_n x^n/\Gamma(a+n+1)\f$, for \f$x < a + 1\f$.
inline double lower_gamma_series(double a, double x) {
  double term = 1.0 / a;
  double sum = term;
  for (int n = 1; n < 1000; ++n) {
    term *= x / (a + n);
    sum += term;
    if (std::abs(term) < std::abs(sum) * 1e-17) break;
  }
  return sum * std::exp(-x + a * std::log(x) - std::lgamma(a));
}

/// \f$Q(a, x)\f$ by its continued fraction, for \f$x \ge a + 1\f$.
inline double upper_gamma_fraction(double a, double x) {
  constexpr double tiny = 1e-300;
  double b = x + 1.0 - a;
  double c = 1.0 / tiny;
  double d = 1.0 / b;
  double h = d;
  for (int i = 1; i < 1000; ++i) {
    const double an = -i * (i - a);
    b += 2.0;
    d = an * d + b;
    if (std::abs(d) < tiny) d = tiny;
    c = b + an / c;
    if (std::abs(c) < tiny) c = tiny;
    d = 1.0 / d;
    const double delta = d * c;
    h *= delta;
    if (std::abs(delta - 1.0) < 1e-16) break;
  }
  return std::exp(-x + a * std::log(x) - std::lgamma(a)) * h;
}

}  // namespace detail

/// \f$\Pr[\chi^2_\nu > x]\f$ for \f$\nu > 0\f$ degrees of freedom.
[[nodiscard]] inline double chi_square_upper_tail(double degrees_of_freedom, double x) {
  detail::require_positive(degrees_of_freedom, "chi_square_upper_tail", "degrees_of_freedom");
  detail::require(!std::isnan(x), "chi_square_upper_tail", "x", "must not be NaN");
  if (x <= 0) return 1.0;
  if (std::isinf(x)) return 0.0;
  const double a = degrees_of_freedom / 2, half = x / 2;
  return half < a + 1 ? 1.0 - detail::lower_gamma_series(a, half) : detail::upper_gamma_fraction(a, half);
}

/// The x with \f$\Pr[\chi^2_\nu > x] = p\f$, for \f$0 < p < 1\f$ (the threshold
/// a χ² test with false-alarm probability p compares its statistic to).
/// Accurate to a relative 1e-12, down to p = 1e-300.
[[nodiscard]] inline double chi_square_upper_quantile(double degrees_of_freedom, double p) {
  constexpr std::string_view who = "chi_square_upper_quantile";
  detail::require_positive(degrees_of_freedom, who, "degrees_of_freedom");
  detail::require(p > 0 && p < 1, who, "p", "must lie in (0, 1)");
  // The tail falls from 1 to 0 as x grows: bracket the root, then halve.
  double low = 0, high = degrees_of_freedom + 10;
  while (chi_square_upper_tail(degrees_of_freedom, high) > p) {
    low = high;
    high *= 2;
  }
  while (high - low > 1e-13 * high) {
    const double mid = 0.5 * (low + high);
    (chi_square_upper_tail(degrees_of_freedom, mid) > p ? low : high) = mid;
  }
  return 0.5 * (low + high);
}

}  // namespace adaptobs
