// Guyader–Zhang observer: one update at the satellite's sizes, and a sweep
// n ∈ {2, …, 64} with p = m = n/2 (the augmented Kalman filter on the same
// problems is in bench_augmented_kalman.cpp, same binary).

#include <adaptobs/observers/guyader_zhang.hpp>

#include "discrete_problems.hpp"

namespace {

using adaptobs::Index;
namespace satellite = adaptobs::examples::satellite;

void BM_GuyaderZhang_Satellite(benchmark::State& state) {
  adaptobs::GuyaderZhangObserver observer(satellite::model<double>(), satellite::paper_gain<double>(), satellite::mu,
                                          satellite::initial_state_estimate<double>(),
                                          satellite::initial_parameter_estimate<double>());
  auto ring = adaptobs::bench::satellite_ring();
  adaptobs::bench::time_updates(state, observer, ring);
}
BENCHMARK(BM_GuyaderZhang_Satellite);

void BM_GuyaderZhang_Satellite_ExcitationMonitor(benchmark::State& state) {
  adaptobs::GuyaderZhangObserver observer(satellite::model<double>(), satellite::paper_gain<double>(), satellite::mu,
                                          satellite::initial_state_estimate<double>(),
                                          satellite::initial_parameter_estimate<double>(), {.excitation_window = 100});
  auto ring = adaptobs::bench::satellite_ring();
  adaptobs::bench::time_updates(state, observer, ring);
}
BENCHMARK(BM_GuyaderZhang_Satellite_ExcitationMonitor);

// Masked updates: the second output absent (Υ through A Υ − K(C̄Υ) instead of
// the cached A − KC), and no output at all (the time update).
template <bool FirstPresent>
void BM_GuyaderZhang_Satellite_Masked(benchmark::State& state) {
  adaptobs::GuyaderZhangObserver observer(satellite::model<double>(), satellite::paper_gain<double>(), satellite::mu,
                                          satellite::initial_state_estimate<double>(),
                                          satellite::initial_parameter_estimate<double>());
  auto ring = adaptobs::bench::satellite_ring();
  adaptobs::bench::time_masked_updates(state, observer, ring,
                                       adaptobs::OutputMask<satellite::Dims<double>>(FirstPresent, false));
}
BENCHMARK(BM_GuyaderZhang_Satellite_Masked<true>)->Name("BM_GuyaderZhang_Satellite_PartialOutput");
BENCHMARK(BM_GuyaderZhang_Satellite_Masked<false>)->Name("BM_GuyaderZhang_Satellite_TimeUpdate");

template <int N>
void BM_GuyaderZhang_Sweep(benchmark::State& state) {
  using Dims = adaptobs::bench::SweepDims<N>;
  const Index n = N == Eigen::Dynamic ? state.range(0) : N;
  auto problem = adaptobs::bench::make_sweep_problem<Dims>(n);
  adaptobs::GuyaderZhangObserver observer(problem.model, problem.gain, 0.01, typename Dims::State(Dims::State::Zero(n)),
                                          typename Dims::Parameters(Dims::Parameters::Zero(n / 2)));
  adaptobs::bench::time_updates(state, observer, problem.ring);
  state.counters["n"] = double(n);
}

// Fixed sizes up to 16; Eigen::Dynamic from 16 on (16 in both, to show the cost of dynamic sizes).
BENCHMARK(BM_GuyaderZhang_Sweep<2>)->Name("BM_GuyaderZhang_Sweep/fixed/2");
BENCHMARK(BM_GuyaderZhang_Sweep<4>)->Name("BM_GuyaderZhang_Sweep/fixed/4");
BENCHMARK(BM_GuyaderZhang_Sweep<8>)->Name("BM_GuyaderZhang_Sweep/fixed/8");
BENCHMARK(BM_GuyaderZhang_Sweep<16>)->Name("BM_GuyaderZhang_Sweep/fixed/16");
BENCHMARK(BM_GuyaderZhang_Sweep<Eigen::Dynamic>)->Name("BM_GuyaderZhang_Sweep/dynamic")->Arg(16)->Arg(32)->Arg(64);

}  // namespace
