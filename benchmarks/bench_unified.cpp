// The continuous-time observers of the unified formulation (Zhang 2005), one
// sample = one RK4 step each, beside the augmented Kalman–Bucy filter on the
// same plants: the third-order SISO plant (Alg. 1, 2) and the periodic MIMO
// plant (Alg. 3, 4).

#include <adaptobs/simulation/plant.hpp>

#include "bench_support.hpp"
#include "models/unified_design_definitions.hpp"

#include <benchmark/benchmark.h>

#include <vector>

namespace {

namespace designs = adaptobs::examples::designs;
namespace siso = adaptobs::examples::siso;
namespace periodic = adaptobs::examples::periodic;

// Samples carry increasing times, so they cannot be replayed in a ring: after
// the last one the observer restarts (one cheap update in 20000).
template <class Observer, class Sample>
void time_steps(benchmark::State& state, Observer& observer, const std::vector<Sample>& samples) {
  const auto eta0 = observer.state();
  const auto theta0 = observer.parameters();
  std::size_t i = 0;
  for (auto _ : state) {
    if (i == samples.size()) {
      observer.reset(eta0, theta0);
      i = 0;
    }
    auto status = observer.update(samples[i++]);
    benchmark::DoNotOptimize(status);
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations());
}

const auto& siso_samples() {
  static const auto samples = adaptobs::record_samples(siso::make_plant<double>(), 20000);
  return samples;
}
const auto& mimo_samples() {
  static const auto samples = adaptobs::record_samples(periodic::make_plant<double>(), 20000);
  return samples;
}

void BM_BastinGevers_ThirdOrder(benchmark::State& state) {
  auto observer = designs::bastin_gevers_observer<double>();
  time_steps(state, observer, siso_samples());
}
BENCHMARK(BM_BastinGevers_ThirdOrder);

void BM_MarinoTomei_ThirdOrder(benchmark::State& state) {
  auto observer = designs::marino_tomei_observer<double>();
  time_steps(state, observer, siso_samples());
}
BENCHMARK(BM_MarinoTomei_ThirdOrder);

void BM_AugmentedKalmanBucy_ThirdOrder(benchmark::State& state) {
  auto filter = designs::kalman_bucy_filter<double>(1.0);
  time_steps(state, filter, siso_samples());
}
BENCHMARK(BM_AugmentedKalmanBucy_ThirdOrder);

void BM_Besancon_PeriodicMimo(benchmark::State& state) {
  auto observer = designs::besancon_observer<double>();
  time_steps(state, observer, mimo_samples());
}
BENCHMARK(BM_Besancon_PeriodicMimo);

void BM_ZhangContinuous_PeriodicMimo(benchmark::State& state) {
  auto observer = designs::zhang_observer<double>(50.0);
  time_steps(state, observer, mimo_samples());
}
BENCHMARK(BM_ZhangContinuous_PeriodicMimo);

void BM_AugmentedKalmanBucy_PeriodicMimo(benchmark::State& state) {
  using D = periodic::Dims<double>;
  using Cov = adaptobs::AugmentedKalmanCovariances<D>;
  const Cov covariances{Cov::AugmentedMatrix::Identity(), Cov::AugmentedMatrix::Identity(),
                        0.1 * Eigen::Matrix2d::Identity()};
  adaptobs::AugmentedKalmanBucyFilter filter(periodic::model<double>(), Eigen::Vector4d::Zero().eval(),
                                             Eigen::Vector2d::Zero().eval(), covariances, designs::quadratic());
  time_steps(state, filter, mimo_samples());
}
BENCHMARK(BM_AugmentedKalmanBucy_PeriodicMimo);

}  // namespace
