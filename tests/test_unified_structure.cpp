// The structure of the unified formulation (Zhang 2005), checked along
// trajectories: the identity (4a) for each algorithm's (F, G, H) and the
// paper's z-form observer equations, Lyapunov functions that never increase,
// joint plant–observer integration to machine precision, and the discrete
// Guyader–Zhang observer as the Euler limit of Algorithm 4. Each integrates
// thousands of small steps: part of test_long_runs, which the sanitizer build
// compiles with optimization (tests/CMakeLists.txt). The designs come from the
// library adaptobs_example_designs (examples/models/unified_designs.hpp).

#include <adaptobs/design/positive_real.hpp>
#include <adaptobs/observers/bastin_gevers.hpp>
#include <adaptobs/observers/besancon.hpp>
#include <adaptobs/observers/guyader_zhang.hpp>
#include <adaptobs/observers/marino_tomei.hpp>
#include <adaptobs/observers/zhang_continuous.hpp>
#include <adaptobs/simulation/continuous_plant.hpp>
#include <adaptobs/simulation/joint_integration.hpp>

#include "models/periodic_mimo.hpp"
#include "models/siso_third_order.hpp"
#include "support/eigen_testing.hpp"
#include "unified_fixtures.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace {

using adaptobs::Index;
using adaptobs::UpdateStatus;
using namespace adaptobs::testing::unified;

// ---------------------------------------------------------------------------
// (4a) along a trajectory, and the paper's z-form observer equations, for each
// algorithm's (F, G, H): plant and observer integrated jointly (h = 1e-3),
// derivatives by central differences (error O(h²)).

template <class Observer, class Plant, class Bracket>
void check_transformed_equations(Observer& observer, Plant& plant, double duration, Bracket&& expected_bracket) {
  constexpr double h = 1e-3;
  adaptobs::JointIntegration joint(plant, observer);
  const auto& st = observer.algorithm().static_transform;
  const auto& dt = observer.algorithm().dynamic_transform;
  const auto theta = plant.parameters();
  struct Point {
    typename Observer::State z, zhat;
  };
  const auto point = [&] {
    return Point{typename Observer::State(st.T() * plant.state() - observer.omega() * theta),
                 observer.transformed_estimate_z()};
  };
  Point previous = point();
  joint.step(h);
  Point current = point();
  double worst_4a = 0, worst_observer = 0, worst_bracket = 0, scale = 0;
  const Index steps = Index(duration / h);
  for (Index k = 1; k < steps; ++k) {
    const double t = joint.time();
    const auto Xi = observer.filter();
    const auto Omega = observer.omega();
    const auto so = observer.transformed_system(t);
    const auto& model = observer.model();
    typename Observer::Input u;
    typename Observer::Output y;
    plant.signals(t, plant.state(), u, y);
    typename Observer::RegressorMatrix Psi;
    st.regressor(model.regressor(t, u, y), Psi);
    typename Observer::State phi;
    st.drive(so, u, y, phi);
    const typename Observer::FilterMatrix F = dt.filter_matrix(so.Ao);
    const auto M = dt.bracket(so.Ao, F, Xi, Psi);
    // The bracket of each algorithm has the closed form printed in §III.
    worst_bracket = std::max(worst_bracket, (M - expected_bracket(so, Xi, Psi)).cwiseAbs().maxCoeff());
    // Observer equation in the paper's coordinates: ẑ' = A_o ẑ + φ + M θ̂ + L (y − C_o ẑ − C_o Ω θ̂).
    typename Observer::GainMatrix L;
    observer.algorithm().injection_gain(so, t, L);
    const auto thetahat = observer.parameters();
    const Point next_guard = current;
    joint.step(h);
    const Point next = point();
    const typename Observer::State dz = (next.z - previous.z) / (2 * h);
    const typename Observer::State dzhat = (next.zhat - previous.zhat) / (2 * h);
    // Evaluate at the middle point (time t): rebuild from `current`.
    const typename Observer::State rhs_4a = so.Ao * current.z + phi + M * theta;
    const typename Observer::Output eps = y - so.Co * current.zhat - so.Co * Omega * thetahat;
    const typename Observer::State rhs_obs = so.Ao * current.zhat + phi + M * thetahat + L * eps;
    worst_4a = std::max(worst_4a, (dz - rhs_4a).cwiseAbs().maxCoeff());
    worst_observer = std::max(worst_observer, (dzhat - rhs_obs).cwiseAbs().maxCoeff());
    scale = std::max(scale, rhs_4a.cwiseAbs().maxCoeff());
    previous = next_guard;
    current = next;
  }
  EXPECT_LT(worst_bracket, 1e-12 * std::max(1.0, scale));
  EXPECT_LT(worst_4a, 1e-4 * std::max(1.0, scale));
  EXPECT_LT(worst_observer, 1e-4 * std::max(1.0, scale));
  EXPECT_GT(scale, 0.1);
}

