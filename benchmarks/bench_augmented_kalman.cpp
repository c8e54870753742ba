// Augmented-state Kalman filter, the baseline of the discrete observers: one
// update at the satellite's sizes and the same sweep as the Guyader–Zhang
// observer. Fixed sizes stop at n = 8 (a 12 × 12 augmented covariance); beyond,
// fixed-size GEMM instantiations cost minutes of compile time for no gain over
// the dynamic kernel.

#include <adaptobs/baselines/augmented_kalman.hpp>

#include "discrete_problems.hpp"

namespace {

using adaptobs::Index;
namespace satellite = adaptobs::examples::satellite;

auto satellite_filter() {
  using Matrix6 = Eigen::Matrix<double, 6, 6>;
  return adaptobs::AugmentedKalmanFilter(
      satellite::model<double>(), satellite::initial_state_estimate<double>(),
      satellite::initial_parameter_estimate<double>(),
      {Matrix6::Identity(), Matrix6::Identity() * 1e-10, Eigen::Matrix2d::Identity() * 1e-4});
}

void BM_AugmentedKalman_Satellite(benchmark::State& state) {
  auto filter = satellite_filter();
  auto ring = adaptobs::bench::satellite_ring();
  adaptobs::bench::time_updates(state, filter, ring);
}
BENCHMARK(BM_AugmentedKalman_Satellite);

// No output: the prediction of x and θ and of the covariance only.
void BM_AugmentedKalman_Satellite_TimeUpdate(benchmark::State& state) {
  auto filter = satellite_filter();
  auto ring = adaptobs::bench::satellite_ring();
  adaptobs::bench::time_masked_updates(state, filter, ring,
                                       adaptobs::OutputMask<satellite::Dims<double>>(false, false));
}
BENCHMARK(BM_AugmentedKalman_Satellite_TimeUpdate);

template <int N>
void BM_AugmentedKalman_Sweep(benchmark::State& state) {
  using Dims = adaptobs::bench::SweepDims<N>;
  const Index n = N == Eigen::Dynamic ? state.range(0) : N;
  auto problem = adaptobs::bench::make_sweep_problem<Dims>(n);
  using Cov = adaptobs::AugmentedKalmanCovariances<Dims>;
  const Index na = n + n / 2;
  Cov cov{Cov::AugmentedMatrix::Identity(na, na), Cov::AugmentedMatrix::Identity(na, na) * 1e-6,
          Dims::OutputMatrixSquare::Identity(n / 2, n / 2)};
  adaptobs::AugmentedKalmanFilter filter(problem.model, typename Dims::State(Dims::State::Zero(n)),
                                         typename Dims::Parameters(Dims::Parameters::Zero(n / 2)), cov);
  adaptobs::bench::time_updates(state, filter, problem.ring);
  state.counters["n"] = double(n);
}

BENCHMARK(BM_AugmentedKalman_Sweep<2>)->Name("BM_AugmentedKalman_Sweep/fixed/2");
BENCHMARK(BM_AugmentedKalman_Sweep<4>)->Name("BM_AugmentedKalman_Sweep/fixed/4");
BENCHMARK(BM_AugmentedKalman_Sweep<8>)->Name("BM_AugmentedKalman_Sweep/fixed/8");
BENCHMARK(BM_AugmentedKalman_Sweep<Eigen::Dynamic>)
    ->Name("BM_AugmentedKalman_Sweep/dynamic")
    ->Arg(16)
    ->Arg(32)
    ->Arg(64);

}  // namespace
