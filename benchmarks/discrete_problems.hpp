#pragma once
// Discrete-time problems shared by the Guyader–Zhang and augmented-Kalman
// benchmarks: the satellite of Guyader & Zhang (2003) and a random stable system whose
// size is swept.

#include <adaptobs/core/discrete_model.hpp>
#include <adaptobs/design/dare.hpp>
#include <adaptobs/design/stability.hpp>
#include <adaptobs/simulation/plant.hpp>

#include "bench_support.hpp"
#include "models/satellite.hpp"

#include <random>
#include <vector>

namespace adaptobs::bench {

inline SampleRing<DiscreteSample<examples::satellite::Dims<double>>> satellite_ring() {
  return SampleRing(record_samples(examples::satellite::make_plant<double>(), 1000));
}

/// n states, p = m = n/2 (one input); all sizes dynamic when N is.
template <int N>
using SweepDims =
    Dimensions<double, N, (N == Eigen::Dynamic ? Eigen::Dynamic : 1), (N == Eigen::Dynamic ? Eigen::Dynamic : N / 2),
               (N == Eigen::Dynamic ? Eigen::Dynamic : N / 2)>;

template <class Dims>
struct SweepProblem {
  DiscreteLtiModel<Dims> model;
  typename Dims::GainMatrix gain;
  SampleRing<DiscreteSample<Dims>> ring;
};

/// Random stable system (spectral radius 0.95), steady-state Kalman gain, and a
/// ring of 16 random samples (small enough to stay in cache at every size).
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
  a *= 0.95 / spectral_radius(a);
  const Eigen::MatrixXd b = random(n, 1);
  const Eigen::MatrixXd c = random(m, n);
  const auto kalman = steady_state_kalman_gain(a, c, Eigen::MatrixXd::Identity(n, n), Eigen::MatrixXd::Identity(m, m));
  std::vector<DiscreteSample<Dims>> samples;
  for (int k = 0; k < 16; ++k) samples.push_back({random(1, 1), random(m, 1), random(n, p) * 0.1});
  return {DiscreteLtiModel<Dims>(a, b, c, p), kalman.K, SampleRing(std::move(samples))};
}

}  // namespace adaptobs::bench