TEST(UnifiedFormulation, Equation4aAndTheObserverEquationsAlongTrajectories) {
  {
    auto observer = bastin_gevers_observer<double>();
    auto plant = siso::make_plant<double>();
    // γ ξᵀ with γ = e1, ξᵀ = a12 Ξ + Ψ1.
    check_transformed_equations(observer, plant, 5.0, [](const auto& so, const auto& Xi, const auto& Psi) {
      Eigen::Matrix<double, 3, 2> m = Eigen::Matrix<double, 3, 2>::Zero();
      m.row(0) = so.Ao.row(0).tail(2) * Xi + Psi.row(0);
      return m;
    });
  }
  {
    auto observer = marino_tomei_observer<double>();
    auto plant = siso::make_plant<double>();
    // γ ξᵀ with γ = (1, 3, 2), ξᵀ = Ξ1 + Ψ1.
    check_transformed_equations(observer, plant, 5.0, [](const auto&, const auto& Xi, const auto& Psi) {
      return Eigen::Matrix<double, 3, 2>(Eigen::Vector3d(1, 3, 2) * (Xi.row(0) + Psi.row(0)));
    });
  }
  {
    auto observer = besancon_observer<double>();
    auto plant = periodic::make_plant<double>();
    // [I; 0](A12 Ξ + Ψ1).
    check_transformed_equations(observer, plant, 5.0, [](const auto& so, const auto& Xi, const auto& Psi) {
      Eigen::Matrix<double, 4, 2> m = Eigen::Matrix<double, 4, 2>::Zero();
      m.topRows(2) = so.Ao.topRightCorner(2, 2) * Xi + Psi.topRows(2);
      return m;
    });
  }
  {
    auto observer = zhang_observer<double>(50.0);
    auto plant = periodic::make_plant<double>();
    check_transformed_equations(observer, plant, 5.0, [](const auto&, const auto&, const auto&) {
      return Eigen::Matrix<double, 4, 2>::Zero().eval();
    });
  }
}

// Joint integration has no sampling floor: Algorithm 4 reaches machine precision.
TEST(ZhangContinuous, JointIntegrationConvergesToMachinePrecision) {
  auto observer = zhang_observer<double>(50.0);
  auto plant = periodic::make_plant<double>();
  adaptobs::JointIntegration joint(plant, observer);
  for (int k = 0; k < 4000; ++k) joint.step(0.01);
  EXPECT_LT((observer.parameters() - plant.parameters()).norm() / plant.parameters().norm(), 1e-12);
  EXPECT_LT((observer.state() - plant.state()).norm() / plant.state().norm(), 1e-12);
}

