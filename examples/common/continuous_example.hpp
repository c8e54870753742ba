#pragma once
// Run loop shared by the continuous-time examples: feeds a simulated plant's
// samples to several observers and records one CSV row every `every` samples,
// after the update (the estimates at the sample's time), in the DESIGN.md
// column order: t, u_*, y_*, x_*, xhat_*, theta_*, thetahat_*, then the other
// observers' xhat_<suffix>_*, thetahat_<suffix>_*.

#include <adaptobs/core/status.hpp>
#include <adaptobs/simulation/runner.hpp>
#include <adaptobs/simulation/series_table.hpp>

#include <cmath>
#include <stdexcept>
#include <string>

namespace adaptobs::examples {

/// As `run_continuous`, calling `after_step(t_{k-1}, t_k)` once the observers have taken sample k.
template <class Plant, class Hook, class First, class... Rest>
void run_continuous_with(Plant& plant, double seconds, double period, int every, SeriesTable& table, Hook&& after_step,
                         Tracked<First> first, Tracked<Rest>... rest) {
  const auto feed = [&](auto& tracked) {
    const UpdateStatus status = tracked.observer.update(plant.sample());
    if (status != UpdateStatus::accepted)
      throw std::runtime_error("observer '" + std::string(tracked.suffix) + "' rejected a sample: " +
                               std::string(to_string(status)));
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
    table.add(detail::column_name("xhat", first.suffix), first.observer.state());
    table.add("theta", plant.parameters());
    table.add(detail::column_name("thetahat", first.suffix), first.observer.parameters());
    (table.add(detail::column_name("xhat", rest.suffix), rest.observer.state())
         .add(detail::column_name("thetahat", rest.suffix), rest.observer.parameters()),
     ...);
  }
}

template <class Plant, class First, class... Rest>
void run_continuous(Plant& plant, double seconds, double period, int every, SeriesTable& table, Tracked<First> first,
                    Tracked<Rest>... rest) {
  run_continuous_with(plant, seconds, period, every, table, [](double, double) {}, first, rest...);
}

}  // namespace adaptobs::examples
