// The four continuous-time observers of the unified formulation (Zhang 2005)
// and the augmented Kalman–Bucy baseline: convergence on the examples' plants
// with fitted decay rates, a flipped update law, fixed against dynamic sizes
// and float, and bad input. The structure along trajectories ((4a), Lyapunov
// functions, the Euler limit) is in test_unified_structure.cpp, the long runs
// and gaps in test_unified_long_runs.cpp. The designs come from the library
// adaptobs_example_designs (examples/models/unified_designs.hpp).

#include <adaptobs/baselines/kalman_bucy.hpp>
#include <adaptobs/core/observer.hpp>
#include <adaptobs/design/riccati_differential.hpp>
#include <adaptobs/observers/bastin_gevers.hpp>
#include <adaptobs/observers/besancon.hpp>
#include <adaptobs/observers/marino_tomei.hpp>
#include <adaptobs/observers/zhang_continuous.hpp>
#include <adaptobs/simulation/continuous_plant.hpp>
#include <adaptobs/simulation/plant.hpp>

#include "models/periodic_mimo.hpp"
#include "models/siso_third_order.hpp"
#include "support/eigen_testing.hpp"
#include "support/observer_contract.hpp"
#include "unified_fixtures.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <tuple>
#include <utility>
#include <vector>

namespace {

using adaptobs::Index;
using adaptobs::UpdateStatus;
using namespace adaptobs::testing::unified;

// ---------------------------------------------------------------------------
// Convergence on the examples' plants, through update() with midpoint samples.

// Over `duration` seconds on `plant`: θ̂ within 1e-6 (relative) at the end, the
// state over the last tenth, and θ̂'s error decaying at least at `rate` over the
// `window` seconds from `from` (Trace::theta_decay_rate).
template <class Observer, class Plant>
void expect_convergence(Observer& observer, Plant plant, double duration, double from, double window, double rate) {
  const Trace trace = run(observer, plant, duration);
  EXPECT_LT(trace.theta_rel.back(), 1e-6);
  EXPECT_LT(trace.state_rel_last_tenth(), 1e-6);
  EXPECT_GT(trace.theta_decay_rate(from, window), rate);
}

TEST(BastinGevers, ConvergesOnTheThirdOrderPlant) {
  auto observer = bastin_gevers_observer<double>();
  EXPECT_MATRIX_NEAR(observer.algorithm().k, Eigen::Vector3d(2, 0, 0), 1e-12, 0);
  expect_convergence(observer, siso::make_plant<double>(), 100.0, 10.0, 10.0, 0.09);
}

TEST(MarinoTomei, ConvergesOnTheThirdOrderPlant) {
  auto observer = marino_tomei_observer<double>();
  EXPECT_MATRIX_NEAR(observer.algorithm().k, Eigen::Vector3d(8, 17, 10), 1e-12, 0);
  expect_convergence(observer, siso::make_plant<double>(), 100.0, 10.0, 10.0, 0.087);
}

TEST(Besancon, ConvergesOnThePeriodicMimoPlant) {
  auto observer = besancon_observer<double>({.sampling = quadratic(), .excitation_window = 629});
  expect_convergence(observer, periodic::make_plant<double>(), 40.0, 4.0, 2.0, 0.6);
  EXPECT_GT(observer.excitation_level().value(), 0.1);  // Λ is persistently exciting (≈ 1.96 / 2π)
}

// Algorithm 3's gain L = [K₁; A₂₁(t)] is what makes the error dynamics
// triangular: with C_o = [I 0], A_o − L C_o = [A₁₁ − K₁, A₁₂; 0, A₂₂] at every t.
TEST(Besancon, InjectionGainCancelsTheLowerLeftBlockOfTheErrorDynamics) {
  auto observer = besancon_observer<double>();
  const auto& algorithm = observer.algorithm();
  double smallest_a21 = std::numeric_limits<double>::infinity();
  for (const double t : {0.0, 0.37, 1.9, 4.2}) {
    const auto so = observer.transformed_system(t);
    const Index m = so.Co.rows(), r = so.Ao.rows() - m;
    ASSERT_EQ(so.Co.leftCols(m), Eigen::MatrixXd::Identity(m, m));
    ASSERT_TRUE(so.Co.rightCols(r).isZero(0));
    decltype(observer)::GainMatrix L;
    algorithm.injection_gain(so, t, L);
    const Eigen::MatrixXd closed = so.Ao - L * so.Co;
    const double scale = so.Ao.cwiseAbs().maxCoeff();
    EXPECT_LT(closed.bottomLeftCorner(r, m).cwiseAbs().maxCoeff(), 1e-15 * scale) << "t = " << t;
    EXPECT_LT((closed.topLeftCorner(m, m) - (so.Ao.topLeftCorner(m, m) - algorithm.K1)).cwiseAbs().maxCoeff(),
              1e-15 * scale);
    EXPECT_EQ(closed.rightCols(r), so.Ao.rightCols(r));
    smallest_a21 = std::min(smallest_a21, so.Ao.bottomLeftCorner(r, m).norm());
  }
  EXPECT_GT(smallest_a21, 0.1) << "A₂₁ must not vanish, or the cancellation is not tested";
}

TEST(ZhangContinuous, ConvergesOnThePeriodicMimoPlant) {
  auto observer = zhang_observer<double>(50.0, {.sampling = quadratic(), .excitation_window = 629});
  expect_convergence(observer, periodic::make_plant<double>(), 40.0, 4.0, 2.0, 0.84);
  // Gramian (15) over one period: λmin ≈ 0.090, i.e. an average level ≈ 0.0143.
  EXPECT_GT(observer.excitation_level().value(), 0.005);
}

TEST(ZhangContinuous, RiccatiGainAlongTheTrajectory) {
  auto observer = zhang_observer<double>(50.0);
  using D = periodic::Dims<double>;
  adaptobs::RiccatiDifferentialEquation<D> riccati(Eigen::Matrix4d::Identity(), Eigen::Matrix4d::Identity(),
                                                   0.1 * Eigen::Matrix2d::Identity());
  const auto model = periodic::model<double>();
  observer.set_output_injection(riccati.gain(model.at(0.0).C));
  auto plant = periodic::make_plant<double>();
  const Trace trace = run(observer, plant, 40.0, [&](double t0, double t1) {
    riccati.advance(model, t0, t1);
    observer.set_output_injection(riccati.gain(model.at(t1).C));
  });
  EXPECT_LT(trace.theta_rel.back(), 1e-6);
  EXPECT_LT(trace.state_rel_last_tenth(), 1e-6);
  EXPECT_GT(trace.theta_decay_rate(4.0, 2.0), 1.1);
}

TEST(KalmanBucy, ConvergesExponentiallyWithParameterNoise) {
  auto filter = kalman_bucy_filter<double>(1.0);
  expect_convergence(filter, siso::make_plant<double>(), 60.0, 6.0, 10.0, 0.24);
}

TEST(KalmanBucy, SetInternalStateRefusesWhatAnUpdateWouldAndChangesNothing) {
  auto filter = kalman_bucy_filter<double>(1.0);
  const auto before = filter.internal_state();  // [x̂; θ̂; vec P], n = 5
  const Index n = 5;
  ASSERT_EQ(before.size(), n + n * n);
  auto nan = before;
  nan(1) = std::nan("");
  EXPECT_FALSE(filter.set_internal_state(nan));
  EXPECT_TRUE(filter.internal_state() == before);
  auto indefinite = before;
  indefinite(n + 2 * n + 2) = -1;  // P(2, 2) < 0
  EXPECT_FALSE(filter.set_internal_state(indefinite));
  EXPECT_TRUE(filter.internal_state() == before);
  auto moved = before;
  moved(0) += 1;
  EXPECT_TRUE(filter.set_internal_state(moved));
  EXPECT_TRUE(filter.internal_state() == moved);
  EXPECT_EQ(filter.state()(0), before(0) + 1);
}

// ---------------------------------------------------------------------------
// A flipped update law θ̂' = −ΓRᵀε makes every observer diverge.

// One law type for every algorithm (all examples have p = 2); the sign is a runtime value.
struct SignedGradientLaw {
  Eigen::Matrix2d gamma;
  double sign;
  template <class DR, class DE, class DT, class DOut>
  void derivative(const Eigen::MatrixBase<DR>& R, const Eigen::MatrixBase<DE>& epsilon, const Eigen::MatrixBase<DT>&,
                  Eigen::MatrixBase<DOut>& dtheta) const {
    dtheta = sign * (gamma * (R.transpose() * epsilon));
  }
};

template <class Observer, class Plant>
double divergence_time(Observer& observer, Plant& plant) {
  const double threshold = 1e3 * plant.parameters().norm();
  EXPECT_EQ(observer.update(plant.sample()), UpdateStatus::accepted);
  for (Index k = 1; k <= 1000; ++k) {
    plant.advance();
    if (observer.update(plant.sample()) != UpdateStatus::accepted) return plant.time();
    if ((observer.parameters() - plant.parameters()).norm() > threshold) return plant.time();
  }
  return std::numeric_limits<double>::infinity();
}

// `good` with its update law replaced by the gradient of step `step` and the
// wrong sign diverges within 5 s from zero estimates on `plant`.
template <class Observer, class Model, class Plant>
void expect_divergence_with_the_sign_flipped(const Observer& good, const Model& model, Plant plant, double step,
                                             const char* name) {
  using Dims = typename Model::Dims;
  adaptobs::UnifiedAdaptiveObserver flipped(
      model, good.algorithm(), SignedGradientLaw{step * Eigen::Matrix2d::Identity(), -1.0}, Dims::State::Zero().eval(),
      Dims::Parameters::Zero().eval(), {.sampling = quadratic()});
  EXPECT_LT(divergence_time(flipped, plant), 5.0) << name;
}

TEST(UpdateLaw, FlippedSignDivergesForEveryAlgorithm) {
  expect_divergence_with_the_sign_flipped(bastin_gevers_observer<double>(), siso::model<double>(),
                                          siso::make_plant<double>(), 5.0, "Bastin-Gevers");
  expect_divergence_with_the_sign_flipped(marino_tomei_observer<double>(), siso::model<double>(),
                                          siso::make_plant<double>(), 20.0, "Marino-Tomei");
  expect_divergence_with_the_sign_flipped(besancon_observer<double>(), periodic::model<double>(),
                                          periodic::make_plant<double>(), 10.0, "Besancon");
  expect_divergence_with_the_sign_flipped(zhang_observer<double>(50.0), periodic::model<double>(),
                                          periodic::make_plant<double>(), 50.0, "Zhang");
}

// ---------------------------------------------------------------------------
// Sizes and scalars.

TEST(ZhangContinuous, SinglePrecisionConverges) {
  auto observer = zhang_observer<float>(50.0f);
  auto plant = periodic::make_plant<float>();
  (void)observer.update(plant.sample());
  for (Index k = 0; k < 2000; ++k) {
    plant.advance();
    ASSERT_EQ(observer.update(plant.sample()), UpdateStatus::accepted);
  }
  EXPECT_LT((observer.parameters() - plant.parameters()).norm() / plant.parameters().norm(), 1e-3f);
  EXPECT_LT((observer.state() - plant.state()).norm() / plant.state().norm(), 1e-3f);
}

// ---------------------------------------------------------------------------
// Bad input and bad configuration.

// The observer contract (support/observer_contract.hpp) for each algorithm and
// the Kalman–Bucy baseline, on its example's plant: 30 samples with midpoints.
template <class Design>
struct UnifiedContract {
  using Observer = decltype(Design::observer());
  using Sample = typename Observer::Sample;
  using Scalar = typename Observer::Scalar;
  static constexpr const char* name = Design::name;
  static Observer make() { return Design::observer(); }
  static std::vector<Sample> samples() { return adaptobs::testing::first_samples<Sample>(Design::plant(), 30); }
  static auto readings(const auto& o) {
    return std::make_tuple(o.internal_state(), o.state(), o.parameters(), o.time());
  }
  static constexpr auto poisonable = std::tuple{&Sample::t, &Sample::u, &Sample::y};
  static std::vector<Sample> more_poisoned(const Sample& valid) {
    std::vector<Sample> out;
    for (const Scalar bad : {std::numeric_limits<Scalar>::quiet_NaN(), std::numeric_limits<Scalar>::infinity()}) {
      out.push_back(valid);
      out.back().midpoint->u(0) = bad;
      out.push_back(valid);
      out.back().midpoint->y(0) = -bad;
    }
    return out;
  }
  template <class S>  // a sample of this observer or of its dynamic-size twin
  static S overflowing(S s) {
    s.y.setConstant(std::numeric_limits<Scalar>::max());
    s.midpoint->y.setConstant(-std::numeric_limits<Scalar>::max());
    return s;
  }
  // ε(t_k) = y_k − C(t_k) η̂(t_k), at the estimate integrated to the sample time.
  static typename Observer::Output expected_output_error(const Observer&, const Observer& after, const Sample& s) {
    static const auto model = Design::plant().model();  // the plant's, independent of the observer's
    return s.y - model.at(s.t).C * after.state();
  }
};

struct BastinGeversDesign {
  static constexpr const char* name = "BastinGevers";
  static auto observer() { return bastin_gevers_observer<double>(); }
  static auto plant() { return siso::make_plant<double>(); }
};
struct MarinoTomeiDesign {
  static constexpr const char* name = "MarinoTomei";
  static auto observer() { return marino_tomei_observer<double>(); }
  static auto plant() { return siso::make_plant<double>(); }
};
struct BesanconDesign {
  static constexpr const char* name = "Besancon";
  static auto observer() { return besancon_observer<double>(); }
  static auto plant() { return periodic::make_plant<double>(); }
};
struct ZhangDesign {
  static constexpr const char* name = "Zhang";
  static auto observer() { return zhang_observer<double>(50.0); }
  static auto plant() { return periodic::make_plant<double>(); }
};
struct KalmanBucyDesign {
  static constexpr const char* name = "KalmanBucy";
  static auto observer() { return kalman_bucy_filter<double>(1.0); }
  static auto plant() { return siso::make_plant<double>(); }
};

// Zhang's observer with Eigen::Dynamic sizes, on the same model and run.
auto zhang_dynamic_observer() {
  using DD = adaptobs::DynamicDimensions<double>;
  const auto model = adaptobs::make_continuous_ltv_model<DD>(
      [](double t) {
        const auto s = periodic::system<double>(t);
        return adaptobs::ContinuousSystem<DD>{s.A, s.B, s.C};
      },
      [](double t) { return Eigen::MatrixXd(periodic::Regressor{}.operator()<double>(t)); }, {4, 1, 2, 2});
  return adaptobs::make_zhang_continuous_observer(
      model, Eigen::MatrixXd(periodic::zhang_gain<double>()), Eigen::MatrixXd(50.0 * Eigen::Matrix2d::Identity()),
      Eigen::VectorXd::Zero(4), Eigen::VectorXd::Zero(2), {.sampling = quadratic()});
}

struct ZhangDynamicContract : UnifiedContract<ZhangDesign> {
  using Observer = decltype(zhang_dynamic_observer());
  using Sample = Observer::Sample;
  using InFixed = UnifiedContract<ZhangDesign>;
  static Observer make() { return zhang_dynamic_observer(); }
  static std::vector<Sample> samples() {
    return adaptobs::testing::first_samples<Sample>(periodic::make_plant<double>(), 30, [](const auto& s) {
      Sample d{s.t, s.u, s.y, std::nullopt};
      if (s.midpoint) d.midpoint = typename Sample::Midpoint{s.midpoint->u, s.midpoint->y};
      return d;
    });
  }
};

}  // namespace

