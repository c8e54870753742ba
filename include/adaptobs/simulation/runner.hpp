#pragma once
/// \file
/// Runs observers on a simulated plant and records every series in a `SeriesTable`.
///
/// Written once against the `Plant` and `Observer` concepts. Row k holds
/// \f$t_k, u_k, y_k, x_k, \hat x_k, \theta_k, \hat\theta_k\f$ — the estimates
/// *before* the sample of step k is consumed, so that \f$\hat x_k\f$ is compared
/// with \f$x_k\f$ — in the column order of the examples' CSV schema
/// (`t,u_*,y_*,x_*,xhat_*,theta_*,thetahat_*`, with `y_available` after `y_*`
/// when outputs can be lost: the present channels as bits); further observers
/// add `xhat_<suffix>_*` and `thetahat_<suffix>_*` columns.

#include <adaptobs/core/dimensions.hpp>
#include <adaptobs/core/observer.hpp>
#include <adaptobs/core/status.hpp>
#include <adaptobs/core/validation.hpp>
#include <adaptobs/simulation/output_loss.hpp>
#include <adaptobs/simulation/plant.hpp>
#include <adaptobs/simulation/series_table.hpp>

#include <array>
#include <concepts>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>

namespace adaptobs {

/// An observer taking part in a simulation, and the suffix of its CSV columns
/// (empty for the primary observer).
template <Observer O>
struct Tracked {
  O& observer;
  std::string_view suffix;
};

/// Names `observer` for a simulation: `track(akf, "akf")` writes `xhat_akf_*`, `thetahat_akf_*`.
template <Observer O>
[[nodiscard]] Tracked<O> track(O& observer, std::string_view suffix = {}) {
  return {observer, suffix};
}

/// Rejected samples per tracked observer, in the order given.
template <std::size_t N>
struct SimulationReport {
  std::array<Index, N> rejected{};
  Index steps = 0;
};

namespace detail {
inline std::string column_name(std::string_view base, std::string_view suffix) {
  std::string name(base);
  if (!suffix.empty()) name.append("_").append(suffix);
  return name;
}
struct NoExtraColumns {
  template <class P>
  void operator()(SeriesTable&, const P&) const {}
};
}  // namespace detail

/// The estimate columns of a row as `simulate` writes them, for a simulation
/// loop of one's own (a continuous-time plant, a hook between samples): `xhat`,
/// the true `theta`, `thetahat`, then the `xhat_<suffix>` and `thetahat_<suffix>`
/// of every further tracked observer.
template <class Parameters, Observer First, Observer... Rest>
void add_estimates(SeriesTable& table, const Parameters& theta, const Tracked<First>& first,
                   const Tracked<Rest>&... rest) {
  table.add(detail::column_name("xhat", first.suffix), first.observer.state());
  table.add("theta", theta);
  table.add(detail::column_name("thetahat", first.suffix), first.observer.parameters());
  (table.add(detail::column_name("xhat", rest.suffix), rest.observer.state())
       .add(detail::column_name("thetahat", rest.suffix), rest.observer.parameters()),
   ...);
}

namespace detail {
/// The loop of `simulate`; `loss` is null when every output arrives (and then
/// no `y_available` column is written).
template <Plant P, class Extras, Observer First, Observer... Rest>
SimulationReport<1 + sizeof...(Rest)> simulate(P& plant, Index steps, SeriesTable& table, OutputLoss* loss,
                                               Extras& extra_columns, Tracked<First> first, Tracked<Rest>... rest) {
  using Dims = typename First::Dims;
  require(steps >= 0, "simulate", "steps", "must be non-negative");
  // The lost channel is checked before the first row, not at the first loss.
  if (loss && loss->options().channel >= 0)
    require(loss->options().channel < plant.sample().y.size(), "simulate", "loss",
            "loses a channel beyond the plant's outputs");
  SimulationReport<1 + sizeof...(Rest)> report;
  for (Index k = 0; k < steps; ++k) {
    const auto& sample = plant.sample();
    OutputMask<Dims> present = OutputMask<Dims>::Constant(sample.y.size(), true);
    if (loss) present = loss->channels_at<Dims>(plant.time(), sample.y.size());
    const bool complete = present.all();
    table.begin_row().add("t", plant.time()).add("u", sample.u).add("y", sample.y);
    if (loss) table.add("y_available", channel_bits(present));
    table.add("x", plant.state());
    add_estimates(table, plant.parameters(), first, rest...);
    extra_columns(table, std::as_const(plant));

    std::size_t i = 0;
    const auto feed = [&](auto& tracked) {
      using O = std::remove_reference_t<decltype(tracked.observer)>;
      UpdateStatus status = UpdateStatus::nonfinite_input;
      if (complete)
        status = tracked.observer.update(sample);
      else if constexpr (PartialOutputObserver<O>)
        status = tracked.observer.update(sample, OutputMask<typename O::Dims>(present));
      if (!accepted(status)) ++report.rejected[i];
      ++i;
    };
    feed(first);
    (feed(rest), ...);
    plant.advance();
    ++report.steps;
  }
  return report;
}
}  // namespace detail

/// Runs `steps` samples; `extra_columns(table, plant)` may append columns to each row
/// (after the observers' columns).
template <Plant P, class Extras, Observer First, Observer... Rest>
  requires std::invocable<Extras&, SeriesTable&, const P&>
SimulationReport<1 + sizeof...(Rest)> simulate(P& plant, Index steps, SeriesTable& table, Extras&& extra_columns,
                                               Tracked<First> first, Tracked<Rest>... rest) {
  return detail::simulate(plant, steps, table, nullptr, extra_columns, first, rest...);
}

/// As above, with the output channels that `loss` lets through: a sample with
/// every channel is `update(sample)`, one with some or none
/// `update(sample, present)` — a `PartialOutputObserver`'s partial or time update;
/// an observer without one counts the sample as rejected. The table gains the
/// column `y_available`, the channels that arrived as an integer (`channel_bits`).
template <Plant P, class Extras, Observer First, Observer... Rest>
  requires std::invocable<Extras&, SeriesTable&, const P&>
SimulationReport<1 + sizeof...(Rest)> simulate(P& plant, Index steps, SeriesTable& table, OutputLoss& loss,
                                               Extras&& extra_columns, Tracked<First> first, Tracked<Rest>... rest) {
  return detail::simulate(plant, steps, table, &loss, extra_columns, first, rest...);
}

/// As above, with no extra columns.
template <Plant P, Observer First, Observer... Rest>
SimulationReport<1 + sizeof...(Rest)> simulate(P& plant, Index steps, SeriesTable& table, Tracked<First> first,
                                               Tracked<Rest>... rest) {
  return simulate(plant, steps, table, detail::NoExtraColumns{}, first, rest...);
}

}  // namespace adaptobs