// A step length that is not finite and positive is refused by name; a step
// that overflows changes neither side and says so; the next good step goes on.
TEST(JointIntegration, BadStepsChangeNeitherThePlantNorTheObserver) {
  auto observer = zhang_observer<double>(50.0);
  auto plant = periodic::make_plant<double>();
  adaptobs::JointIntegration joint(plant, observer);
  ASSERT_EQ(joint.step(0.01), UpdateStatus::accepted);
  const auto plant_state = plant.state();
  const auto internal = observer.internal_state();
  const double time = joint.time();
  for (const double h : {std::nan(""), -0.5, 0.0, std::numeric_limits<double>::infinity()}) {
    EXPECT_CONFIGURATION_ERROR_NAMES(joint.step(h), "h");
  }
  EXPECT_EQ(joint.step(1e300), UpdateStatus::nonfinite_result);
  EXPECT_TRUE(plant.state() == plant_state);
  EXPECT_TRUE(observer.internal_state() == internal);
  EXPECT_EQ(joint.time(), time);
  EXPECT_EQ(plant.time(), time);
  EXPECT_EQ(joint.step(0.01), UpdateStatus::accepted);
  EXPECT_DOUBLE_EQ(plant.time(), 0.02);
}

// The plant's clock counts periods: in float, 20000 periods of 0.01 read 200
// to within the rounding of one product, not a sum that drifts.
TEST(ContinuousLinearPlant, ItsClockDoesNotDriftOverManyPeriods) {
  auto plant = siso::make_plant<float>();
  for (int k = 0; k < 20000; ++k) plant.advance();
  EXPECT_NEAR(plant.sample().t, 200.0f, 2e-5f);
}

// The input callable's result is checked before it is stored or multiplied,
// and a start that is not finite is refused by name.
TEST(ContinuousLinearPlant, AnInputOfAnotherSizeAndNonFiniteStartsAreRefusedByName) {
  const auto model = siso::model<double>();
  const auto eta0 = siso::initial_state<double>();
  const auto theta = siso::true_parameters<double>();
  const auto wide_input = [](double t) { return Eigen::VectorXd::Constant(t > 0 ? 2 : 1, 1.0); };
  adaptobs::ContinuousLinearPlant plant(model, eta0, theta, wide_input);
  EXPECT_CONFIGURATION_ERROR_NAMES(plant.advance(), "input(t)");
  const auto input = [](double) { return Eigen::VectorXd::Ones(1); };
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_CONFIGURATION_ERROR_NAMES(adaptobs::ContinuousLinearPlant(model, eta0, theta, input, {.start_time = nan}),
                                   "options.start_time");
  EXPECT_CONFIGURATION_ERROR_NAMES(adaptobs::ContinuousLinearPlant(model, decltype(eta0)::Constant(nan), theta, input),
                                   "eta0");
}

// V = eᵀPe + θ̃ᵀΓ⁻¹θ̃ (P from the KYP certificate) never increases (Alg. 1–2);
// V = |e|² + θ̃ᵀΓ⁻¹θ̃ never increases for Alg. 3 on the periodic plant.
template <class Observer, class Plant, class Weight>
double largest_relative_increase(Observer& observer, Plant& plant, const Weight& P, double gamma, double duration) {
  adaptobs::JointIntegration joint(plant, observer);
  const auto lyapunov = [&] {
    const auto& st = observer.algorithm().static_transform;
    const typename Observer::State z = st.T() * plant.state() - observer.omega() * plant.parameters();
    const typename Observer::State e = observer.transformed_estimate_z() - z;
    const auto th = observer.parameters() - plant.parameters();
    return double(e.dot(P * e)) + th.squaredNorm() / gamma;
  };
  const double v0 = lyapunov();
  double previous = v0, worst = 0;
  for (Index k = 0; k < Index(duration / 0.005); ++k) {
    joint.step(0.005);
    const double v = lyapunov();
    worst = std::max(worst, (v - previous) / v0);
    previous = v;
  }
  EXPECT_LT(previous, 1e-3 * v0);
  return worst;
}