ADAPTOBS_OBSERVER_CONTRACT(UnifiedFormulation, UnifiedContract<BastinGeversDesign>, UnifiedContract<MarinoTomeiDesign>,
                           UnifiedContract<BesanconDesign>, UnifiedContract<ZhangDesign>,
                           UnifiedContract<KalmanBucyDesign>);
ADAPTOBS_TWIN_CONTRACT(UnifiedFormulation, DynamicFollowsFixed, ZhangDynamicContract);

namespace {

// With Eigen::Dynamic sizes, arguments and model callables of the wrong run-time
// size are refused with the name the caller knows, at any time, and a refused
// update leaves the observer as it was.
TEST(ZhangContinuous, WrongRunTimeSizesAreRefusedNamingTheArgumentAndChangeNothing) {
  using DD = adaptobs::DynamicDimensions<double>;
  // From t = 0.5 on, the matrices (bad_matrices) or the regressor (bad_regressor) change size.
  const auto model_of = [](bool bad_matrices, bool bad_regressor) {
    return adaptobs::make_continuous_ltv_model<DD>(
        [bad_matrices](double t) {
          const auto s = periodic::system<double>(t);
          if (bad_matrices && t > 0.5) return adaptobs::ContinuousSystem<DD>{Eigen::MatrixXd::Zero(5, 5), s.B, s.C};
          return adaptobs::ContinuousSystem<DD>{s.A, s.B, s.C};
        },
        [bad_regressor](double t) {
          if (bad_regressor && t > 0.5) return Eigen::MatrixXd(Eigen::MatrixXd::Zero(5, 2));
          return Eigen::MatrixXd(periodic::Regressor{}.operator()<double>(t));
        },
        {4, 1, 2, 2});
  };
  const Eigen::MatrixXd K = periodic::zhang_gain<double>(), gamma = 50.0 * Eigen::Matrix2d::Identity();
  const Eigen::VectorXd eta0 = Eigen::VectorXd::Zero(4), theta0 = Eigen::VectorXd::Zero(2);
  EXPECT_CONFIGURATION_ERROR_NAMES(adaptobs::make_zhang_continuous_observer(
                                       model_of(false, false), Eigen::MatrixXd::Ones(4, 4), gamma, eta0, theta0),
                                   "K");
  EXPECT_CONFIGURATION_ERROR_NAMES(adaptobs::make_zhang_continuous_observer(
                                       model_of(false, false), K, Eigen::MatrixXd::Identity(1, 1), eta0, theta0),
                                   "gamma");

  for (const auto& [bad_matrices, argument] : {std::pair{true, "matrices_at(t)"}, std::pair{false, "Phi"}}) {
    auto observer =
        adaptobs::make_zhang_continuous_observer(model_of(bad_matrices, !bad_matrices), K, gamma, eta0, theta0);
    auto plant = periodic::make_plant<double>();
    while (plant.sample().t <= 0.5) {
      const auto& s = plant.sample();
      ASSERT_EQ(observer.update({s.t, s.u, s.y, std::nullopt}), UpdateStatus::accepted);
      plant.advance();
    }
    const Eigen::VectorXd state = observer.state(), parameters = observer.parameters();
    const Eigen::MatrixXd omega = observer.omega();
    const auto& s = plant.sample();
    EXPECT_CONFIGURATION_ERROR_NAMES(observer.update({s.t, s.u, s.y, std::nullopt}), argument);
    EXPECT_TRUE(observer.state() == state);
    EXPECT_TRUE(observer.parameters() == parameters);
    EXPECT_TRUE(observer.omega() == omega);
  }
}

TEST(UnifiedFormulation, BadConfigurationNamesTheArgument) {
  using SD = siso::Dims<double>;
  const auto model = siso::model<double>();
  const Eigen::Vector3d zero3 = Eigen::Vector3d::Zero();
  const Eigen::Vector2d zero2 = Eigen::Vector2d::Zero();
  const auto st1 = bastin_gevers_transform<double>();
  const Eigen::Matrix2d gamma = Eigen::Matrix2d::Identity();
  // Γ not positive definite, k not SPR, a transform not in form (5), a wrong-size x0.
  EXPECT_CONFIGURATION_ERROR_NAMES(adaptobs::make_bastin_gevers_observer(model, st1, Eigen::Vector3d(2, 0, 0),
                                                                         Eigen::Matrix2d(-gamma), zero3, zero2),
                                   "gamma");
  EXPECT_CONFIGURATION_ERROR_NAMES(
      adaptobs::make_bastin_gevers_observer(model, st1, Eigen::Vector3d(-0.5, 0, 0), gamma, zero3, zero2), "k");
  EXPECT_CONFIGURATION_ERROR_NAMES(
      adaptobs::make_bastin_gevers_observer(model, adaptobs::StaticTransform<SD>::identity(), Eigen::Vector3d(2, 0, 0),
                                            gamma, zero3, zero2),
      "static_transform");
  const auto st2 = marino_tomei_transform<double>();
  EXPECT_CONFIGURATION_ERROR_NAMES(
      adaptobs::make_marino_tomei_observer(model, st2, Eigen::Vector3d(1, -3, 2), Eigen::Vector3d(8, 17, 10), gamma,
                                           zero3, zero2),
      "gamma");
  EXPECT_CONFIGURATION_ERROR_NAMES(
      adaptobs::make_marino_tomei_observer(model, st1, Eigen::Vector3d(1, 3, 2), Eigen::Vector3d(8, 17, 10), gamma,
                                           zero3, zero2),
      "static_transform");
  // Algorithm 4: K not stabilizing; Algorithm 3: K1 too small.
  EXPECT_CONFIGURATION_ERROR_NAMES(
      adaptobs::make_zhang_continuous_observer(model, Eigen::Vector3d(-10, 0, 0), gamma, zero3, zero2), "K");
  EXPECT_CONFIGURATION_ERROR_NAMES(
      adaptobs::make_besancon_observer(model, besancon_transform<double>(), Eigen::Matrix<double, 1, 1>(-1.0), gamma,
                                       zero3, zero2),
      "K1");
  // Options and samples.
  EXPECT_CONFIGURATION_ERROR_NAMES(zhang_observer<double>(50.0, {.sampling = {.substeps = 0}}), "options.substeps");
  {
    auto observer = zhang_observer<double>(50.0);
    auto plant = periodic::make_plant<double>();
    ASSERT_EQ(observer.update(plant.sample()), UpdateStatus::accepted);
    plant.advance();
    auto s = plant.sample();
    s.midpoint.reset();
    EXPECT_CONFIGURATION_ERROR_NAMES((void)observer.update(s), "sample.midpoint");
  }
  EXPECT_CONFIGURATION_ERROR_NAMES(adaptobs::StaticTransform<SD>(Eigen::Matrix3d::Zero(), zero3), "T");
  EXPECT_CONFIGURATION_ERROR_NAMES(kalman_bucy_filter<double>(-1.0), "covariances.Q");
  // Run-time sizes: a transform without states, or measuring more states than it has.
  using DD = adaptobs::DynamicDimensions<double>;
  const adaptobs::StaticTransform<DD> empty(Eigen::MatrixXd(0, 0), Eigen::MatrixXd(0, 1));
  EXPECT_CONFIGURATION_ERROR_NAMES(adaptobs::BastinGevers<DD>(empty, Eigen::MatrixXd(0, 1)), "transform");
  EXPECT_CONFIGURATION_ERROR_NAMES(adaptobs::MarinoTomei<DD>(empty, Eigen::VectorXd(0), Eigen::MatrixXd(0, 1)),
                                   "transform");
  EXPECT_CONFIGURATION_ERROR_NAMES(adaptobs::Besancon<DD>(adaptobs::StaticTransform<DD>(Eigen::MatrixXd::Identity(2, 2),
                                                                                        Eigen::MatrixXd::Zero(2, 3)),
                                                          Eigen::MatrixXd::Identity(3, 3)),
                                   "transform");
}

TEST(UnifiedFormulation, AnOutputInjectionThatBreaksTheConditionsIsRefusedAndChangesNothing) {
  auto observer = siso_zhang_observer<double>();
  const Eigen::Vector3d k = observer.algorithm().static_transform.K();
  const Eigen::Matrix3d ao = observer.transformed_system(0).Ao;
  // A − KC with K = (−10, 0, 0) is not Hurwitz: refused as at construction.
  EXPECT_CONFIGURATION_ERROR_NAMES(observer.set_output_injection(Eigen::Vector3d(-10, 0, 0)), "K");
  EXPECT_TRUE(observer.algorithm().static_transform.K() == k);
  EXPECT_TRUE(observer.transformed_system(0).Ao == ao);
  // A stabilizing K is taken, and A_o = A − KC follows it.
  const Eigen::Vector3d doubled = 2 * k;
  observer.set_output_injection(doubled);
  EXPECT_TRUE(observer.algorithm().static_transform.K() == doubled);
  EXPECT_TRUE(observer.transformed_system(0).Ao.isApprox(ao - k * observer.model().system().C));
}

static_assert(adaptobs::Observer<decltype(bastin_gevers_observer<double>())>);
static_assert(adaptobs::Observer<decltype(marino_tomei_observer<double>())>);
static_assert(adaptobs::Observer<decltype(besancon_observer<double>())>);
static_assert(adaptobs::Observer<decltype(zhang_observer<double>(1.0))>);
static_assert(adaptobs::Observer<decltype(zhang_observer<float>(1.0f))>);
static_assert(adaptobs::Observer<decltype(kalman_bucy_filter<double>(1.0))>);

}  // namespace

