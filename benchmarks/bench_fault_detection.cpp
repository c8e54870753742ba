// Fault detection at the satellite's sizes (Guyader & Zhang 2003, §4): the CUSUM and the
// GLR on θ̂ and the χ² test on the output errors, each alone and with the Guyader–Zhang
// update they watch (BM_GuyaderZhang_Satellite, same binary, is the update
// alone); and the Monte-Carlo evaluator's throughput on 1 and 2 threads.

#include <adaptobs/diagnostics/fault_monitor.hpp>
#include <adaptobs/simulation/detection_evaluation.hpp>

#include "discrete_problems.hpp"
#include "models/satellite_fault.hpp"

#include <vector>

namespace {

using adaptobs::Index;
namespace satellite = adaptobs::examples::satellite;

// A design from 5 fault-free runs of 1100 s, for false alarms every 10⁴ s:
// enough for the benchmarks, which time the tests, not their calibration (the
// smoke run executes it unoptimized).
const satellite::MonitorDesign& design() {
  static const satellite::MonitorDesign d = satellite::design_monitor(1e4, 1.0, 5, 1100);
  return d;
}

// θ̂ and output errors of the observer over the benchmark ring's samples.
struct Recording {
  std::vector<Eigen::Vector2d> parameters;
  std::vector<Eigen::Vector2d> output_errors;
};

const Recording& recording() {
  static const Recording r = [] {
    Recording rec;
    auto observer = satellite::make_observer();
    auto ring = adaptobs::bench::satellite_ring();
    for (int k = 0; k < 1000; ++k) {
      (void)observer.update(ring.next());
      rec.parameters.push_back(observer.parameters());
      rec.output_errors.push_back(observer.output_error());
    }
    return rec;
  }();
  return r;
}

// Times `detector.update(values[i])` over the recorded values, one per iteration.
template <class Detector, class Values>
void time_replay(benchmark::State& state, Detector& detector, const Values& values) {
  std::size_t i = 0;
  for (auto _ : state) {
    auto status = detector.update(values[i]);
    benchmark::DoNotOptimize(status);
    i = i + 1 == values.size() ? 0 : i + 1;
  }
  state.SetItemsProcessed(state.iterations());
}

// The CUSUM alone; range(0) is the stride (1: every value reaches the sums).
void BM_Cusum_Satellite(benchmark::State& state) {
  const auto& d = design();
  adaptobs::CusumDetector<double, 2> cusum(d.nominal, d.cusum.scale, d.cusum.drift, d.cusum.threshold,
                                           {.stride = state.range(0)});
  time_replay(state, cusum, recording().parameters);
}
BENCHMARK(BM_Cusum_Satellite)->Arg(1)->Arg(100);

void BM_ChiSquare_Satellite(benchmark::State& state) {
  const auto& d = design();
  adaptobs::ChiSquareTest<double, 2> test(d.output_error_covariance, d.window, d.false_alarm_probability,
                                          d.chi_square_options);
  time_replay(state, test, recording().output_errors);
}
BENCHMARK(BM_ChiSquare_Satellite);

void BM_Glr_Satellite(benchmark::State& state) {
  const auto& d = design();
  adaptobs::GlrDetector<double, 2> glr(d.nominal, d.cusum.scale, d.glr_window, d.glr_threshold,
                                       {.stride = state.range(0)});
  time_replay(state, glr, recording().parameters);
}
BENCHMARK(BM_Glr_Satellite)->Arg(1)->Arg(100);

// One Guyader–Zhang update followed by the monitor's three tests on its
// estimates; range(0) is the stride of the CUSUM and the GLR (100 as designed,
// 1 to evaluate them at every sample).
void BM_GuyaderZhang_Satellite_Monitored(benchmark::State& state) {
  auto observer = satellite::make_observer();
  auto strided = design();
  strided.cusum_options.stride = state.range(0);
  adaptobs::FaultMonitor monitor(strided);
  auto ring = adaptobs::bench::satellite_ring();
  for (auto _ : state) {
    auto status = observer.update(ring.next());
    auto watched = monitor.observe(observer);
    benchmark::DoNotOptimize(status);
    benchmark::DoNotOptimize(watched);
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_GuyaderZhang_Satellite_Monitored)->Arg(100)->Arg(1);

// Seeds per second of the evaluator on the default fault (each seed: the faulty
// run and its twin, 250 s of satellite), range(0) threads.
void BM_DetectionEvaluation_Satellite(benchmark::State& state) {
  const auto& d = design();
  const satellite::ThrusterFault fault;
  auto scenario = [&](std::uint64_t seed, bool faulty) {
    return satellite::monitored_run(d, adaptobs::examples::Detector::cusum, fault, seed, faulty, 250);
  };
  constexpr Index seeds = 8;
  for (auto _ : state) {
    auto summary = adaptobs::evaluate_detection(scenario, {.time = fault.time, .parameter = fault.parameter}, 1000,
                                                seeds, static_cast<unsigned>(state.range(0)));
    benchmark::DoNotOptimize(summary.detection_rate);
  }
  state.counters["seeds_per_second"] =
      benchmark::Counter(static_cast<double>(seeds * state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_DetectionEvaluation_Satellite)->Arg(1)->Arg(2)->UseRealTime()->Unit(benchmark::kMillisecond);

}  // namespace