TEST(UnifiedFormulation, LyapunovFunctionsDecrease) {
  {
    auto observer = bastin_gevers_observer<double>();
    const auto so = observer.transformed_system(0.0);
    const auto kyp =
        spr_report(Eigen::Matrix3d(so.Ao - observer.algorithm().k * so.Co), Eigen::Vector3d(1, 0, 0), so.Co).kyp;
    ASSERT_TRUE(kyp.has_value());
    auto plant = siso::make_plant<double>();
    EXPECT_LT(largest_relative_increase(observer, plant, kyp->P, 5.0, 60.0), 1e-9);
  }
  {
    auto observer = marino_tomei_observer<double>();
    const auto so = observer.transformed_system(0.0);
    const auto kyp =
        spr_report(Eigen::Matrix3d(so.Ao - observer.algorithm().k * so.Co), observer.algorithm().gamma, so.Co).kyp;
    ASSERT_TRUE(kyp.has_value());
    auto plant = siso::make_plant<double>();
    EXPECT_LT(largest_relative_increase(observer, plant, kyp->P, 20.0, 60.0), 1e-9);
  }
  {
    auto observer = besancon_observer<double>();
    auto plant = periodic::make_plant<double>();
    EXPECT_LT(largest_relative_increase(observer, plant, Eigen::Matrix4d::Identity().eval(), 10.0, 20.0), 1e-9);
  }
}

// ---------------------------------------------------------------------------
// The two families agree: Guyader–Zhang on the Euler-sampled system
// (A_k = I + Ts A(t_k), B_k = Ts B, Ψ_k = Ts Φ(t_k), K_k = Ts K, μ = Ts γ)
// approaches the continuous Zhang observer as O(Ts).

struct Differences {
  double x = 0, theta = 0, upsilon = 0;
};

Differences discrete_against_continuous(double ts) {
  using D = periodic::Dims<double>;
  const double gamma = 10.0, duration = 20.0;
  auto continuous = zhang_observer<double>(gamma);
  auto plant = periodic::make_plant<double>({.period = ts});
  const auto euler = adaptobs::make_discrete_ltv_model<D>([ts](Index k) {
    const auto s = periodic::system<double>(double(k) * ts);
    return adaptobs::DiscreteSystem<D>{Eigen::Matrix4d::Identity() + ts * s.A, ts * s.B, s.C};
  });
  adaptobs::GuyaderZhangObserver discrete(euler, Eigen::Matrix<double, 4, 2>(ts * periodic::zhang_gain<double>()),
                                          ts * gamma, Eigen::Vector4d::Zero().eval(), Eigen::Vector2d::Zero().eval());
  Differences d;
  EXPECT_EQ(continuous.update(plant.sample()), UpdateStatus::accepted);
  for (Index k = 0; k < Index(std::llround(duration / ts)); ++k) {
    // x̂_k, θ̂_k, Υ_k of the discrete observer against x̂(t_k), θ̂(t_k), Ω(t_k).
    d.x = std::max(d.x, (discrete.state() - continuous.state()).cwiseAbs().maxCoeff());
    d.theta = std::max(d.theta, (discrete.parameters() - continuous.parameters()).cwiseAbs().maxCoeff());
    d.upsilon = std::max(d.upsilon, (discrete.upsilon() - continuous.omega()).cwiseAbs().maxCoeff());
    const auto& s = plant.sample();
    const adaptobs::DiscreteSample<D> sample{s.u, s.y, ts * periodic::Regressor{}.operator()<double>(s.t)};
    EXPECT_EQ(discrete.update(sample), UpdateStatus::accepted);
    EXPECT_LE(discrete.assumption2_norm(), 1.0);
    plant.advance();
    EXPECT_EQ(continuous.update(plant.sample()), UpdateStatus::accepted);
  }
  return d;
}

TEST(UnifiedFormulation, GuyaderZhangIsTheEulerLimitOfZhang) {
  const Differences d1 = discrete_against_continuous(0.01);
  const Differences d2 = discrete_against_continuous(0.005);
  const Differences d3 = discrete_against_continuous(0.0025);
  for (const auto& [a, b] :
       {std::pair{d1.x, d2.x}, std::pair{d2.x, d3.x}, std::pair{d1.theta, d2.theta}, std::pair{d2.theta, d3.theta},
        std::pair{d1.upsilon, d2.upsilon}, std::pair{d2.upsilon, d3.upsilon}}) {
    EXPECT_GT(a / b, 1.8) << a << " " << b;
    EXPECT_LT(a / b, 2.2) << a << " " << b;
  }
  EXPECT_LT(d1.upsilon, 0.3 * 0.01);
  EXPECT_LT(d3.theta, 2e-3);
}

}  // namespace