namespace {

// Ψ = TΦ(t, u, y) is computed once per distinct (t, u, y) of the RK4 stages. With
// the input held over each interval, the last stage of an interval and the first
// of the next share their time but not their u: a Φ that reads u must be
// evaluated at both. update() against the RK4 step written here on the public
// derivative(), which keeps nothing from one call to the next.
TEST(UnifiedFormulation, EachStageEvaluatesTheRegressorAtItsOwnSignals) {
  using D = periodic::Dims<double>;
  const auto model = adaptobs::make_continuous_ltv_model<D>(
      [](double t) { return periodic::system<double>(t); },
      [](double t, const D::Input& u, const D::Output& y) {
        return D::RegressorMatrix((1.0 + 0.5 * u(0) + 0.2 * y(0)) * periodic::Regressor{}.operator()<double>(t));
      });
  const adaptobs::SamplingOptions hold_and_line;  // u held, y a straight line, one RK4 step per interval
  auto observer = adaptobs::make_zhang_continuous_observer(
      model, periodic::zhang_gain<double>(), D::ParameterMatrix(50.0 * Eigen::Matrix2d::Identity()), D::State::Zero(),
      D::Parameters::Zero(), {.sampling = hold_and_line});
  const auto rhs = observer;  // for derivative() alone
  using State = decltype(observer)::InternalState;
  const auto samples = adaptobs::record_samples(periodic::make_plant<double>(), 300);
  ASSERT_EQ(observer.update(samples[0]), UpdateStatus::accepted);
  State x = observer.internal_state();
  double worst = 0;
  for (std::size_t k = 1; k < samples.size(); ++k) {
    const auto& a = samples[k - 1];
    const auto& b = samples[k];
    ASSERT_EQ(observer.update(b), UpdateStatus::accepted);
    const double h = b.t - a.t;
    const auto f = [&](const State& s, double sigma) {
      const D::Output y = (1 - sigma) * a.y + sigma * b.y;
      State ds;
      rhs.derivative(s, ds, a.t + sigma * h, a.u, y);
      return ds;
    };
    const State k1 = f(x, 0.0), k2 = f(x + h / 2 * k1, 0.5), k3 = f(x + h / 2 * k2, 0.5), k4 = f(x + h * k3, 1.0);
    x += h / 6 * (k1 + 2 * (k2 + k3) + k4);
    worst =
        std::max(worst, (observer.internal_state() - x).cwiseAbs().maxCoeff() / std::max(1.0, x.cwiseAbs().maxCoeff()));
    x = observer.internal_state();
  }
  EXPECT_LT(worst, 1e-13);
  // θ̂ has moved from 0: the comparison is of an observer at work.
  EXPECT_GT(observer.parameters().norm(), 0.1);
}

}  // namespace

