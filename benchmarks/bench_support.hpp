#pragma once
// Shared pieces of the benchmarks: a ring of pre-generated samples, so that a
// timed iteration is one observer update and nothing else.

#include <adaptobs/core/dimensions.hpp>
#include <adaptobs/core/status.hpp>

#include <benchmark/benchmark.h>

#include <cstddef>
#include <vector>

namespace adaptobs::bench {

/// Pre-generated samples replayed in a loop.
template <class Sample>
class SampleRing {
 public:
  explicit SampleRing(std::vector<Sample> samples) : samples_(std::move(samples)) {}
  const Sample& next() {
    const Sample& s = samples_[i_];
    i_ = (i_ + 1 == samples_.size()) ? 0 : i_ + 1;
    return s;
  }

 private:
  std::vector<Sample> samples_;
  std::size_t i_ = 0;
};

/// Whether a copy of `observer` accepts every sample over `passes` passes of
/// `samples` (as the ring replays them); if not, the benchmark is skipped with an
/// error: timing rejected samples would time the checks alone.
template <class Observer, class Sample>
[[nodiscard]] bool accepts_every_sample(benchmark::State& state, Observer observer, const std::vector<Sample>& samples,
                                        int passes) {
  for (int pass = 0; pass < passes; ++pass)
    for (const Sample& s : samples)
      if (observer.update(s) != UpdateStatus::accepted) {
        state.SkipWithError("the observer rejects samples of the ring");
        return false;
      }
  return true;
}

/// Times `observer.update(ring.next())`, one update per iteration.
template <class Observer, class Sample>
void time_updates(benchmark::State& state, Observer& observer, SampleRing<Sample>& ring) {
  for (auto _ : state) {
    auto status = observer.update(ring.next());
    benchmark::DoNotOptimize(status);
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations());
}

/// Times `observer.update(ring.next(), present)`: with some channels absent the
/// partial update, with none the time update. Registered as `Arg(0)` (no
/// channel, `BM_*_TimeUpdate`) beside the observer's full update in the same run.
template <class Observer, class Sample, class Mask>
void time_masked_updates(benchmark::State& state, Observer& observer, SampleRing<Sample>& ring, const Mask& present) {
  for (auto _ : state) {
    auto status = observer.update(ring.next(), present);
    benchmark::DoNotOptimize(status);
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations());
}

}  // namespace adaptobs::bench
