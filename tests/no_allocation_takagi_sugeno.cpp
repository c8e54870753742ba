// No heap allocation inside fixed-size updates of the Takagi–Sugeno observer
// for time-varying parameters (21), with the leakage K_θ; the observer contract
// checks constant parameters (65).

#include <adaptobs/observers/takagi_sugeno.hpp>
#include <adaptobs/simulation/plant.hpp>

#include "models/wwtp.hpp"
#include "support/allocation_counter.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace {

using adaptobs::testing::allocations_during;
namespace wwtp = adaptobs::examples::wwtp;

TEST(NoAllocation, TakagiSugenoWithLeakageFixedSizeUpdates) {
  const auto samples = adaptobs::record_samples(wwtp::make_plant<double>(0.1), 5000);
  auto gains = wwtp::paper_gains<double>();
  gains.K_theta = wwtp::Vector1<double>(1e-3);
  adaptobs::TakagiSugenoObserver observer(wwtp::model<double>(), gains, wwtp::initial_state_estimate<double>(),
                                          wwtp::initial_parameter_estimate<double>());
  int rejected = 0;
  EXPECT_EQ(allocations_during([&] {
              for (const auto& s : samples) rejected += observer.update(s) != adaptobs::UpdateStatus::accepted;
            }),
            0);
  EXPECT_EQ(rejected, 0);
}

// The premise variables of the plant, from run-time-sized estimates, as a
// fixed-size vector: the function itself allocates nothing.
struct FixedSizePremises {
  Eigen::Vector2d operator()(const Eigen::VectorXd& x, const Eigen::VectorXd& u, const Eigen::VectorXd&) const {
    return {u(0), x(0) / (x(1) + wwtp::b)};
  }
};

// With run-time sizes and premise count the model returned its premise
// variables as a new dynamic vector: one allocation per update.
TEST(NoAllocation, TakagiSugenoDynamicSizeUpdates) {
  using Dims = adaptobs::DynamicDimensions<double>;
  using Model = adaptobs::TakagiSugenoModel<Dims, Eigen::Dynamic, FixedSizePremises>;
  const auto fixed_model = wwtp::model<double>();
  std::vector<adaptobs::TakagiSugenoVertex<Dims>> vertices;
  for (adaptobs::Index i = 0; i < fixed_model.vertex_count(); ++i)
    vertices.push_back({fixed_model.A(i), fixed_model.B(i)});
  const auto zb = wwtp::premise_bounds<double>();
  const auto tb = wwtp::parameter_bounds<double>();
  const Model model(vertices, Eigen::MatrixXd(fixed_model.C()), {}, {zb.lower, zb.upper}, {tb.lower, tb.upper});
  const auto fixed_gains = wwtp::paper_gains<double>();
  adaptobs::TakagiSugenoGains<Dims> gains;
  for (std::size_t i = 0; i < fixed_gains.L.size(); ++i) {
    gains.L.emplace_back(fixed_gains.L[i]);
    gains.K.emplace_back(fixed_gains.K[i]);
  }
  adaptobs::TakagiSugenoObserver observer(model, gains, Eigen::VectorXd(wwtp::initial_state_estimate<double>()),
                                          Eigen::VectorXd(wwtp::initial_parameter_estimate<double>()));
  std::vector<adaptobs::InputOutputSample<Dims>> samples;
  for (const auto& s : adaptobs::record_samples(wwtp::make_plant<double>(0.1), 2000))
    samples.push_back({Eigen::VectorXd(s.u), Eigen::VectorXd(s.y)});
  int rejected = 0;
  EXPECT_EQ(allocations_during([&] {
              for (const auto& s : samples) rejected += observer.update(s) != adaptobs::UpdateStatus::accepted;
            }),
            0);
  EXPECT_EQ(rejected, 0);
  EXPECT_EQ(observer.step(), 2000);
}

}  // namespace
