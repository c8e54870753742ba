// Takagi–Sugeno polytopic adaptive observer on the waste water plant of
// Srinivasarengan et al. (2018), §6 (2 states, 8 vertices): one update with constant (65) and time-varying
// (21) parameters, fixed and dynamic sizes.

#include <adaptobs/observers/takagi_sugeno.hpp>
#include <adaptobs/simulation/plant.hpp>

#include "bench_support.hpp"
#include "models/wwtp.hpp"

#include <vector>

namespace {

using adaptobs::Index;
using adaptobs::bench::SampleRing;
namespace wwtp = adaptobs::examples::wwtp;

SampleRing<adaptobs::InputOutputSample<wwtp::Dims<double>>> wwtp_ring() {
  return SampleRing(adaptobs::record_samples(wwtp::make_plant<double>(0.1), 1000));
}

void BM_TakagiSugeno_WWTP(benchmark::State& state) {
  adaptobs::TakagiSugenoObserver observer(wwtp::model<double>(), wwtp::paper_gains<double>(),
                                          wwtp::initial_state_estimate<double>(),
                                          wwtp::initial_parameter_estimate<double>());
  auto ring = wwtp_ring();
  adaptobs::bench::time_updates(state, observer, ring);
}
BENCHMARK(BM_TakagiSugeno_WWTP);

// No output: the state through the weighted vertices, θ̂ held.
void BM_TakagiSugeno_WWTP_TimeUpdate(benchmark::State& state) {
  adaptobs::TakagiSugenoObserver observer(wwtp::model<double>(), wwtp::paper_gains<double>(),
                                          wwtp::initial_state_estimate<double>(),
                                          wwtp::initial_parameter_estimate<double>());
  auto ring = wwtp_ring();
  adaptobs::bench::time_masked_updates(state, observer, ring, adaptobs::OutputMask<wwtp::Dims<double>>(false));
}
BENCHMARK(BM_TakagiSugeno_WWTP_TimeUpdate);

void BM_TakagiSugeno_WWTP_TimeVarying(benchmark::State& state) {
  auto gains = wwtp::paper_gains<double>();
  gains.K_theta = wwtp::Vector1<double>(1e-3);
  adaptobs::TakagiSugenoObserver observer(wwtp::model<double>(), gains, wwtp::initial_state_estimate<double>(),
                                          wwtp::initial_parameter_estimate<double>());
  auto ring = wwtp_ring();
  adaptobs::bench::time_updates(state, observer, ring);
}
BENCHMARK(BM_TakagiSugeno_WWTP_TimeVarying);

struct DynamicPremises {
  Eigen::VectorXd operator()(const Eigen::VectorXd& x, const Eigen::VectorXd& u, const Eigen::VectorXd&) const {
    Eigen::VectorXd z(2);
    z << u(0), x(0) / (x(1) + wwtp::b);
    return z;
  }
};

// The same observer with every size dynamic (the premise function returns a heap vector).
void BM_TakagiSugeno_WWTP_Dynamic(benchmark::State& state) {
  using DD = adaptobs::DynamicDimensions<double>;
  const auto fixed = wwtp::model<double>();
  std::vector<adaptobs::TakagiSugenoVertex<DD>> vertices;
  for (Index i = 0; i < fixed.vertex_count(); ++i) vertices.push_back({fixed.A(i), fixed.B(i)});
  const auto zb = fixed.premise_bounds();
  const auto tb = fixed.parameter_bounds();
  const adaptobs::TakagiSugenoModel<DD, Eigen::Dynamic, DynamicPremises> model(
      vertices, Eigen::MatrixXd(fixed.C()), {}, {zb.lower, zb.upper}, {tb.lower, tb.upper});
  adaptobs::TakagiSugenoGains<DD> gains;
  for (const auto& l : wwtp::paper_gains<double>().L) gains.L.emplace_back(l);
  for (const auto& k : wwtp::paper_gains<double>().K) gains.K.emplace_back(k);
  adaptobs::TakagiSugenoObserver observer(model, gains, Eigen::VectorXd(wwtp::initial_state_estimate<double>()),
                                          Eigen::VectorXd(wwtp::initial_parameter_estimate<double>()));
  auto fixed_ring = wwtp_ring();
  std::vector<adaptobs::InputOutputSample<DD>> samples;
  for (int k = 0; k < 1000; ++k) {
    const auto& s = fixed_ring.next();
    samples.push_back({s.u, s.y});
  }
  SampleRing ring(std::move(samples));
  adaptobs::bench::time_updates(state, observer, ring);
}
BENCHMARK(BM_TakagiSugeno_WWTP_Dynamic);

}  // namespace
