// The baseline of benchmarks/python/bench_python.py: the observers it times
// from Python, with run-time sizes, driven by a plain C++ loop over recorded
// samples that keeps what the package's run() returns (state, parameters,
// output error, status, the observer's diagnostics). Prints nanoseconds per
// sample, the minimum of five passes, in CPU time of the process (std::clock), as
// the Python benchmarks time their own single-threaded cases: on a shared machine
// far steadier than the wall clock.
//
//   c++ -std=c++20 -O3 -DNDEBUG -Iinclude -Iexamples $(pkg-config --cflags eigen3) \
//       benchmarks/python/cxx_dynamic_loop.cpp -o cxx_dynamic_loop && ./cxx_dynamic_loop 100000

#include <adaptobs/baselines/augmented_kalman.hpp>
#include <adaptobs/design/canonical_forms.hpp>
#include <adaptobs/design/positive_real.hpp>
#include <adaptobs/observers/bastin_gevers.hpp>
#include <adaptobs/observers/dey_bhasin.hpp>
#include <adaptobs/observers/guyader_zhang.hpp>

#include "models/dey_bhasin.hpp"
#include "models/satellite.hpp"
#include "models/siso_third_order.hpp"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <vector>

namespace {

using Dims = adaptobs::DynamicDimensions<double>;
constexpr int X = Eigen::Dynamic;

// What run() keeps of each sample.
struct Record {
  std::vector<double> x, theta, error, diagnostics;
  std::vector<signed char> status;
  template <class Observer>
  void keep(const Observer& o, adaptobs::UpdateStatus s) {
    status.push_back(static_cast<signed char>(s));
    x.insert(x.end(), o.state().data(), o.state().data() + o.state().size());
    theta.insert(theta.end(), o.parameters().data(), o.parameters().data() + o.parameters().size());
    error.insert(error.end(), o.output_error().data(), o.output_error().data() + o.output_error().size());
  }
};

template <class Observer, class Sample, class Diagnose>
double nanoseconds_per_sample(const Observer& observer, const std::vector<Sample>& samples, Diagnose diagnose) {
  double best = 1e300;
  for (int pass = 0; pass < 5; ++pass) {
    Observer o = observer;
    Record record;
    record.x.reserve(samples.size() * 8);
    record.theta.reserve(samples.size() * 16);
    record.error.reserve(samples.size() * 2);
    record.status.reserve(samples.size());
    record.diagnostics.reserve(samples.size() * 2);
    const std::clock_t start = std::clock();
    for (const Sample& sample : samples) {
      record.keep(o, o.update(sample));
      diagnose(o, record.diagnostics);
    }
    const double ns = 1e9 * double(std::clock() - start) / CLOCKS_PER_SEC;
    if (std::count(record.status.begin(), record.status.end(), 0) != static_cast<long>(samples.size())) std::abort();
    best = std::min(best, ns / double(samples.size()));
  }
  return best;
}

void guyader_zhang_and_augmented_kalman(long n) {
  namespace satellite = adaptobs::examples::satellite;
  auto plant = satellite::make_plant<double>(0.01, 2003);
  std::vector<adaptobs::DiscreteSample<Dims>> samples;
  for (long k = 0; k < n; ++k, plant.advance())
    samples.push_back({plant.sample().u, plant.sample().y, plant.sample().Psi});
  const auto fixed = satellite::model<double>();
  const adaptobs::DiscreteLtiModel<Dims> model(fixed.system().A, fixed.system().B, fixed.system().C, 2);
  const Eigen::VectorXd x0 = satellite::initial_state_estimate<double>();
  const Eigen::VectorXd theta0 = satellite::initial_parameter_estimate<double>();
  const adaptobs::GuyaderZhangObserver gz(model, Eigen::MatrixXd(satellite::paper_gain<double>()), satellite::mu, x0,
                                          theta0);
  std::printf("GuyaderZhangObserver %.2f\n",
              nanoseconds_per_sample(gz, samples, [](const auto& o, std::vector<double>& d) {
                d.push_back(o.assumption2_norm());
                d.push_back(o.excitation_level().value_or(0.0));
              }));
  Eigen::MatrixXd p0 = Eigen::MatrixXd::Zero(6, 6);
  p0.diagonal() << 0.1, 1e-4, 0.1, 1e-4, 1.0, 1.0;
  Eigen::MatrixXd q = Eigen::MatrixXd::Zero(6, 6);
  q.diagonal().head(4).setConstant(1e-10);
  const adaptobs::AugmentedKalmanFilter akf(model, x0, theta0, {p0, q, Eigen::MatrixXd::Identity(2, 2) * 1e-4});
  std::printf("AugmentedKalmanFilter %.2f\n", nanoseconds_per_sample(akf, samples, [](const auto&, auto&) {}));
}

void dey_bhasin(long n) {
  namespace mimo = adaptobs::examples::dey_bhasin::mimo;
  auto plant = mimo::make_plant(mimo::RichInput{});
  using Observer = adaptobs::DeyBhasinObserver<double, X, X, X>;
  std::vector<Observer::Sample> samples;
  for (long k = 0; k < n; ++k, plant.advance()) samples.push_back({plant.sample().u, plant.sample().y});
  const Observer observer(Eigen::VectorXd(mimo::f()), Eigen::VectorXd(mimo::x_hat0()), Eigen::VectorXd(mimo::a_hat0()),
                          Eigen::MatrixXd(mimo::B_hat0()),
                          {.k0 = mimo::k0, .kmin = mimo::kmin, .R = Eigen::MatrixXd::Identity(2, 2)});
  std::printf("DeyBhasinObserver %.2f\n",
              nanoseconds_per_sample(observer, samples, [](const auto& o, std::vector<double>& d) {
                d.push_back(static_cast<double>(o.law().reset_count()));
              }));
}

void bastin_gevers(long n) {
  namespace siso = adaptobs::examples::siso;
  auto plant = siso::make_plant<double>();
  std::vector<adaptobs::ContinuousSample<Dims>> samples;
  for (long k = 0; k < n; ++k) {
    if (k > 0) plant.advance();
    const auto& s = plant.sample();
    adaptobs::ContinuousSample<Dims> sample{s.t, s.u, s.y, std::nullopt};
    if (s.midpoint) sample.midpoint = {{s.midpoint->u, s.midpoint->y}};
    samples.push_back(sample);
  }
  const auto phi = [](double t) { return Eigen::MatrixXd(siso::Regressor{}.operator()<double>(t)); };
  const auto model = adaptobs::make_continuous_lti_model<Dims>(siso::dynamics<double>(), siso::input_matrix<double>(),
                                                               siso::output_matrix<double>(), phi, 2);
  adaptobs::Polynomial<double> zeros(3);
  zeros << 1, 4, 3;
  const auto transform =
      adaptobs::bastin_gevers_form<Dims>(siso::dynamics<double>(), siso::output_matrix<double>(), zeros);
  const auto so = transform.apply(model.system());
  const Eigen::VectorXd k = adaptobs::spr_injection_gain(so.Ao, so.Co, Eigen::VectorXd(Eigen::Vector3d(1, 0, 0)), 2.0);
  const auto observer = adaptobs::make_bastin_gevers_observer(
      model, transform, Eigen::MatrixXd(k), Eigen::MatrixXd(5.0 * Eigen::MatrixXd::Identity(2, 2)),
      Eigen::VectorXd(Eigen::VectorXd::Zero(3)), Eigen::VectorXd(Eigen::VectorXd::Zero(2)),
      {.sampling = {.substeps = 1,
                    .input = adaptobs::SignalReconstruction::quadratic,
                    .output = adaptobs::SignalReconstruction::quadratic}});
  std::printf("BastinGeversObserver %.2f\n",
              nanoseconds_per_sample(observer, samples, [](const auto& o, std::vector<double>& d) {
                d.push_back(o.excitation_level().value_or(0.0));
              }));
}

}  // namespace

int main(int argc, char** argv) {
  const long n = argc > 1 ? std::atol(argv[1]) : 100000;
  guyader_zhang_and_augmented_kalman(n);
  dey_bhasin(std::min(n, 20000L));  // the example's input is rich; its estimates stay finite this long
  bastin_gevers(n);
}
