// The baseline of benchmarks/python/bench_python.py: the same observers with
// run-time sizes, driven by a plain C++ loop over recorded samples, as the
// Python package's run() drives them. Prints nanoseconds per sample.
//
//   g++ -std=c++20 -O3 -DNDEBUG -Iinclude -Iexamples -I/usr/include/eigen3 \
//       benchmarks/python/cxx_dynamic_loop.cpp -o cxx_dynamic_loop && ./cxx_dynamic_loop 100000

#include <adaptobs/baselines/augmented_kalman.hpp>
#include <adaptobs/observers/guyader_zhang.hpp>

#include "models/satellite.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <vector>

namespace {

using Dims = adaptobs::DynamicDimensions<double>;
namespace satellite = adaptobs::examples::satellite;

adaptobs::DiscreteLtiModel<Dims> model() {
  const auto m = satellite::model<double>();
  return {m.system().A, m.system().B, m.system().C, 2};
}

template <class Observer>
double nanoseconds_per_sample(Observer observer, const std::vector<adaptobs::DiscreteSample<Dims>>& samples) {
  double best = 1e300;
  for (int repetition = 0; repetition < 5; ++repetition) {
    Observer o = observer;
    const auto start = std::chrono::steady_clock::now();
    int rejected = 0;
    std::vector<double> theta(samples.size() * 2);
    for (std::size_t k = 0; k < samples.size(); ++k) {
      rejected += o.update(samples[k]) != adaptobs::UpdateStatus::accepted;
      theta[2 * k] = o.parameters()(0);  // what run() stores of each sample
      theta[2 * k + 1] = o.parameters()(1);
    }
    const double ns = std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - start).count();
    if (rejected != 0 || theta.back() == 0) std::abort();
    best = std::min(best, ns / double(samples.size()));
  }
  return best;
}

}  // namespace

int main(int argc, char** argv) {
  const long n = argc > 1 ? std::atol(argv[1]) : 100000;
  auto plant = satellite::make_plant<double>(0.01, 2003);
  std::vector<adaptobs::DiscreteSample<Dims>> samples;
  for (long k = 0; k < n; ++k) {
    samples.push_back({plant.sample().u, plant.sample().y, plant.sample().Psi});
    plant.advance();
  }
  const adaptobs::GuyaderZhangObserver gz(model(), Eigen::MatrixXd(satellite::paper_gain<double>()), satellite::mu,
                                          Eigen::VectorXd(satellite::initial_state_estimate<double>()),
                                          Eigen::VectorXd(satellite::initial_parameter_estimate<double>()));
  Eigen::MatrixXd p0 = Eigen::MatrixXd::Zero(6, 6);
  p0.diagonal() << 0.1, 1e-4, 0.1, 1e-4, 1.0, 1.0;
  Eigen::MatrixXd q = Eigen::MatrixXd::Zero(6, 6);
  q.diagonal().head(4).setConstant(1e-10);
  const adaptobs::AugmentedKalmanFilter akf(model(), Eigen::VectorXd(satellite::initial_state_estimate<double>()),
                                            Eigen::VectorXd(satellite::initial_parameter_estimate<double>()),
                                            {p0, q, Eigen::MatrixXd::Identity(2, 2) * 1e-4});
  std::printf("GuyaderZhangObserver %.2f\n", nanoseconds_per_sample(gz, samples));
  std::printf("AugmentedKalmanFilter %.2f\n", nanoseconds_per_sample(akf, samples));
}
