// The matrix exponential at the sizes of sampled models (2 to 9 states): a
// moderate A T, which r_m(A T) serves without squaring, and a stiff one,
// ‖A T‖₁ ≈ 200, which needs squarings and so goes through the Schur form.

#include <adaptobs/core/matrix_exponential.hpp>

#include <benchmark/benchmark.h>

#include <Eigen/Core>

#include <random>

namespace {

using Index = Eigen::Index;

// A random A with entries uniform in [−1, 1], times `scale`, shifted to be stable.
Eigen::MatrixXd random_generator(Index n, double scale) {
  std::mt19937_64 rng(static_cast<std::mt19937_64::result_type>(n));
  std::uniform_real_distribution<double> d(-1, 1);
  Eigen::MatrixXd a(n, n);
  for (Index j = 0; j < n; ++j)
    for (Index i = 0; i < n; ++i) a(i, j) = d(rng);
  return scale * (a - double(n) * Eigen::MatrixXd::Identity(n, n)) / double(n);
}

void time_exponential(benchmark::State& state, double scale) {
  const Eigen::MatrixXd a = random_generator(state.range(0), scale);
  for (auto _ : state) {
    Eigen::MatrixXd e = adaptobs::matrix_exponential(a);
    benchmark::DoNotOptimize(e.data());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations());
}

void BM_MatrixExponential_Moderate(benchmark::State& state) { time_exponential(state, 0.5); }
BENCHMARK(BM_MatrixExponential_Moderate)->DenseRange(2, 9);

void BM_MatrixExponential_Stiff(benchmark::State& state) { time_exponential(state, 100.0); }
BENCHMARK(BM_MatrixExponential_Stiff)->DenseRange(2, 9);

}  // namespace
