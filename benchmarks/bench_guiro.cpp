// Guiro–Iggidr–Ngom–Touré observer against the augmented-state Kalman filter
// on the same sampled system (x_{k+1} = e^{AT}x_k + Ψ_kθ, Ψ_k = e^{AT}H_k):
// one sample with Ψ_k given, and one sample that first recomputes H_k from
// φ(t) (adaptive quadrature, or the exact form for a piecewise-linear φ); at
// the paper's sizes (n = 2, m = p = 1) and at n = 6, m = p = 3.

#include <adaptobs/baselines/augmented_kalman.hpp>
#include <adaptobs/core/sampled_model.hpp>
#include <adaptobs/design/guiro_gains.hpp>
#include <adaptobs/design/pole_placement.hpp>
#include <adaptobs/models/regressor_integral.hpp>
#include <adaptobs/observers/guiro.hpp>
#include <adaptobs/simulation/plant.hpp>

#include "bench_support.hpp"
#include "models/guiro.hpp"

#include <Eigen/Eigenvalues>

#include <array>
#include <cmath>
#include <random>
#include <vector>

namespace {

using adaptobs::Index;
using adaptobs::bench::SampleRing;
namespace g = adaptobs::examples::guiro;
using PaperDims = g::Dims<double>;
using PaperSample = adaptobs::DiscreteSample<PaperDims>;
constexpr Index ring_size = 256;

std::vector<PaperSample> paper_samples() { return adaptobs::record_samples(g::make_plant<double>(), ring_size); }

adaptobs::GuiroObserver<adaptobs::DiscreteLtiModel<PaperDims>> paper_observer() {
  const auto model = g::model<double>();
  const auto gains = adaptobs::design_guiro_gains(model.system().A, model.system().C, g::closed_form_H<double>(0),
                                                  g::requested_poles());
  return {model, gains.K, gains.Gamma, g::initial_state_estimate<double>(), g::initial_parameter_estimate<double>()};
}

void BM_Guiro_Paper(benchmark::State& state) {
  auto observer = paper_observer();
  SampleRing ring(paper_samples());
  adaptobs::bench::time_updates(state, observer, ring);
}
BENCHMARK(BM_Guiro_Paper);

// No output: the open-loop prediction z⁻ = E z + Ψ θ̂, θ̂ held.
void BM_Guiro_Paper_TimeUpdate(benchmark::State& state) {
  auto observer = paper_observer();
  SampleRing ring(paper_samples());
  adaptobs::bench::time_masked_updates(state, observer, ring, adaptobs::OutputMask<PaperDims>(false));
}
BENCHMARK(BM_Guiro_Paper_TimeUpdate);

// Times one update per iteration on the paper's samples, each with its Ψ_k
// recomputed first by `recompute(t_k, h)` into h.
template <class Recompute>
void time_updates_recomputing_psi(benchmark::State& state, Recompute&& recompute) {
  auto observer = paper_observer();
  const auto samples = paper_samples();
  adaptobs::SampledRegressor<double, 2, 1> h;
  std::size_t k = 0;
  for (auto _ : state) {
    PaperSample sample = samples[k];
    recompute(double(k) * g::period, h);
    sample.Psi = h.Psi;
    auto status = observer.update(sample);
    benchmark::DoNotOptimize(status);
    benchmark::ClobberMemory();
    k = (k + 1 == samples.size()) ? 0 : k + 1;
  }
  state.SetItemsProcessed(state.iterations());
}

// Each iteration integrates H_k (and Ψ_k) for φ(t) = ((t+1)/(t+2), 0) over its period, then updates.
void BM_Guiro_Paper_RecomputeH_Quadrature(benchmark::State& state) {
  adaptobs::RegressorIntegral<double, 2, 1> integral(g::continuous_dynamics<double>(), g::period);
  time_updates_recomputing_psi(
      state, [&](double t, adaptobs::SampledRegressor<double, 2, 1>& h) { integral.integrate(g::Regressor{}, t, h); });
}
BENCHMARK(BM_Guiro_Paper_RecomputeH_Quadrature);

// φ linear on each period (through its values at both ends): exact H_k from precomputed moments.
void BM_Guiro_Paper_RecomputeH_PiecewiseLinear(benchmark::State& state) {
  const adaptobs::PolynomialRegressorIntegral<double, 2, 1> integral(g::continuous_dynamics<double>(), g::period, 1);
  std::array<Eigen::Vector2d, 2> coefficients;
  time_updates_recomputing_psi(state, [&](double t, adaptobs::SampledRegressor<double, 2, 1>& h) {
    coefficients[0] = g::Regressor{}(t);
    coefficients[1] = (g::Regressor{}(t + g::period) - coefficients[0]) / g::period;
    integral.integrate(coefficients, h);
  });
}
BENCHMARK(BM_Guiro_Paper_RecomputeH_PiecewiseLinear);

void BM_AugmentedKalman_GuiroPaper(benchmark::State& state) {
  using Matrix3 = Eigen::Matrix3d;
  adaptobs::AugmentedKalmanFilter filter(
      g::model<double>(), g::initial_state_estimate<double>(), g::initial_parameter_estimate<double>(),
      {Matrix3::Identity(), Matrix3::Identity() * 1e-10, Eigen::Matrix<double, 1, 1>(1e-4)});
  SampleRing ring(paper_samples());
  adaptobs::bench::time_updates(state, filter, ring);
}
BENCHMARK(BM_AugmentedKalman_GuiroPaper);

// ---- n = 6 states, m = 3 outputs, p = 3 parameters ----------------------------

using MimoDims = adaptobs::Dimensions<double, 6, 1, 3, 3>;
using MimoSample = adaptobs::DiscreteSample<MimoDims>;
using MimoRegressor = Eigen::Matrix<double, 6, 3>;

struct MimoProblem {
  Eigen::Matrix<double, 6, 6> a;
  MimoRegressor phi0, phi1;
  adaptobs::DiscreteLtiModel<MimoDims> model;
  std::vector<MimoSample> samples;
  MimoRegressor operator()(double t) const { return phi0 + std::sin(t) * phi1; }
};

MimoProblem make_mimo() {
  std::mt19937_64 rng(6);
  std::uniform_real_distribution<double> d(-1, 1);
  const auto random = [&](Index r, Index c) {
    Eigen::MatrixXd x(r, c);
    for (Index j = 0; j < c; ++j)
      for (Index i = 0; i < r; ++i) x(i, j) = d(rng);
    return x;
  };
  // A random a, shifted so that its eigenvalues have real parts at most -0.3: a
  // stable plant, whose samples stay of order one over the ring's passes (the
  // unshifted a gave a sampled spectral radius of 1.23).
  Eigen::Matrix<double, 6, 6> a = random(6, 6) * 0.5;
  a -= (Eigen::EigenSolver<Eigen::MatrixXd>(a).eigenvalues().real().maxCoeff() + 0.3) *
       Eigen::Matrix<double, 6, 6>::Identity();
  const Eigen::Matrix<double, 6, 1> b = random(6, 1);
  const Eigen::Matrix<double, 3, 6> c = random(3, 6);
  const double T = 0.5;
  // The regressor's varying part 0.3 of the size of its constant one: the gains
  // are designed for H at t = 0, and with parts of equal size they do not hold
  // along the run (the observer diverged; with 0.3 it gives θ to 1e-5 on the ring).
  MimoProblem problem{a, random(6, 3), 0.3 * random(6, 3), adaptobs::sampled_lti_model<MimoDims>(a, b, c, T), {}};
  adaptobs::RegressorIntegral<double, 6, 3> integral(a, T);
  Eigen::Matrix<double, 6, 1> x = Eigen::Matrix<double, 6, 1>::Zero();
  const Eigen::Vector3d theta(1, -2, 0.5);
  const auto& system = problem.model.system();
  for (Index k = 0; k < 64; ++k) {
    const Eigen::Matrix<double, 1, 1> u(std::sin(0.2 * double(k)));
    const MimoRegressor psi = integral.integrate(problem, double(k) * T).Psi;
    problem.samples.push_back({u, system.C * x, psi});
    x = (system.A * x + system.B * u + psi * theta).eval();
  }
  return problem;
}

void BM_Guiro_Mimo6(benchmark::State& state) {
  const MimoProblem problem = make_mimo();
  const auto& system = problem.model.system();
  const MimoRegressor h_nominal = adaptobs::RegressorIntegral<double, 6, 3>(problem.a, 0.5).integrate(problem, 0.0).H;
  const auto gains =
      adaptobs::design_guiro_gains(system.A, system.C, h_nominal, adaptobs::spread_poles<double>(9, 0.6));
  adaptobs::GuiroObserver observer(problem.model, gains.K, gains.Gamma, Eigen::Matrix<double, 6, 1>::Zero().eval(),
                                   Eigen::Vector3d::Zero().eval());
  if (!adaptobs::bench::accepts_every_sample(state, observer, problem.samples, 100)) return;
  SampleRing ring(problem.samples);
  adaptobs::bench::time_updates(state, observer, ring);
}
BENCHMARK(BM_Guiro_Mimo6);

void BM_Guiro_Mimo6_RecomputeH_Quadrature(benchmark::State& state) {
  const MimoProblem problem = make_mimo();
  const auto& system = problem.model.system();
  adaptobs::RegressorIntegral<double, 6, 3> integral(problem.a, 0.5);
  const auto gains = adaptobs::design_guiro_gains(system.A, system.C, integral.integrate(problem, 0.0).H,
                                                  adaptobs::spread_poles<double>(9, 0.6));
  adaptobs::GuiroObserver observer(problem.model, gains.K, gains.Gamma, Eigen::Matrix<double, 6, 1>::Zero().eval(),
                                   Eigen::Vector3d::Zero().eval());
  adaptobs::SampledRegressor<double, 6, 3> h;
  std::size_t k = 0;
  for (auto _ : state) {
    MimoSample sample = problem.samples[k];
    integral.integrate(problem, double(k) * 0.5, h);
    sample.Psi = h.Psi;
    auto status = observer.update(sample);
    benchmark::DoNotOptimize(status);
    benchmark::ClobberMemory();
    k = (k + 1 == problem.samples.size()) ? 0 : k + 1;
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_Guiro_Mimo6_RecomputeH_Quadrature);

void BM_AugmentedKalman_GuiroMimo6(benchmark::State& state) {
  const MimoProblem problem = make_mimo();
  using Matrix9 = Eigen::Matrix<double, 9, 9>;
  adaptobs::AugmentedKalmanFilter filter(
      problem.model, Eigen::Matrix<double, 6, 1>::Zero().eval(), Eigen::Vector3d::Zero().eval(),
      {Matrix9::Identity(), Matrix9::Identity() * 1e-10, Eigen::Matrix3d::Identity() * 1e-4});
  SampleRing ring(problem.samples);
  adaptobs::bench::time_updates(state, filter, ring);
}
BENCHMARK(BM_AugmentedKalman_GuiroMimo6);

}  // namespace