namespace {

// A time-varying model's matrices of (2) and F(t) are kept from one RK4 stage to
// the next at the same t; over an outage, F is that of the measured channels'
// system. A model given as time-varying whose matrices are constant follows the
// time-invariant one, whose matrices are computed once, through an outage of
// the second output and after it.
TEST(UnifiedFormulation, AConstantTimeVaryingModelFollowsTheTimeInvariantOneThroughAnOutage) {
  using D = periodic::Dims<double>;
  const auto frozen = periodic::system<double>(0.0);
  const auto regressor = [](double t) { return periodic::Regressor{}.operator()<double>(t); };
  const auto lti = adaptobs::make_continuous_lti_model<D>(frozen.A, frozen.B, frozen.C, regressor);
  const auto ltv = adaptobs::make_continuous_ltv_model<D>([frozen](double) { return frozen; }, regressor);
  const auto observer_of = [](const auto& model) {
    return adaptobs::make_zhang_continuous_observer(model, periodic::zhang_gain<double>(),
                                                    D::ParameterMatrix(50.0 * Eigen::Matrix2d::Identity()),
                                                    D::State::Zero(), D::Parameters::Zero(), {.sampling = quadratic()});
  };
  auto constant = observer_of(lti);
  auto varying = observer_of(ltv);
  const auto samples = adaptobs::record_samples(periodic::make_plant<double>(), 400);
  adaptobs::OutputMask<D> first_only;
  first_only << true, false;
  double worst = 0;
  for (std::size_t k = 0; k < samples.size(); ++k) {
    const bool outage = k >= 150 && k < 200;
    const auto update = [&](auto& o) { return outage ? o.update(samples[k], first_only) : o.update(samples[k]); };
    ASSERT_EQ(update(constant), UpdateStatus::accepted);
    ASSERT_EQ(update(varying), UpdateStatus::accepted);
    worst = std::max(worst, (constant.internal_state() - varying.internal_state()).cwiseAbs().maxCoeff());
  }
  EXPECT_LT(worst, 1e-13);
  EXPECT_GT(constant.parameters().norm(), 0.1);
}

}  // namespace
