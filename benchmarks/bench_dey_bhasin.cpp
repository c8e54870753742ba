// Dey–Bhasin and Suzuki observers (Dey & Bhasin 2022, §5) against the augmented-state
// Kalman filter on the same systems (written in the linear-in-p form (7):
// x_{t+1} = F x_t + Ψ_t p with Ψ_t = [I_r ⊗ y_t, u_tᵀ ⊗ I_n]); each adaptation
// law alone at p ∈ {4, 16, 64} (q = 2); and the cost of the reset test of
// (23): Cholesky against eigenvalues and a full eigendecomposition.

#include <adaptobs/adaptation/covariance_resetting.hpp>
#include <adaptobs/adaptation/exponential_forgetting.hpp>
#include <adaptobs/adaptation/normalized_gradient.hpp>
#include <adaptobs/adaptation/recursive_least_squares.hpp>
#include <adaptobs/baselines/augmented_kalman.hpp>
#include <adaptobs/observers/dey_bhasin.hpp>

#include <Eigen/Eigenvalues>
#include <Eigen/QR>

#include "bench_support.hpp"
#include "models/dey_bhasin.hpp"

#include <cmath>
#include <random>
#include <vector>

namespace {

using adaptobs::Index;
using adaptobs::bench::SampleRing;
namespace db = adaptobs::examples::dey_bhasin;

// --- Observers on the paper's systems ---------------------------------------------

template <class Observer, class Plant>
SampleRing<typename Observer::Sample> observer_ring(Plant plant, Index steps) {
  std::vector<typename Observer::Sample> samples;
  for (Index k = 0; k < steps; ++k) {
    samples.push_back({plant.sample().u, plant.sample().y});
    plant.advance();
  }
  return SampleRing(std::move(samples));
}

void BM_DeyBhasin_MIMO(benchmark::State& state) {
  auto observer = db::mimo::make_observer();
  auto ring = observer_ring<db::mimo::Observer<double>>(db::mimo::make_plant(db::mimo::RichInput{}), 3000);
  adaptobs::bench::time_updates(state, observer, ring);
  state.counters["resets_per_update"] =
      benchmark::Counter(double(observer.law().reset_count()), benchmark::Counter::kAvgIterations);
  state.counters["cholesky_per_update"] =
      benchmark::Counter(double(observer.law().reset_tests_run()), benchmark::Counter::kAvgIterations);
}
BENCHMARK(BM_DeyBhasin_MIMO);

// The second output absent (the law steps on one channel), and none (the time
// update: the filters advance, the law is not called).
template <bool FirstPresent>
void BM_DeyBhasin_MIMO_Masked(benchmark::State& state) {
  auto observer = db::mimo::make_observer();
  auto ring = observer_ring<db::mimo::Observer<double>>(db::mimo::make_plant(db::mimo::RichInput{}), 3000);
  adaptobs::bench::time_masked_updates(state, observer, ring,
                                       adaptobs::OutputMask<db::mimo::Observer<double>::Dims>(FirstPresent, false));
}
BENCHMARK(BM_DeyBhasin_MIMO_Masked<true>)->Name("BM_DeyBhasin_MIMO_PartialOutput");
BENCHMARK(BM_DeyBhasin_MIMO_Masked<false>)->Name("BM_DeyBhasin_MIMO_TimeUpdate");

void BM_DeyBhasin_MIMO_Dynamic(benchmark::State& state) {
  using Dynamic = adaptobs::DeyBhasinObserver<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::Dynamic>;
  Dynamic observer(Eigen::VectorXd(db::mimo::f()), Eigen::VectorXd(db::mimo::x_hat0()),
                   Eigen::VectorXd(db::mimo::a_hat0()), Eigen::MatrixXd(db::mimo::B_hat0()),
                   {.k0 = db::mimo::k0, .kmin = db::mimo::kmin, .R = Eigen::MatrixXd::Identity(2, 2)});
  auto ring = observer_ring<Dynamic>(db::mimo::make_plant(db::mimo::RichInput{}), 3000);
  adaptobs::bench::time_updates(state, observer, ring);
}
BENCHMARK(BM_DeyBhasin_MIMO_Dynamic);

// Ψ_t = [I_r ⊗ y_t, u_tᵀ ⊗ I_n]: eq. (7) as x_{t+1} = F x_t + Ψ_t p, for the augmented Kalman filter.
template <class Dims, class U, class Y>
typename Dims::RegressorMatrix equation7_regressor(const U& u, const Y& y, Index r) {
  const Index q = y.size(), n = r * q;
  typename Dims::RegressorMatrix psi = Dims::RegressorMatrix::Zero(n, r + u.size() * n);
  for (Index k = 0; k < r; ++k) psi.block(k * q, k, q, 1) = y;
  for (Index i = 0; i < u.size(); ++i) psi.block(0, r + i * n, n, n).diagonal().setConstant(u(i));
  return psi;
}

template <int R, int Q, int M, class Plant>
void time_augmented_kalman(benchmark::State& state, const Eigen::Matrix<double, R, 1>& f, Plant plant) {
  constexpr int N = R * Q, P = R + M * N;
  using Dims = adaptobs::Dimensions<double, N, M, Q, P>;
  using Cov = adaptobs::AugmentedKalmanCovariances<Dims>;
  const typename Dims::StateMatrix a = adaptobs::block_companion_matrix<Q>(f);
  const typename Dims::OutputMatrix c = db::canonical_output_matrix<double>(R, Q);
  const adaptobs::DiscreteLtiModel<Dims> model(a, Dims::InputMatrix::Zero(), c);
  typename Cov::AugmentedMatrix p0 = Cov::AugmentedMatrix::Identity();
  p0.template bottomRightCorner<P, P>() *= 1e3;
  Cov covariances{p0, Cov::AugmentedMatrix::Identity() * 1e-12, Dims::OutputMatrixSquare::Identity() * 1e-6};
  adaptobs::AugmentedKalmanFilter filter(model, Dims::State::Zero().eval(), Dims::Parameters::Zero().eval(),
                                         covariances);
  std::vector<adaptobs::DiscreteSample<Dims>> samples;
  for (Index k = 0; k < 3000; ++k) {
    const auto& s = plant.sample();
    samples.push_back({s.u, s.y, equation7_regressor<Dims>(s.u, s.y, R)});
    plant.advance();
  }
  SampleRing ring(std::move(samples));
  adaptobs::bench::time_updates(state, filter, ring);
}

void BM_AugmentedKalman_MIMO(benchmark::State& state) {
  time_augmented_kalman<3, 2, 2>(state, db::mimo::f(), db::mimo::make_plant(db::mimo::RichInput{}));
}
BENCHMARK(BM_AugmentedKalman_MIMO);

void BM_DeyBhasin_SISO(benchmark::State& state) {
  auto observer = db::siso::make_observer();
  auto ring = observer_ring<db::siso::Observer<double>>(db::siso::make_plant(), 3000);
  adaptobs::bench::time_updates(state, observer, ring);
}
BENCHMARK(BM_DeyBhasin_SISO);

// A persistently exciting input keeps the forgetting law finite, so that every timed
// update is a full one (with the paper's sine it overflows after about 2050 updates).
struct RandomInput {
  std::vector<double> values;
  RandomInput() {
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> d(-1, 1);
    for (int k = 0; k < 3000; ++k) values.push_back(d(rng));
  }
  Eigen::Matrix<double, 1, 1> operator()(Index k) const {
    return Eigen::Matrix<double, 1, 1>(values[std::size_t(k) % values.size()]);
  }
};

void BM_Suzuki_SISO(benchmark::State& state) {
  auto observer = db::siso::make_suzuki();
  auto ring = observer_ring<db::siso::Suzuki<double>>(db::siso::make_plant(RandomInput{}), 3000);
  Index rejected = 0;
  for (auto _ : state) {
    auto status = observer.update(ring.next());
    rejected += status != adaptobs::UpdateStatus::accepted;
    benchmark::DoNotOptimize(status);
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations());
  state.counters["rejected"] = double(rejected);
}
BENCHMARK(BM_Suzuki_SISO);

void BM_AugmentedKalman_SISO(benchmark::State& state) {
  time_augmented_kalman<2, 1, 1>(state, db::siso::f(), db::siso::make_plant());
}
BENCHMARK(BM_AugmentedKalman_SISO);

// --- Each adaptation law alone, p ∈ {4, 16, 64}, q = 2 -------------------------------

constexpr int kMeasurements = 2;

template <int P>
struct LawData {
  using Regressor = Eigen::Matrix<double, P, kMeasurements>;
  using Measurement = Eigen::Matrix<double, kMeasurements, 1>;
  std::vector<Regressor> phi;
  std::vector<Measurement> z;
  std::size_t i = 0;
  explicit LawData(Index p) {
    std::mt19937_64 rng(64);
    std::uniform_real_distribution<double> d(-1, 1);
    Eigen::VectorXd truth(p);
    for (Index k = 0; k < p; ++k) truth(k) = d(rng);
    for (int s = 0; s < 64; ++s) {
      Regressor r(p, kMeasurements);
      for (Index j = 0; j < kMeasurements; ++j)
        for (Index k = 0; k < p; ++k) r(k, j) = d(rng);
      phi.push_back(r);
      z.push_back(r.transpose() * truth + 0.01 * Measurement(d(rng), d(rng)));
    }
  }
  void next() { i = (i + 1 == phi.size()) ? 0 : i + 1; }
};

template <int P>
using Weight = Eigen::Matrix<double, kMeasurements, kMeasurements>;

template <class Law>
void time_law(benchmark::State& state, Law& law, Index p) {
  constexpr int P = Law::Regressor::RowsAtCompileTime;
  LawData<P> data(p);
  for (auto _ : state) {
    const bool ok = law.propose(data.phi[data.i], data.z[data.i]);
    law.commit();
    data.next();
    benchmark::DoNotOptimize(ok);
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations());
  state.counters["p"] = double(p);
}

template <int P>
Index size_of(const benchmark::State& state) {
  return P == Eigen::Dynamic ? state.range(0) : P;
}

template <int P>
void BM_Law_Rls(benchmark::State& state) {
  const Index p = size_of<P>(state);
  using Law = adaptobs::RecursiveLeastSquares<double, P, kMeasurements>;
  Law law(Law::Parameters::Zero(p), {Law::Covariance::Identity(p, p), Weight<P>::Identity()});
  time_law(state, law, p);
}

template <int P>
void BM_Law_Resetting(benchmark::State& state) {
  const Index p = size_of<P>(state);
  using Law = adaptobs::CovarianceResettingRls<double, P, kMeasurements>;
  Law law(Law::Parameters::Zero(p), {.k0 = 1e3, .kmin = 1e-4, .R = Weight<P>::Identity()});
  time_law(state, law, p);
  state.counters["cholesky_per_update"] =
      benchmark::Counter(double(law.reset_tests_run()), benchmark::Counter::kAvgIterations);
}

template <int P>
void BM_Law_ResettingUnscreened(benchmark::State& state) {
  const Index p = size_of<P>(state);
  using Law = adaptobs::CovarianceResettingRls<double, P, kMeasurements>;
  Law law(Law::Parameters::Zero(p), {.k0 = 1e3, .kmin = 1e-4, .R = Weight<P>::Identity(), .screen_reset_test = false});
  time_law(state, law, p);
}

template <int P>
void BM_Law_Forgetting(benchmark::State& state) {
  const Index p = size_of<P>(state);
  using Law = adaptobs::ExponentialForgettingRls<double, P, kMeasurements>;
  Law law(Law::Parameters::Zero(p), {Law::Covariance::Identity(p, p), Weight<P>::Identity(), 0.98});
  time_law(state, law, p);
}

template <int P>
void BM_Law_NormalizedGradient(benchmark::State& state) {
  const Index p = size_of<P>(state);
  using Law = adaptobs::NormalizedGradient<double, P, kMeasurements>;
  Law law(Law::Parameters::Zero(p), {.mu = 1.0, .offset = 1.0}, kMeasurements);
  time_law(state, law, p);
}

#define ADAPTOBS_LAW_SWEEP(name)                \
  BENCHMARK(name<4>)->Name(#name "/fixed/4");   \
  BENCHMARK(name<16>)->Name(#name "/fixed/16"); \
  BENCHMARK(name<Eigen::Dynamic>)->Name(#name "/dynamic")->Arg(64)

ADAPTOBS_LAW_SWEEP(BM_Law_Rls);
ADAPTOBS_LAW_SWEEP(BM_Law_Resetting);
ADAPTOBS_LAW_SWEEP(BM_Law_ResettingUnscreened);
ADAPTOBS_LAW_SWEEP(BM_Law_Forgetting);
ADAPTOBS_LAW_SWEEP(BM_Law_NormalizedGradient);

// --- The reset test of (23): is λ_min(Γ̄) > kmin? ----------------------------------------

template <int P>
Eigen::Matrix<double, P, P> covariance_for_reset_test(Index p) {
  std::mt19937_64 rng(23);
  std::uniform_real_distribution<double> d(-1, 1);
  Eigen::MatrixXd m(p, p);
  for (Index j = 0; j < p; ++j)
    for (Index i = 0; i < p; ++i) m(i, j) = d(rng);
  const Eigen::MatrixXd q = Eigen::HouseholderQR<Eigen::MatrixXd>(m).householderQ();
  Eigen::VectorXd lambda(p);
  for (Index i = 0; i < p; ++i) lambda(i) = std::pow(10.0, -3.0 + 6.0 * double(i) / double(p - 1));  // 1e-3 … 1e3
  return q * lambda.asDiagonal() * q.transpose();
}

// What the law runs: copy Γ̄ − kmin I, factor it.
template <int P>
void BM_ResetTest_Cholesky(benchmark::State& state) {
  const Index p = size_of<P>(state);
  const Eigen::Matrix<double, P, P> gamma = covariance_for_reset_test<P>(p);
  Eigen::Matrix<double, P, P> shifted(p, p);
  for (auto _ : state) {
    shifted = gamma;
    shifted.diagonal().array() -= 1e-4;
    bool above = adaptobs::detail::cholesky_in_place(shifted);
    benchmark::DoNotOptimize(above);
    benchmark::ClobberMemory();
  }
  state.counters["p"] = double(p);
}

template <int P, int Options>
void time_eigen_test(benchmark::State& state) {
  const Index p = size_of<P>(state);
  const Eigen::Matrix<double, P, P> gamma = covariance_for_reset_test<P>(p);
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, P, P>> solver(p);
  for (auto _ : state) {
    solver.compute(gamma, Options);
    bool above = solver.eigenvalues()(0) > 1e-4;
    benchmark::DoNotOptimize(above);
    benchmark::ClobberMemory();
  }
  state.counters["p"] = double(p);
}

template <int P>
void BM_ResetTest_Eigenvalues(benchmark::State& state) {
  time_eigen_test<P, Eigen::EigenvaluesOnly>(state);
}

template <int P>
void BM_ResetTest_EigenDecomposition(benchmark::State& state) {
  time_eigen_test<P, Eigen::ComputeEigenvectors>(state);
}

ADAPTOBS_LAW_SWEEP(BM_ResetTest_Cholesky);
ADAPTOBS_LAW_SWEEP(BM_ResetTest_Eigenvalues);
ADAPTOBS_LAW_SWEEP(BM_ResetTest_EigenDecomposition);

}  // namespace
