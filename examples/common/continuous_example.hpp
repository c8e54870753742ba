#pragma once
// What the continuous-time examples share: the run loop, which feeds a
// simulated plant's samples to several observers and records one CSV row every
// `every` samples, after the update (the estimates at the sample's time), in the
// column order of every example's CSV: t, u_*, y_*, x_*, xhat_*, theta_*, thetahat_*, then
// the other observers' xhat_<suffix>_*, thetahat_<suffix>_*; the printout of
// the final errors and of an SPR condition; and the common two-panel figure.

#include <adaptobs/core/status.hpp>
#include <adaptobs/simulation/runner.hpp>
#include <adaptobs/simulation/series_table.hpp>

#include "common/example_support.hpp"
#include "models/unified_designs.hpp"

#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace adaptobs::examples {

/// As `run_continuous`, calling `after_step(t_{k-1}, t_k)` once the observers have taken sample k.
template <class Plant, class Hook, class First, class... Rest>
void run_continuous_with(Plant& plant, double seconds, double period, int every, SeriesTable& table, Hook&& after_step,
                         Tracked<First> first, Tracked<Rest>... rest) {
  const auto feed = [&](auto& tracked) {
    const UpdateStatus status = tracked.observer.update(plant.sample());
    if (status != UpdateStatus::accepted)
      throw std::runtime_error("observer '" + std::string(tracked.suffix) +
                               "' rejected a sample: " + std::string(to_string(status)));
  };
  const long steps = std::lround(seconds / period);
  for (long k = 0; k <= steps; ++k) {
    const double t0 = plant.time();
    if (k > 0) plant.advance();
    feed(first);
    (feed(rest), ...);
    if (k > 0) after_step(t0, plant.time());
    if (k % every != 0) continue;
    const auto& s = plant.sample();
    table.begin_row().add("t", plant.time()).add("u", s.u).add("y", s.y).add("x", plant.state());
    add_estimates(table, plant.parameters(), first, rest...);
  }
}

template <class Plant, class First, class... Rest>
void run_continuous(Plant& plant, double seconds, double period, int every, SeriesTable& table, Tracked<First> first,
                    Tracked<Rest>... rest) {
  run_continuous_with(plant, seconds, period, every, table, [](double, double) {}, first, rest...);
}

/// The flags of the continuous-time examples: the run's length (default
/// `seconds`), the output noise and its seed.
inline std::vector<Option> continuous_options(std::string seconds) {
  return {{"seconds", std::move(seconds), "length of the run", "s", real_in(1, 1e5)},
          noise_option("0"),
          seed_option("1", "seed of the output noise")};
}

/// Prints θ, θ̂ and the final relative errors of θ̂ and of the state estimate.
template <class Plant, class Observer>
void print_final_errors(const Plant& plant, const Observer& observer) {
  print_value("theta", plant.parameters());
  print_value("thetahat", observer.parameters());
  print_value("theta_relative_error", (observer.parameters() - plant.parameters()).norm() / plant.parameters().norm());
  print_value("state_relative_error", (observer.state() - plant.state()).norm() / plant.state().norm());
}

/// Prints the coordinates of a SISO observer of Algorithm 1 or 2 at t = 0: the
/// static transform (T, K) and the transformed pair \f$(A_o, c_o)\f$.
template <class Observer>
void print_coordinates(const Observer& observer) {
  const auto so = observer.transformed_system(0.0);
  print_value("T", observer.algorithm().static_transform.T());
  print_value("K", observer.algorithm().static_transform.K());
  print_value("A_o", so.Ao);
  print_value("c_o", so.Co);
}

/// Prints the SPR condition of Algorithms 1 and 2: G(s), the exact test and its KYP certificate.
inline void print_spr_report(const designs::SprReport& spr) {
  print_value("G_numerator", spr.transfer_function.numerator.transpose());
  print_value("G_denominator", spr.transfer_function.denominator.transpose());
  print_value("spr_exact", double(spr.exact.strictly_positive_real));
  print_value("spr_sweep_min_weighted_re", spr.sweep.min_weighted_real_part);
  if (!spr.kyp) return;
  print_value("kyp_P", spr.kyp->P);
  print_value("kyp_residual_Pb_minus_c", spr.kyp->equality_residual);
  print_value("kyp_max_eig_AtP_PA", spr.kyp->max_eigenvalue_lyapunov);
}

/// gnuplot expression of \f$|a - b|\f$ over the CSV columns a_1..a_size and b_1..b_size.
inline std::string error_norm_expression(std::string_view a, std::string_view b, int size) {
  std::string sum;
  for (int i = 1; i <= size; ++i) {
    const std::string index = std::to_string(i);
    if (i > 1) sum += " + ";
    sum += "(column('" + std::string(a) + "_" + index + "')-column('" + std::string(b) + "_" + index + "'))**2";
  }
  return "sqrt(" + sum + ")";
}

/// The figure of a one-observer example: θ̂ against the true θ, then the norms
/// of the parameter and state errors on a log scale, below 1e-12 drawn at
/// 1e-12. The plants of these examples are the library's own and have no units.
inline std::string estimates_and_errors_figure(std::string_view title, std::string_view truth, int parameters,
                                               int states) {
  std::string script =
      std::string(log_floor_function) + "set multiplot layout 2,1 title '" + std::string(title) +
      " (no units)'\nset grid\nset lmargin 12\nset xlabel 't (s)'\nset title 'parameter estimates (true " +
      std::string(truth) + ")'\nset ylabel 'theta (no unit)'\nplot ";
  for (int i = 1; i <= parameters; ++i)
    script += "csv using 't':'thetahat_" + std::to_string(i) + "' with lines lw 1.5 title 'theta^" + std::to_string(i) +
              " estimate', \\\n     ";
  for (int i = 1; i <= parameters; ++i)
    script += "csv using 't':'theta_" + std::to_string(i) + "' with lines lc 'black' dt 3 " +
              (i == 1 ? "title 'true'" : "notitle") + (i < parameters ? ", \\\n     " : "\n");
  script +=
      "set title 'estimation errors (log scale: below 10^{-12} drawn at 10^{-12})'\n"
      "set ylabel 'error norm (no unit)'\nset logscale y\nset format y '10^{%T}'\nplot csv using 't':(floored(" +
      error_norm_expression("thetahat", "theta", parameters) +
      ", 1e-12)) with lines lw 1.5 title '|theta estimate - theta|', \\\n" + "     csv using 't':(floored(" +
      error_norm_expression("xhat", "x", states) +
      ", 1e-12)) with lines lw 1.5 title '|state estimate - x|'\nunset multiplot\n";
  return script;
}

/// The rest of a SISO example of Algorithm 1 or 2: the third-order plant with
/// the command line's noise and seed, run for its seconds (h = 0.01 s, every
/// tenth sample recorded), the final errors and the two-panel figure.
template <class Observer>
void run_siso_example(Observer& observer, const Arguments& args, const std::string& name, std::string_view title) {
  auto plant = siso::make_plant<double>(
      {.output_noise = args.number("noise"), .seed = static_cast<std::uint64_t>(args.number("seed"))});
  SeriesTable table;
  run_continuous(plant, args.number("seconds"), 0.01, 10, table, track(observer));
  print_final_errors(plant, observer);
  write_outputs(table, args.out_dir(), name, estimates_and_errors_figure(title, "2 and -1", 2, 3));
}

}  // namespace adaptobs::examples
