// Time of the LMI synthesis (theorem 2, K_i = 0.03, Q_e of Remark 6) for the
// waste water plant of Srinivasarengan et al. (2018) §6 with DSDP: building the 60 × 60 vertex LMIs,
// solving, and verifying the solution.

#include <adaptobs/design/lmi/takagi_sugeno_synthesis.hpp>

#include "models/wwtp.hpp"

#include <benchmark/benchmark.h>

namespace {

namespace wwtp = adaptobs::examples::wwtp;

adaptobs::TakagiSugenoLmiOptions wwtp_options() {
  adaptobs::TakagiSugenoLmiOptions options;
  options.Q_x = 1e-3 * Eigen::MatrixXd::Identity(2, 2);
  options.Q_theta = Eigen::MatrixXd::Constant(1, 1, 0.1);
  options.parameter_gain = Eigen::MatrixXd::Constant(1, 1, 0.03);
  return options;
}

template <class Model>
void time_synthesis(benchmark::State& state, const Model& model, const adaptobs::TakagiSugenoLmiOptions& options) {
  int iterations = 0;
  double dsdp_seconds = 0;
  for (auto _ : state) {
    const auto result = adaptobs::synthesize_takagi_sugeno_gains(model, options);
    if (!result.feasible()) state.SkipWithError("LMI synthesis did not return verified gains");
    iterations = result.solver.iterations;
    dsdp_seconds = result.solver.seconds;
    benchmark::DoNotOptimize(result.gains);
  }
  state.counters["dsdp_iterations"] = iterations;
  state.counters["dsdp_seconds"] = dsdp_seconds;
}

// Corollary 1 (minimise β) with the input's sector narrowed to [0.05, 0.4]: β* = 536.65.
void BM_TakagiSugeno_WWTP_LmiSynthesis(benchmark::State& state) {
  time_synthesis(state, wwtp::model<double>(0.05), wwtp_options());
}
BENCHMARK(BM_TakagiSugeno_WWTP_LmiSynthesis)->Unit(benchmark::kMillisecond);

// The paper's sectors (u ∈ [0, 0.4]), ill-conditioned: largest margin with Γ = 10⁸.
void BM_TakagiSugeno_WWTP_LmiSynthesisPaperSectors(benchmark::State& state) {
  auto options = wwtp_options();
  options.objective = adaptobs::TakagiSugenoObjective::maximize_margin;
  options.fixed_gamma = 1e8;
  time_synthesis(state, wwtp::model<double>(), options);
}
BENCHMARK(BM_TakagiSugeno_WWTP_LmiSynthesisPaperSectors)->Unit(benchmark::kMillisecond);

}  // namespace
