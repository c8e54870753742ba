// Guyader–Zhang observer against the augmented-state Kalman filter: one update
// at the satellite's sizes, and a sweep n ∈ {2, …, 64} with p = m = n/2.

#include <adaptobs/baselines/augmented_kalman.hpp>
#include <adaptobs/design/dare.hpp>
#include <adaptobs/observers/guyader_zhang.hpp>

#include "bench_support.hpp"
#include "models/satellite.hpp"

#include <random>

namespace {

using adaptobs::Index;
using adaptobs::bench::SampleRing;
namespace satellite = adaptobs::examples::satellite;

SampleRing<adaptobs::DiscreteSample<satellite::Dims<double>>> satellite_ring() {
  auto plant = satellite::make_plant<double>();
  std::vector<adaptobs::DiscreteSample<satellite::Dims<double>>> samples;
  for (Index k = 0; k < 1000; ++k) {
    samples.push_back(plant.sample());
    plant.advance();
  }
  return SampleRing(std::move(samples));
}

void BM_GuyaderZhang_Satellite(benchmark::State& state) {
  adaptobs::GuyaderZhangObserver observer(satellite::model<double>(), satellite::paper_gain<double>(), satellite::mu,
                                          satellite::initial_state_estimate<double>(),
                                          satellite::initial_parameter_estimate<double>());
  auto ring = satellite_ring();
  adaptobs::bench::time_updates(state, observer, ring);
}
BENCHMARK(BM_GuyaderZhang_Satellite);

void BM_GuyaderZhang_Satellite_ExcitationMonitor(benchmark::State& state) {
  adaptobs::GuyaderZhangObserver observer(satellite::model<double>(), satellite::paper_gain<double>(), satellite::mu,
                                          satellite::initial_state_estimate<double>(),
                                          satellite::initial_parameter_estimate<double>(), {.excitation_window = 100});
  auto ring = satellite_ring();
  adaptobs::bench::time_updates(state, observer, ring);
}
BENCHMARK(BM_GuyaderZhang_Satellite_ExcitationMonitor);

void BM_AugmentedKalman_Satellite(benchmark::State& state) {
  using Matrix6 = Eigen::Matrix<double, 6, 6>;
  adaptobs::AugmentedKalmanFilter filter(satellite::model<double>(), satellite::initial_state_estimate<double>(),
                                         satellite::initial_parameter_estimate<double>(),
                                         {Matrix6::Identity(), Matrix6::Identity() * 1e-10, Eigen::Matrix2d::Identity() * 1e-4});
  auto ring = satellite_ring();
  adaptobs::bench::time_updates(state, filter, ring);
}
BENCHMARK(BM_AugmentedKalman_Satellite);

// --- Sweep: random stable LTI system, n states, p = m = n/2 ------------------

template <class Dims>
struct SweepProblem {
  adaptobs::DiscreteLtiModel<Dims> model;
  typename Dims::GainMatrix gain;
  SampleRing<adaptobs::DiscreteSample<Dims>> ring;
};

template <class Dims>
SweepProblem<Dims> make_sweep_problem(Index n) {
  const Index m = n / 2, p = n / 2;
  std::mt19937_64 rng(42);
  std::uniform_real_distribution<double> d(-1, 1);
  auto random = [&](Index r, Index c) {
    Eigen::MatrixXd x(r, c);
    for (Index j = 0; j < c; ++j)
      for (Index i = 0; i < r; ++i) x(i, j) = d(rng);
    return x;
  };
  Eigen::MatrixXd a = random(n, n);
  a *= 0.95 / adaptobs::spectral_radius(a);
  const Eigen::MatrixXd b = random(n, 1);
  const Eigen::MatrixXd c = random(m, n);
  const auto kalman = adaptobs::steady_state_kalman_gain(a, c, Eigen::MatrixXd::Identity(n, n), Eigen::MatrixXd::Identity(m, m));
  std::vector<adaptobs::DiscreteSample<Dims>> samples;
  for (int k = 0; k < 16; ++k)
    samples.push_back({random(1, 1), random(m, 1), random(n, p) * 0.1});
  return {adaptobs::DiscreteLtiModel<Dims>(a, b, c, p), kalman.K, SampleRing(std::move(samples))};
}

template <int N>
using SweepDims = adaptobs::Dimensions<double, N, (N == Eigen::Dynamic ? Eigen::Dynamic : 1),
                                       (N == Eigen::Dynamic ? Eigen::Dynamic : N / 2),
                                       (N == Eigen::Dynamic ? Eigen::Dynamic : N / 2)>;

template <int N>
void BM_GuyaderZhang_Sweep(benchmark::State& state) {
  using Dims = SweepDims<N>;
  const Index n = N == Eigen::Dynamic ? state.range(0) : N;
  auto problem = make_sweep_problem<Dims>(n);
  adaptobs::GuyaderZhangObserver observer(problem.model, problem.gain, 0.01,
                                          typename Dims::State(Dims::State::Zero(n)),
                                          typename Dims::Parameters(Dims::Parameters::Zero(n / 2)));
  adaptobs::bench::time_updates(state, observer, problem.ring);
  state.counters["n"] = double(n);
}

template <int N>
void BM_AugmentedKalman_Sweep(benchmark::State& state) {
  using Dims = SweepDims<N>;
  const Index n = N == Eigen::Dynamic ? state.range(0) : N;
  auto problem = make_sweep_problem<Dims>(n);
  using Cov = adaptobs::AugmentedKalmanCovariances<Dims>;
  const Index na = n + n / 2;
  Cov cov{Cov::AugmentedMatrix::Identity(na, na), Cov::AugmentedMatrix::Identity(na, na) * 1e-6,
          Dims::OutputMatrixSquare::Identity(n / 2, n / 2)};
  adaptobs::AugmentedKalmanFilter filter(problem.model, typename Dims::State(Dims::State::Zero(n)),
                                         typename Dims::Parameters(Dims::Parameters::Zero(n / 2)), cov);
  adaptobs::bench::time_updates(state, filter, problem.ring);
  state.counters["n"] = double(n);
}

// Fixed sizes up to 16; Eigen::Dynamic at 32 and 64 (and at 16, to show the cost of dynamic sizes).
BENCHMARK(BM_GuyaderZhang_Sweep<2>)->Name("BM_GuyaderZhang_Sweep/fixed/2");
BENCHMARK(BM_GuyaderZhang_Sweep<4>)->Name("BM_GuyaderZhang_Sweep/fixed/4");
BENCHMARK(BM_GuyaderZhang_Sweep<8>)->Name("BM_GuyaderZhang_Sweep/fixed/8");
BENCHMARK(BM_GuyaderZhang_Sweep<16>)->Name("BM_GuyaderZhang_Sweep/fixed/16");
BENCHMARK(BM_GuyaderZhang_Sweep<Eigen::Dynamic>)->Name("BM_GuyaderZhang_Sweep/dynamic")->Arg(16)->Arg(32)->Arg(64);
BENCHMARK(BM_AugmentedKalman_Sweep<2>)->Name("BM_AugmentedKalman_Sweep/fixed/2");
BENCHMARK(BM_AugmentedKalman_Sweep<4>)->Name("BM_AugmentedKalman_Sweep/fixed/4");
BENCHMARK(BM_AugmentedKalman_Sweep<8>)->Name("BM_AugmentedKalman_Sweep/fixed/8");
BENCHMARK(BM_AugmentedKalman_Sweep<16>)->Name("BM_AugmentedKalman_Sweep/fixed/16");
BENCHMARK(BM_AugmentedKalman_Sweep<Eigen::Dynamic>)->Name("BM_AugmentedKalman_Sweep/dynamic")->Arg(16)->Arg(32)->Arg(64);

}  // namespace
