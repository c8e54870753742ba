// No heap allocation in the per-sample work of the Guiro–Iggidr–Ngom–Touré
// observer for fixed sizes: the update itself, and the regressor integrals
// that recompute Ψ_k = e^{AT}H_k each period (quadrature and polynomial form).

#include <adaptobs/design/guiro_gains.hpp>
#include <adaptobs/models/regressor_integral.hpp>
#include <adaptobs/observers/guiro.hpp>
#include <adaptobs/simulation/plant.hpp>

#include "models/guiro.hpp"
#include "support/allocation_counter.hpp"

#include <gtest/gtest.h>

#include <array>
#include <vector>

namespace {

using adaptobs::testing::allocations_during;
namespace g = adaptobs::examples::guiro;

TEST(NoAllocation, GuiroFixedSizeUpdatesAndRegressorIntegrals) {
  const auto model = g::model<double>();
  const auto gains = adaptobs::design_guiro_gains(model.system().A, model.system().C, g::closed_form_H<double>(0),
                                                  g::requested_poles());
  adaptobs::GuiroObserver observer(model, gains.K, gains.Gamma, g::initial_state_estimate<double>(),
                                   g::initial_parameter_estimate<double>());
  adaptobs::RegressorIntegral<double, 2, 1> integral(g::continuous_dynamics<double>(), g::period);
  auto samples = adaptobs::record_samples(g::make_plant<double>(), 200);
  adaptobs::SampledRegressor<double, 2, 1> h;
  int rejected = 0;
  bool converged = true;
  const long count = allocations_during([&] {
    for (std::size_t k = 0; k < samples.size(); ++k) {
      auto sample = samples[k];
      converged = integral.integrate(g::Regressor{}, double(k) * g::period, h) && converged;
      sample.Psi = h.Psi;
      rejected += observer.update(sample) != adaptobs::UpdateStatus::accepted;
    }
  });
  EXPECT_EQ(count, 0);
  EXPECT_EQ(rejected, 0);
  EXPECT_TRUE(converged);

  // A kink forces bisection: still no allocation.
  const auto kink = [](double t) { return Eigen::Vector2d(std::abs(t - 0.3), 0.0); };
  EXPECT_EQ(allocations_during([&] { converged = integral.integrate(kink, 0.0, h); }), 0);
  EXPECT_TRUE(converged);

  const adaptobs::PolynomialRegressorIntegral<double, 2, 1> polynomial(g::continuous_dynamics<double>(), g::period, 1);
  const std::array<Eigen::Vector2d, 2> coefficients{Eigen::Vector2d(1, 0), Eigen::Vector2d(0.5, 0)};
  EXPECT_EQ(allocations_during([&] { polynomial.integrate(coefficients, h); }), 0);
}

}  // namespace
