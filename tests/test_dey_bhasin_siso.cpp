// Dey–Bhasin observer on the SISO comparison of Dey & Bhasin (2022) §5: the Suzuki et
// al. exponential-forgetting baseline losing boundedness while resetting does
// not, float and double, and the observer with another adaptation law. The
// covariance over 10⁶ steps is in test_dey_bhasin_long_runs.cpp.

#include <adaptobs/adaptation/covariance_resetting.hpp>
#include <adaptobs/adaptation/exponential_forgetting.hpp>
#include <adaptobs/adaptation/normalized_gradient.hpp>
#include <adaptobs/core/observer.hpp>
#include <adaptobs/observers/dey_bhasin.hpp>

#include "models/dey_bhasin.hpp"
#include "support/eigen_testing.hpp"
#include "support/observer_contract.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

namespace {

using adaptobs::Index;
using adaptobs::UpdateStatus;
namespace db = adaptobs::examples::dey_bhasin;
namespace siso = db::siso;

using Vector4 = Eigen::Vector4d;
static_assert(adaptobs::Observer<siso::Observer<double>>);
static_assert(adaptobs::Observer<siso::Suzuki<double>>);

// §5, figures 4–5: without a persistently exciting regressor exponential forgetting
// (λ = √0.5) winds its covariance up by 1/λ per step until it overflows, while
// covariance resetting keeps everything bounded.
// A first sample whose measurement z = y − C F⁰ x̂₀ overflows (y and x̂₀ near
// the range's ends with opposite signs): the step is refused, not accepted
// with an infinite output error, and later samples are still accepted.
TEST(DeyBhasinSiso, AStepWhoseMeasurementOverflowsIsRefusedWithNothingChanged) {
  using Observer = adaptobs::DeyBhasinObserver<double, 2, 1, 1>;
  const Eigen::Vector2d f(0.5, -0.06);
  Observer observer(f, Eigen::Vector2d(-1.5e308, 0), f, Eigen::Vector2d::Zero(),
                    {.k0 = 100, .kmin = 1e-4, .R = Eigen::Matrix<double, 1, 1>::Identity()});
  using Vector1 = Eigen::Matrix<double, 1, 1>;
  EXPECT_EQ(observer.update(Observer::Sample{Vector1(0), Vector1(1.5e308)}), UpdateStatus::nonfinite_result);
  EXPECT_EQ(observer.step(), 0);
  EXPECT_TRUE(observer.output_error().allFinite());
  EXPECT_TRUE(observer.measurement().allFinite());
  EXPECT_EQ(observer.update(Observer::Sample{Vector1(0), Vector1(1)}), UpdateStatus::accepted);
}

TEST(DeyBhasinSiso, SuzukiBaselineLosesBoundednessWhileResettingDoesNot) {
  constexpr Index steps = 2500;
  auto resetting = siso::make_observer();
  auto suzuki = siso::make_suzuki();
  // The raw law, fed with the same regressor and always committed (plain IEEE arithmetic).
  adaptobs::ExponentialForgettingRls<double, 4, 1> raw(resetting.parameters(), siso::suzuki_options());
  auto plant = siso::make_plant();
  const Vector4 p = resetting.parameters_of(siso::a(), siso::B());
  const double initial_error = (p - resetting.parameters()).norm();
  EXPECT_NEAR(initial_error, 1.725630, 1e-6);

  Index first_rejected = -1, raw_covariance_nonfinite = -1, raw_estimate_nonfinite = -1;
  double max_resetting_error = initial_error, max_resetting_gamma = 0, growth_at_1000 = 0;
  double previous_max = 0, min_ratio = 1e9, max_ratio = 0;
  Vector4 frozen_parameters;
  for (Index t = 0; t < steps; ++t) {
    ASSERT_EQ(resetting.update(plant.sample()), UpdateStatus::accepted) << "step " << t;
    const UpdateStatus status = suzuki.update(plant.sample());
    if (t > 0) {
      (void)raw.propose(resetting.regressor(), resetting.measurement());
      raw.commit();
    }
    if (raw_covariance_nonfinite < 0 && !raw.covariance().allFinite()) raw_covariance_nonfinite = t;
    if (raw_estimate_nonfinite < 0 && !raw.parameters().allFinite()) raw_estimate_nonfinite = t;
    if (first_rejected < 0) {
      if (status == UpdateStatus::accepted) {
        // Until it breaks, the library's observer is the raw law to the last bit.
        ASSERT_TRUE(adaptobs::testing::bitwise_equal(suzuki.parameters(), raw.parameters())) << "step " << t;
        ASSERT_TRUE(adaptobs::testing::bitwise_equal(suzuki.law().covariance(), raw.covariance())) << "step " << t;
      } else {
        first_rejected = t;
        frozen_parameters = suzuki.parameters();
        EXPECT_EQ(status, UpdateStatus::nonfinite_result);
      }
    } else {
      // From then on every update is refused and the estimates stay as they were.
      EXPECT_EQ(status, UpdateStatus::nonfinite_result) << "step " << t;
      EXPECT_TRUE(adaptobs::testing::bitwise_equal(suzuki.parameters(), frozen_parameters));
    }
    const double largest = suzuki.law().covariance().cwiseAbs().maxCoeff();
    if (t > 500 && t <= 1000) {
      min_ratio = std::min(min_ratio, largest / previous_max);
      max_ratio = std::max(max_ratio, largest / previous_max);
    }
    if (t == 1000) growth_at_1000 = largest;
    previous_max = largest;
    max_resetting_error = std::max(max_resetting_error, (p - resetting.parameters()).norm());
    max_resetting_gamma = std::max(max_resetting_gamma, resetting.law().covariance().cwiseAbs().maxCoeff());
    plant.advance();
  }
  // Forgetting: Γ grows as λ^{-t} = √2^t, then overflows; the observer flags it and freezes.
  EXPECT_GT(min_ratio, 1.414);
  EXPECT_LT(max_ratio, 1.415);
  EXPECT_GT(growth_at_1000, 1e100);
  EXPECT_GE(first_rejected, 2000);
  EXPECT_LE(first_rejected, 2100);
  EXPECT_EQ(raw_covariance_nonfinite, first_rejected);
  EXPECT_GE(raw_estimate_nonfinite, first_rejected);
  EXPECT_LE(raw_estimate_nonfinite, first_rejected + 5);
  EXPECT_TRUE(suzuki.parameters().allFinite() && suzuki.state().allFinite());
  // Resetting: everything accepted, Γ ≤ k0, and ‖p̃_t‖ never exceeds the corrected
  // theorem-5 bound, here ‖p̃_0‖ since x̃_0 = 0.
  EXPECT_LE(max_resetting_gamma, siso::k0);
  EXPECT_LE(max_resetting_error, initial_error + 1e-9);
  const Eigen::VectorXd normalized = db::normalized_estimates(resetting, siso::a(), siso::B());
  EXPECT_LT((normalized.array() - 1).abs().maxCoeff(), 1e-3);
  RecordProperty("suzuki_first_rejected_step", std::to_string(first_rejected));
}

// With λ = 0.5 (the weighting factor entering squared) the same failure comes twice as early.
TEST(DeyBhasinSiso, SuzukiWithHalfForgettingFailsTwiceAsEarly) {
  auto suzuki = siso::make_suzuki(0.5);
  auto plant = siso::make_plant();
  Index first_rejected = -1;
  for (Index t = 0; t < 1200 && first_rejected < 0; ++t) {
    if (suzuki.update(plant.sample()) != UpdateStatus::accepted) first_rejected = t;
    plant.advance();
  }
  EXPECT_GE(first_rejected, 1000);
  EXPECT_LE(first_rejected, 1100);
}

// Two sinusoids: a sufficiently rich input for the SISO example (4 parameters).
template <typename S>
struct TwoSines {
  Eigen::Matrix<S, 1, 1> operator()(Index k) const {
    const double t = double(k);
    return Eigen::Matrix<S, 1, 1>(S(std::sin(0.2 * t) + std::sin(0.9 * t)));
  }
};

ADAPTOBS_TYPED_SUITE_IN_BOTH_PRECISIONS(DeyBhasinSisoTyped);

// In single precision k0/kmin must stay well inside 1/ε: k0 = 100, kmin = 0.01.
TYPED_TEST(DeyBhasinSisoTyped, RichInputConvergesInBothPrecisions) {
  using S = TypeParam;
  auto observer = siso::make_observer<S>(siso::law_options<S>(S(100), S(0.01)));
  auto plant = siso::make_plant<S>(TwoSines<S>{});
  for (Index t = 0; t < 2000; ++t) {
    ASSERT_EQ(observer.update(plant.sample()), UpdateStatus::accepted) << "step " << t;
    plant.advance();
  }
  const Eigen::VectorXd normalized = db::normalized_estimates(observer, siso::a<double>(), siso::B<double>());
  const double tolerance = std::is_same_v<S, float> ? 1e-2 : 1e-8;
  EXPECT_LT((normalized.array() - 1).abs().maxCoeff(), tolerance);
  const S state_tolerance = std::is_same_v<S, float> ? S(1e-2) : S(1e-8);
  EXPECT_LT((observer.state() - plant.state()).norm(), state_tolerance);  // x̂_{T|T−1} against x_T
}

// The observer takes any adaptation law: the normalized gradient never lets ‖p̃‖
// grow (x̃_0 = 0, so the regression is exact) and converges, more slowly than RLS.
TEST(DeyBhasinSiso, WorksWithTheNormalizedGradientLaw) {
  using GradientObserver = adaptobs::DeyBhasinObserver<double, 2, 1, 1, adaptobs::NormalizedGradient>;
  static_assert(adaptobs::Observer<GradientObserver>);
  GradientObserver observer(siso::f(), siso::x0(), siso::a_hat0(), siso::B_hat0(), {.mu = 1.0, .offset = 1.0});
  auto plant = siso::make_plant(TwoSines<double>{});
  const Vector4 p = observer.parameters_of(siso::a(), siso::B());
  double previous = (p - observer.parameters()).norm();
  const double initial = previous;
  for (Index t = 0; t < 20000; ++t) {
    ASSERT_EQ(observer.update(plant.sample()), UpdateStatus::accepted);
    const double error = (p - observer.parameters()).norm();
    ASSERT_LE(error, previous * (1 + 1e-12) + 1e-15) << "step " << t;
    previous = error;
    plant.advance();
  }
  EXPECT_LT(previous, 1e-3 * initial);
}

// The observer contract (support/observer_contract.hpp) on the SISO example:
// the proposed observer (covariance resetting) and the Suzuki et al. baseline
// (exponential forgetting).
template <class Design>
struct DeyBhasinSisoContract {
  using Observer = decltype(Design::observer());
  using Sample = typename Observer::Sample;
  static constexpr const char* name = Design::name;
  static Observer make() { return Design::observer(); }
  static std::vector<Sample> samples() {
    return adaptobs::testing::first_samples<Sample>(siso::make_plant(), 40,
                                                    [](const auto& s) { return Sample{s.u, s.y}; });
  }
  static auto readings(const Observer& o) {
    return std::make_tuple(o.state(), o.current_state(), o.parameters(), o.regressor(), o.measurement(),
                           o.filter_bank(), o.law().covariance(), o.step());
  }
  static typename Observer::Output expected_output_error(const Observer& before, const Observer&, const Sample& s) {
    return s.y - db::canonical_output_matrix<double>(siso::order, 1) * before.state();
  }
};
struct ResettingDesign {
  static constexpr const char* name = "CovarianceResetting";
  static auto observer() { return siso::make_observer(); }
};
struct SuzukiDesign {
  static constexpr const char* name = "Suzuki";
  static auto observer() { return siso::make_suzuki(); }
};

}  // namespace

ADAPTOBS_OBSERVER_CONTRACT(DeyBhasinSiso, DeyBhasinSisoContract<ResettingDesign>, DeyBhasinSisoContract<SuzukiDesign>);
