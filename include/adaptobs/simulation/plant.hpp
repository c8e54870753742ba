#pragma once
/// \file
/// What a simulated plant is (the `Plant` concept), and the recording of its
/// samples that tests and benchmarks replay into observers.

#include <adaptobs/core/dimensions.hpp>
#include <adaptobs/core/validation.hpp>

#include <concepts>
#include <cstddef>
#include <vector>

namespace adaptobs {

/// A simulated system: current truth, current measured sample, and a way forward.
template <class P>
concept Plant = requires(P& p, const P& cp) {
  typename P::Sample;
  { cp.sample() } -> std::convertible_to<const typename P::Sample&>;
  cp.sample().u;
  cp.sample().y;
  cp.state();
  cp.parameters();
  { cp.time() } -> std::convertible_to<double>;
  p.advance();
};

/// The samples of the first n steps of `plant` (which it advances n times), in
/// order: a sample stream recorded once and replayed into observers.
template <Plant P>
[[nodiscard]] std::vector<typename P::Sample> record_samples(P plant, Index n) {
  require(n >= 0, "record_samples", "n", "must be non-negative");
  std::vector<typename P::Sample> samples;
  samples.reserve(static_cast<std::size_t>(n));
  for (Index k = 0; k < n; ++k) {
    samples.push_back(plant.sample());
    plant.advance();
  }
  return samples;
}

}  // namespace adaptobs
