// Guyader–Zhang adaptive observer (Guyader & Zhang 2003): theorem 1 (noise free,
// exponential convergence), the satellite example, the diagnostics of
// assumptions 2–3, float/double and fixed/dynamic agreement, and rejection of
// bad input. Theorem 2 over long runs and many seeds is in
// test_guyader_zhang_long_runs.cpp.

#include <adaptobs/core/observer.hpp>
#include <adaptobs/design/dense_eigenvalues.hpp>
#include <adaptobs/design/riccati_recursion.hpp>
#include <adaptobs/observers/guyader_zhang.hpp>
#include <adaptobs/simulation/discrete_plant.hpp>

#include "guyader_zhang_fixtures.hpp"
#include "models/satellite.hpp"
#include "support/eigen_testing.hpp"
#include "support/ltv_test_system.hpp"
#include "support/observer_contract.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <type_traits>
#include <vector>

namespace {

using adaptobs::Index;
using adaptobs::UpdateStatus;
using adaptobs::testing::Tolerance;
using namespace adaptobs::testing::guyader_zhang;

// Geometric rate of the decaying part of an error sequence: the samples from
// the start until the error first reaches `floor`.
double decay_rate(const std::vector<double>& errors, double floor) {
  std::vector<double> decaying;
  for (double e : errors) {
    if (e <= floor) break;
    decaying.push_back(e);
  }
  EXPECT_GT(decaying.size(), 20u) << "too few samples above the floor to fit a rate";
  return adaptobs::testing::fit_geometric_rate(decaying);
}

ADAPTOBS_TYPED_SUITE_IN_BOTH_PRECISIONS(GuyaderZhangTyped);

// Theorem 1 on the satellite of §4 without noise: x̃ and θ̃ vanish exponentially.
TYPED_TEST(GuyaderZhangTyped, Theorem1SatelliteNoiseFreeConvergesGeometrically) {
  using S = TypeParam;
  auto observer = make_satellite_observer<S>();
  auto plant = satellite::make_plant<S>(S(0));
  // 60 s: long enough to converge, short enough that the drifting orbit keeps
  // float rounding below the tolerance.
  const ErrorHistory h = run(observer, plant, 600);
  // Relative to the size of the state, which drifts with the thrusts.
  const double scale = std::max(1.0, static_cast<double>(plant.state().norm()));
  EXPECT_LT(h.state.back() / scale, Tolerance<S>::converged);
  EXPECT_LT(h.parameter.back(), Tolerance<S>::converged);
  // Down to 1e-3, a range float resolves, both scalars decay at the rate of the
  // double-precision run (0.963 per sample here; a Υ index error gives 0.949).
  if constexpr (std::is_same_v<S, float>) {
    auto reference = make_satellite_observer<double>();
    auto reference_plant = satellite::make_plant<double>(0.0);
    const ErrorHistory r = run(reference, reference_plant, 600);
    EXPECT_NEAR(decay_rate(h.combined, 1e-3), decay_rate(r.combined, 1e-3), 1e-3);
  }
}

TEST(GuyaderZhang, Theorem1SatelliteRateAndFloor) {
  auto observer = make_satellite_observer<double>();
  auto plant = satellite::make_plant<double>(0.0);
  const ErrorHistory h = run(observer, plant, 6000);
  EXPECT_LT(h.state.back(), 1e-9);
  EXPECT_LT(h.parameter.back(), 1e-9);
  // Theorem 1: once θ̃ has converged the error decays like η, at the spectral
  // radius of A − KC (0.932). Fitted on the errors from 1e-3 down to 1e-10: 0.929;
  // with Υ_k for Υ_{k+1} in (2c), 0.948.
  std::vector<double> late;
  for (double e : h.combined)
    if (e < 1e-3 && e > 1e-10) late.push_back(e);
  ASSERT_GT(late.size(), 100u);
  const auto model = satellite::model<double>();
  const Eigen::MatrixXd closed_loop = model.system().A - satellite::paper_gain<double>() * model.system().C;
  const double radius = adaptobs::detail::dense_eigenvalues<double>(closed_loop).cwiseAbs().maxCoeff();
  EXPECT_NEAR(adaptobs::testing::fit_geometric_rate(late), radius, 0.008);
}

// A genuinely time-varying system: A_k, C_k and Ψ_k vary, K_k comes from the
// Riccati recursion (assumption 1), μ satisfies assumption 2.
using Ltv = adaptobs::Dimensions<double, 3, 1, 1, 2>;

adaptobs::DiscreteSystem<Ltv> ltv_system(Index k) {
  const Eigen::Matrix3d a = adaptobs::testing::rotating_ltv_dynamics(k);
  Eigen::RowVector3d c(1.0, 0.3 * std::cos(0.1 * double(k)), 0.5);
  return {a, Eigen::Vector3d(0, 0, 1), c};
}

Eigen::Matrix<double, 3, 2> ltv_regressor(Index k, const Eigen::Matrix<double, 1, 1>& /*u*/) {
  Eigen::Matrix<double, 3, 2> psi;
  const double t = double(k);
  psi << std::sin(0.11 * t), 0.0,  //
      0.0, std::cos(0.07 * t),     //
      0.3, 0.2 * std::sin(0.31 * t);
  return psi;
}

TEST(GuyaderZhang, Theorem1TimeVaryingSystemWithRiccatiGains) {
  const auto model = adaptobs::make_discrete_ltv_model<Ltv>(ltv_system);
  auto input = [](Index k) { return Eigen::Matrix<double, 1, 1>(std::sin(0.02 * double(k))); };
  adaptobs::DiscreteLinearPlant plant(model, Eigen::Vector3d(1, -1, 0.5), Eigen::Vector2d(0.7, -1.2), input,
                                      ltv_regressor);
  adaptobs::KalmanGainRecursion<Ltv> gains(Eigen::Matrix3d::Identity(), Eigen::Matrix3d::Identity() * 0.1,
                                           Eigen::Matrix<double, 1, 1>(1.0));
  adaptobs::GuyaderZhangObserver observer(model, Eigen::Vector3d::Zero().eval(), 0.05, Eigen::Vector3d::Zero().eval(),
                                          Eigen::Vector2d::Zero().eval(), {.excitation_window = 200});
  std::vector<double> combined;
  double worst_assumption2 = 0;
  double weakest_excitation = std::numeric_limits<double>::infinity();
  for (Index k = 0; k < 6000; ++k) {
    combined.push_back(
        std::hypot((observer.state() - plant.state()).norm(), (observer.parameters() - plant.parameters()).norm()));
    observer.set_gain(gains.next_gain(model.at(k)));
    ASSERT_EQ(observer.update(plant.sample()), UpdateStatus::accepted);
    worst_assumption2 = std::max(worst_assumption2, observer.assumption2_norm());
    if (const auto level = observer.excitation_level()) weakest_excitation = std::min(weakest_excitation, *level);
    plant.advance();
  }
  EXPECT_LE(worst_assumption2, 1.0) << "assumption 2 violated: the test's μ is too large";
  EXPECT_GT(weakest_excitation, 1e-4) << "assumption 3: Ψ_k is not persistently exciting";
  EXPECT_LT(combined.back(), 1e-9);
  EXPECT_LT(decay_rate(combined, 1e-10), 0.999);
}

// The identities in the proof of theorem 1, step by step along a noise-free LTV
// trajectory. With x̃ = x − x̂, θ̃ = θ − θ̂, η = x̃ − Υθ̃ and δ_k = θ_{k+1} − θ_k:
//   η_{k+1} = (A_k − K_kC_k) η_k − Υ_{k+1} δ_k,
//   θ̃_{k+1} = θ̃_k − μ Υ_kᵀC_kᵀC_k x̃_k + δ_k.
// The drift term Υ_{k+1}δ_k is the one theorem 2 bounds for a slowly varying θ;
// with δ = 0 these are the proof's exact recursions. Each uses a different Υ
// (Υ_k in (2b), Υ_{k+1} in (2c)), so trading one for the other breaks them.
TEST(GuyaderZhang, ProofRecursionsHoldStepByStepWithConstantAndDriftingParameters) {
  const auto model = adaptobs::make_discrete_ltv_model<Ltv>(ltv_system);
  const double mu = 0.05;
  for (double drift : {0.0, 2e-3}) {
    const auto theta_at = [drift](Index k) {
      const double t = double(k);
      return Eigen::Vector2d(0.7 + drift * t * std::sin(0.01 * t) / 10, -1.2 + drift * std::cos(0.03 * t) * 50);
    };
    adaptobs::KalmanGainRecursion<Ltv> gains(Eigen::Matrix3d::Identity(), Eigen::Matrix3d::Identity() * 0.1,
                                             Eigen::Matrix<double, 1, 1>(1.0));
    adaptobs::GuyaderZhangObserver observer(model, Eigen::Vector3d::Zero().eval(), mu, Eigen::Vector3d::Zero().eval(),
                                            Eigen::Vector2d::Zero().eval());
    Eigen::Vector3d x(1, -1, 0.5);
    double worst_eta = 0, worst_theta = 0, largest_drift_term = 0;
    for (Index k = 0; k < 2000; ++k) {
      const auto& system = model.at(k);
      const Eigen::Vector3d gain = gains.next_gain(system);
      observer.set_gain(gain);
      const Eigen::Matrix<double, 1, 1> u(std::sin(0.02 * double(k)));
      const Eigen::Matrix<double, 3, 2> psi = ltv_regressor(k, u);
      const Eigen::Vector2d theta = theta_at(k), delta = theta_at(k + 1) - theta;
      const Eigen::Matrix<double, 1, 1> y = system.C * x;

      const Eigen::Vector3d x_error = x - observer.state();
      const Eigen::Vector2d theta_error = theta - observer.parameters();
      const Eigen::Matrix<double, 3, 2> upsilon = observer.upsilon();
      const Eigen::Vector3d eta = x_error - upsilon * theta_error;
      ASSERT_EQ(observer.update({u, y, psi}), UpdateStatus::accepted);
      x = system.A * x + system.B * u + psi * theta;

      const Eigen::Vector2d next_theta_error = theta + delta - observer.parameters();
      const Eigen::Vector3d next_eta = x - observer.state() - observer.upsilon() * next_theta_error;
      const Eigen::Matrix3d closed_loop = system.A - gain * system.C;
      const Eigen::Vector3d drift_term = observer.upsilon() * delta;
      const Eigen::Vector3d eta_expected = closed_loop * eta - drift_term;
      const Eigen::Vector2d theta_error_expected =
          theta_error - mu * upsilon.transpose() * system.C.transpose() * (system.C * x_error) + delta;
      const double scale = std::max(1.0, x.norm());
      worst_eta = std::max(worst_eta, (next_eta - eta_expected).norm() / scale);
      worst_theta = std::max(worst_theta, (next_theta_error - theta_error_expected).norm() / scale);
      largest_drift_term = std::max(largest_drift_term, drift_term.norm());
    }
    EXPECT_LT(worst_eta, 1e-12) << "drift " << drift;
    EXPECT_LT(worst_theta, 1e-12) << "drift " << drift;
    if (drift > 0) {
      EXPECT_GT(largest_drift_term, 1e-3) << "the drift term must be exercised";
    }
  }
}

// Remark 1: a known input term f_k of the measured u_k and y_k joins B_ku_k in
// (1b) and, as (2c′), the estimate. It cancels in x̃, so the proof's recursion
// η_{k+1} = (A − KC)η_k holds as without it (docs/readings/guyader_zhang.md).
// Noise free, 3000 steps (300 s): the recursion's residual is at most 1.3e-12 and
// ‖θ̃‖ ends at 7.9e-12; with f left out of (2c′) they are 1.0e-3 and 9.3e-4, with
// f_{k−1} in place of f_k 2.0e-3 and 6.5e-5. The run is, bit for bit, that of
// the observer of the workaround B = I, u_k := f_k (the satellite's B is 0).
TEST(GuyaderZhang, Remark1KnownInputTermCancelsInTheErrorRecursion) {
  using Workaround = adaptobs::Dimensions<double, 4, 4, 2, 2>;
  const auto model = satellite::model<double>();
  const adaptobs::DiscreteLtiModel<Workaround> workaround_model(model.system().A, Eigen::Matrix4d::Identity(),
                                                                model.system().C);
  auto observer = make_satellite_observer<double>();
  adaptobs::GuyaderZhangObserver workaround(workaround_model, satellite::paper_gain<double>(), satellite::mu,
                                            satellite::initial_state_estimate<double>(),
                                            satellite::initial_parameter_estimate<double>());
  auto plant = make_plant_with_known_input<double>();
  const Eigen::Matrix4d closed_loop = model.system().A - satellite::paper_gain<double>() * model.system().C;
  const auto eta = [&] {
    return Eigen::Vector4d(plant.state() - observer.state() -
                           observer.upsilon() * (plant.parameters() - observer.parameters()));
  };
  double worst = 0, largest_f = 0;
  for (Index k = 0; k < 3000; ++k) {
    const auto& s = plant.sample();
    ASSERT_EQ(s.f.size(), 4);
    largest_f = std::max(largest_f, s.f.norm());
    const Eigen::Vector4d before = eta();
    ASSERT_EQ(observer.update(s), UpdateStatus::accepted);
    ASSERT_EQ(workaround.update({Eigen::Vector4d(s.f), s.y, s.Psi}), UpdateStatus::accepted);
    plant.advance();
    worst = std::max(worst, (eta() - closed_loop * before).norm());
  }
  EXPECT_LE(worst, 1e-10);
  EXPECT_LT((observer.parameters() - plant.parameters()).norm(), 1e-9);
  EXPECT_GT(largest_f, 1e-3) << "the term must be exercised";
  EXPECT_TRUE(adaptobs::testing::bitwise_equal(observer.state(), workaround.state()));
  EXPECT_TRUE(adaptobs::testing::bitwise_equal(observer.parameters(), workaround.parameters()));
  EXPECT_TRUE(adaptobs::testing::bitwise_equal(observer.upsilon(), workaround.upsilon()));
}

// The paper's example: θ̂ averaged over the last 100 s is within 0.05 of θ.
TEST(GuyaderZhang, SatelliteWithPaperNoiseRecoversThrustEfficiencies) {
  auto observer = make_satellite_observer<double>();
  auto plant = satellite::make_plant<double>();  // σ = 0.01 on both outputs
  constexpr Index steps = 3000;                  // 300 s
  Eigen::Vector2d sum = Eigen::Vector2d::Zero();
  for (Index k = 0; k < steps; ++k) {
    ASSERT_EQ(observer.update(plant.sample()), UpdateStatus::accepted);
    plant.advance();
    if (k >= steps - 1000) sum += observer.parameters();
  }
  const Eigen::Vector2d average = sum / 1000.0;
  EXPECT_NEAR(average(0), 1.0, 0.05);
  EXPECT_NEAR(average(1), 1.5, 0.05);
}

// Assumption 2 is what makes (10) stable: 5-s pulses break it and the observer
// diverges, and the diagnostic says so.
TEST(GuyaderZhang, Assumption2DiagnosticFlagsDivergentSetting) {
  {
    auto observer = make_satellite_observer<double>();
    auto plant = satellite::make_plant<double>(0.0);
    bool always = true;
    for (Index k = 0; k < 1000; ++k) {
      ASSERT_EQ(observer.update(plant.sample()), UpdateStatus::accepted);
      always = always && observer.assumption2_holds();
      plant.advance();
    }
    EXPECT_TRUE(always);
    EXPECT_GT(observer.assumption2_norm(), 0.0);
  }
  {
    satellite::PulseThrusts long_pulses;
    long_pulses.width = 5.0;
    long_pulses.period = 20.0;
    long_pulses.tangential_delay = 10.0;
    auto observer = make_satellite_observer<double>();
    auto plant = satellite::make_plant<double>(0.0, 1, long_pulses);
    bool violated = false;
    Index k = 0;
    for (; k < 3000; ++k) {
      if (observer.update(plant.sample()) != UpdateStatus::accepted) break;
      violated = violated || !observer.assumption2_holds();
      plant.advance();
    }
    EXPECT_TRUE(violated);
    EXPECT_GT((observer.parameters() - plant.parameters()).norm(), 1e3) << "expected divergence";
  }
}

// Assumption 3: without tangential thrust θ² is not identifiable and the
// excitation level falls to zero; with both thrusts it stays positive.
TEST(GuyaderZhang, ExcitationMonitorDetectsUnidentifiableParameter) {
  auto level_after = [](satellite::PulseThrusts thrusts, bool tangential) {
    auto observer = make_satellite_observer<double>({.excitation_window = 200});
    auto input = [thrusts, tangential](Index k) {
      Eigen::Vector2d u = thrusts.operator()<double>(k);
      if (!tangential) u(1) = 0;
      return u;
    };
    auto plant = adaptobs::DiscreteLinearPlant(satellite::model<double>(), satellite::initial_state<double>(),
                                               satellite::true_parameters<double>(), input,
                                               satellite::ThrustRegressor<double>{});
    for (Index k = 0; k < 1000; ++k) {
      EXPECT_EQ(observer.update(plant.sample()), UpdateStatus::accepted);
      plant.advance();
    }
    return observer.excitation_level().value();
  };
  EXPECT_GT(level_after({}, true), 1e-3);
  EXPECT_LT(level_after({}, false), 1e-12);
}

TEST(GuyaderZhang, DiagnosticsStayFiniteOrUnavailableAfterAHugeRegressor) {
  auto observer = make_satellite_observer<double>({.excitation_window = 20});
  // Samples whose output is the observer's own prediction: the innovation is zero, so
  // the estimates stay put and only Υ moves. One regressor of 1e160 is accepted (all
  // finite), and for many steps after it μ ΥᵀCᵀCΥ ≈ 1e320 is not representable.
  const auto sample = [&](double psi) {
    adaptobs::DiscreteSample<satellite::Dims<double>> s;
    s.u.setZero();
    s.y = satellite::output_matrix<double>() * observer.state();
    s.Psi.setConstant(psi);
    return s;
  };
  ASSERT_EQ(observer.update(sample(1e160)), UpdateStatus::accepted);
  int unavailable = 0;
  for (Index k = 0; k < 3000; ++k) {
    ASSERT_EQ(observer.update(sample(0)), UpdateStatus::accepted) << "step " << k;
    ASSERT_TRUE(std::isfinite(observer.assumption2_norm())) << "step " << k;
    const auto level = observer.excitation_level();
    if (level) {
      ASSERT_TRUE(std::isfinite(*level)) << "step " << k;
    } else {
      ++unavailable;
    }
  }
  EXPECT_GT(unavailable, 0);
  EXPECT_TRUE(observer.excitation_level().has_value()) << "Υ has decayed: the level is back";
}

// The observer contract (support/observer_contract.hpp) on the satellite, in
// float and double: the plant's first 40 samples, everything a user can read.
template <typename S>
struct GuyaderZhangContract {
  using Observer = decltype(make_satellite_observer<S>());
  using Sample = typename Observer::Sample;
  using InDouble = GuyaderZhangContract<double>;  // the twin of the float instance
  static Observer make() { return make_satellite_observer<S>({.excitation_window = 20}); }
  static std::vector<Sample> samples() {
    return adaptobs::testing::first_samples<Sample>(satellite::make_plant<S>(), 40);
  }
  static auto readings(const auto& o) {
    return std::make_tuple(o.state(), o.parameters(), o.upsilon(), o.step(), o.assumption2_norm(),
                           o.excitation_level());
  }
  // (2b)–(2c): the innovation y_k − C x̂_k of the prediction the update corrects.
  static typename Observer::Output expected_output_error(const Observer& before, const Observer&, const Sample& s) {
    return s.y - satellite::output_matrix<S>() * before.state();
  }
};

// The same observer, model and run with Eigen::Dynamic sizes.
struct GuyaderZhangDynamicContract : GuyaderZhangContract<double> {
  using Dims = adaptobs::DynamicDimensions<double>;
  using Observer = adaptobs::GuyaderZhangObserver<adaptobs::DiscreteLtiModel<Dims>>;
  using Sample = Observer::Sample;
  using InFixed = GuyaderZhangContract<double>;
  static Observer make() {
    const auto fixed = satellite::model<double>();
    const adaptobs::DiscreteLtiModel<Dims> model(fixed.system().A, fixed.system().B, fixed.system().C, 2);
    return Observer(model, Eigen::MatrixXd(satellite::paper_gain<double>()), satellite::mu,
                    Eigen::VectorXd(satellite::initial_state_estimate<double>()),
                    Eigen::VectorXd(satellite::initial_parameter_estimate<double>()), {.excitation_window = 20});
  }
  static std::vector<Sample> samples() {
    return adaptobs::testing::first_samples<Sample>(satellite::make_plant<double>(), 40,
                                                    [](const auto& s) { return Sample{s.u, s.y, s.Psi}; });
  }
};

// The twins on the overflow path of the normalized step: one regressor of 1e200
// at k = 10, after which ‖C̄Υ‖²_F overflows for the rest of the run, μ_k underflows,
// and the step is √μ_k C̄Υᵀ(√μ_k ε) with √μ_k C̄Υ fed to the excitation monitor.
// Both measured states see it (C picks x₁ and x₃), so that C̄Υ has rank 2 and the
// level of the monitor's window is not zero.
constexpr Index huge_regressor_step = 10;

struct GuyaderZhangNormalizedContract : GuyaderZhangContract<double> {
  static constexpr adaptobs::GuyaderZhangOptions options{.excitation_window = 5, .normalized_step = true};
  static Observer make() { return make_satellite_observer<double>(options); }
  template <class Run>
  static Run with_a_huge_regressor(Run run) {
    auto& psi = run[huge_regressor_step].Psi;
    psi.setZero();
    psi(0, 0) = psi(2, 1) = 1e200;
    return run;
  }
  static std::vector<Sample> samples() { return with_a_huge_regressor(GuyaderZhangContract<double>::samples()); }
};

struct GuyaderZhangNormalizedDynamicContract : GuyaderZhangDynamicContract {
  static constexpr const char* name = "normalized_step";
  using InFixed = GuyaderZhangNormalizedContract;
  static Observer make() {
    const auto fixed = satellite::model<double>();
    const adaptobs::DiscreteLtiModel<Dims> model(fixed.system().A, fixed.system().B, fixed.system().C, 2);
    return Observer(model, Eigen::MatrixXd(satellite::paper_gain<double>()), satellite::mu,
                    Eigen::VectorXd(satellite::initial_state_estimate<double>()),
                    Eigen::VectorXd(satellite::initial_parameter_estimate<double>()),
                    GuyaderZhangNormalizedContract::options);
  }
  static std::vector<Sample> samples() {
    return GuyaderZhangNormalizedContract::with_a_huge_regressor(GuyaderZhangDynamicContract::samples());
  }
};

}  // namespace

ADAPTOBS_OBSERVER_CONTRACT(GuyaderZhang, GuyaderZhangContract<float>, GuyaderZhangContract<double>);
ADAPTOBS_TWIN_CONTRACT(GuyaderZhang, FloatFollowsDouble, GuyaderZhangContract<float>);
ADAPTOBS_TWIN_CONTRACT(GuyaderZhang, DynamicFollowsFixed, GuyaderZhangDynamicContract,
                       GuyaderZhangNormalizedDynamicContract);

namespace {

// x_{k+1} = x_k/2 + Ψ_kθ, y = x (n = p = 2, K = 0, μ = 1, the normalized step), with
// Ψ_0 = 1e200·I and Ψ_k = 0 after: Υ_k = 2^{1−k}·1e200·I for k ≥ 1, so ‖C̄Υ_k‖²_F
// overflows for a hundred steps, and μ_k = 1/‖C̄Υ_k‖²_F underflows.
template <bool fixed>
auto halving_observer(const Eigen::Vector2d& theta0) {
  using D = std::conditional_t<fixed, adaptobs::Dimensions<double, 2, 1, 2, 2>, adaptobs::DynamicDimensions<double>>;
  using Matrix = std::conditional_t<fixed, Eigen::Matrix2d, Eigen::MatrixXd>;
  using Vector = std::conditional_t<fixed, Eigen::Vector2d, Eigen::VectorXd>;
  const Matrix identity = Eigen::Matrix2d::Identity();
  const adaptobs::DiscreteLtiModel<D> model = [&] {
    if constexpr (fixed) {
      return adaptobs::DiscreteLtiModel<D>(0.5 * identity, Eigen::Vector2d::Zero(), identity);
    } else {
      return adaptobs::DiscreteLtiModel<D>(0.5 * identity, Eigen::MatrixXd::Zero(2, 1), identity, 2);
    }
  }();
  return adaptobs::GuyaderZhangObserver(model, Matrix(Matrix::Zero(2, 2)), 1.0, Vector(Vector::Zero(2)), Vector(theta0),
                                        {.excitation_window = 3, .normalized_step = true});
}

template <class Observer>
UpdateStatus halving_step(Observer& observer, Index k) {
  typename Observer::Sample s{Observer::Input::Zero(1), Observer::Output::Zero(2),
                              Observer::RegressorMatrix::Zero(2, 2)};
  if (k == 0) s.Psi.diagonal().setConstant(1e200);
  return observer.update(s);
}

// At k = 1, x̂_1 = Ψ_0θ̂_0 = 1e200·θ̂_0 and ε_1 = −x̂_1: the normalized step
// √μ_1 C̄Υ_1ᵀ(√μ_1 ε_1), with √μ_1 = 1/(√2·1e200), is −θ̂_0/2 whatever the size type.
// The dynamic twin took √μ_1 out of the product, after C̄Υ_1ᵀε_1 = −1e400 had
// overflowed, and refused every sample from k = 1 on.
TEST(GuyaderZhang, TheNormalizedStepBeyondTheFloatingPointRangeIsTheSameWithRunTimeSizes) {
  const Eigen::Vector2d theta0(1, 3);
  auto fixed = halving_observer<true>(theta0);
  auto dynamic = halving_observer<false>(theta0);
  for (Index k = 0; k < 2; ++k) {
    ASSERT_EQ(halving_step(fixed, k), UpdateStatus::accepted) << "k = " << k;
    ASSERT_EQ(halving_step(dynamic, k), UpdateStatus::accepted) << "k = " << k;
  }
  EXPECT_MATRIX_NEAR(fixed.parameters(), Eigen::Vector2d(0.5, 1.5), 1e-15, 0);
  EXPECT_MATRIX_NEAR(dynamic.parameters(), Eigen::Vector2d(0.5, 1.5), 1e-15, 0);
  for (Index k = 2; k < 40; ++k) {
    ASSERT_EQ(halving_step(fixed, k), UpdateStatus::accepted) << "k = " << k;
    ASSERT_EQ(halving_step(dynamic, k), UpdateStatus::accepted) << "k = " << k;
  }
  EXPECT_MATRIX_NEAR(dynamic.parameters(), fixed.parameters(), 1e-15, 0);
  EXPECT_MATRIX_NEAR(dynamic.state(), fixed.state(), 0, 1e-14);
}

// The excitation monitor is fed √μ_k C̄Υ_k = I/√2 at every step from k = 1 on, so
// the level is exactly 1/2. For dynamic sizes it was fed the previous step's C̄Υ
// scaled by this step's √μ_k, twice too large: a level of 2.
TEST(GuyaderZhang, TheMonitorSeesThisStepsRegressorWhenTheStepSizeUnderflows) {
  auto fixed = halving_observer<true>(Eigen::Vector2d::Zero());
  auto dynamic = halving_observer<false>(Eigen::Vector2d::Zero());
  for (Index k = 0; k < 20; ++k) {
    ASSERT_EQ(halving_step(fixed, k), UpdateStatus::accepted) << "k = " << k;
    ASSERT_EQ(halving_step(dynamic, k), UpdateStatus::accepted) << "k = " << k;
    if (k < 3) continue;  // the window holds the steps 1 to k
    ASSERT_TRUE(fixed.excitation_level().has_value() && dynamic.excitation_level().has_value()) << "k = " << k;
    EXPECT_NEAR(*fixed.excitation_level(), 0.5, 1e-15) << "k = " << k;
    EXPECT_NEAR(*dynamic.excitation_level(), 0.5, 1e-15) << "k = " << k;
    EXPECT_NEAR(dynamic.assumption2_norm(), std::sqrt(0.5), 1e-15) << "k = " << k;
  }
}

using adaptobs::testing::configuration_error_of;

// With run-time sizes A fixes nx: a B or C that disagrees with it is the one
// blamed, and the message says where nx came from.
TEST(GuyaderZhang, WithRunTimeSizesTheOrderOfAFixesNxAndTheRefusalSaysSo) {
  using Model = adaptobs::DiscreteLtiModel<adaptobs::DynamicDimensions<double>>;
  const Eigen::MatrixXd A = Eigen::MatrixXd::Identity(3, 3);
  EXPECT_EQ(configuration_error_of([&] { Model(A, Eigen::MatrixXd::Zero(4, 1), Eigen::MatrixXd::Zero(1, 3), 1); }),
            "DiscreteLtiModel: argument 'B' must be 3x1 (got 4x1): nx = 3 is the order of A");
  EXPECT_EQ(configuration_error_of([&] { Model(A, Eigen::MatrixXd::Zero(3, 1), Eigen::MatrixXd::Zero(1, 4), 1); }),
            "DiscreteLtiModel: argument 'C' must be 1x3 (got 1x4): nx = 3 is the order of A");
}

TEST(GuyaderZhang, ATimeVaryingModelOfWrongSizesAtAStepIsRefusedAndChangesNothing) {
  adaptobs::testing::expect_resized_step_refused([](auto model) {
    return adaptobs::GuyaderZhangObserver(std::move(model), Eigen::MatrixXd::Constant(2, 1, 0.3), 0.5,
                                          Eigen::VectorXd::Zero(2), Eigen::VectorXd::Zero(1));
  });
}

TEST(GuyaderZhang, BadConfigurationNamesTheArgument) {
  const auto model = satellite::model<double>();
  const Eigen::Matrix<double, 4, 2> k = satellite::paper_gain<double>();
  const Eigen::Vector4d x0 = Eigen::Vector4d::Zero();
  const Eigen::Vector2d th0 = Eigen::Vector2d::Zero();
  for (double mu : {0.0, -1.0, std::numeric_limits<double>::quiet_NaN()}) {
    const std::string message =
        configuration_error_of([&] { adaptobs::GuyaderZhangObserver o(model, k, mu, x0, th0); });
    EXPECT_NE(message.find("'mu'"), std::string::npos) << message;
  }
  // A parameter count other than the compile-time one (θ̂ is sized by the type).
  using SatelliteDims = std::remove_cvref_t<decltype(model)>::Dims;
  EXPECT_CONFIGURATION_ERROR_NAMES(
      (adaptobs::DiscreteLtiModel<SatelliteDims>(model.system().A, model.system().B, model.system().C, 3)), "np");
  auto observer = make_satellite_observer<double>();
  EXPECT_NE(configuration_error_of([&] { observer.set_mu(0.0); }).find("'mu'"), std::string::npos);
  Eigen::Matrix<double, 4, 2> nan_gain = k;
  nan_gain(0, 0) = std::nan("");
  EXPECT_NE(configuration_error_of([&] { observer.set_gain(nan_gain); }).find("'K'"), std::string::npos);

  // Mismatched run-time sizes with dynamic dimensions.
  using DynDims = adaptobs::DynamicDimensions<double>;
  const adaptobs::DiscreteLtiModel<DynDims> dynamic_model(model.system().A, model.system().B, model.system().C, 2);
  const Eigen::MatrixXd good_k = k;
  const Eigen::VectorXd good_x = x0, good_th = th0;
  EXPECT_NE(configuration_error_of([&] {
              adaptobs::GuyaderZhangObserver o(dynamic_model, Eigen::MatrixXd(3, 2), 1.0, good_x, good_th);
            }).find("'K'"),
            std::string::npos);
  EXPECT_NE(configuration_error_of([&] {
              adaptobs::GuyaderZhangObserver o(dynamic_model, good_k, 1.0, Eigen::VectorXd(5), good_th);
            }).find("'x0'"),
            std::string::npos);
  EXPECT_NE(configuration_error_of([&] {
              adaptobs::GuyaderZhangObserver o(dynamic_model, good_k, 1.0, good_x, Eigen::VectorXd(3));
            }).find("'theta0'"),
            std::string::npos);
  adaptobs::GuyaderZhangObserver dynamic(dynamic_model, good_k, 1.0, good_x, good_th);
  const adaptobs::DiscreteSample<DynDims> short_y{Eigen::VectorXd::Zero(2), Eigen::VectorXd::Zero(1),
                                                  Eigen::MatrixXd::Zero(4, 2)};
  EXPECT_NE(configuration_error_of([&] { (void)dynamic.update(short_y); }).find("'sample.y'"), std::string::npos);
  EXPECT_EQ(dynamic.step(), 0);
  // A known input term of neither nx entries nor none, whatever the sizes.
  const adaptobs::DiscreteSample<DynDims> long_f{Eigen::VectorXd::Zero(2), Eigen::VectorXd::Zero(2),
                                                 Eigen::MatrixXd::Zero(4, 2), Eigen::VectorXd::Zero(5)};
  EXPECT_EQ(configuration_error_of([&] { (void)dynamic.update(long_f); }),
            "GuyaderZhangObserver::update: argument 'sample.f' must have nx = 4 entries, or none for no known "
            "input term (got 5)");
  EXPECT_EQ(dynamic.step(), 0);
  auto short_f = satellite::make_plant<double>().sample();
  short_f.f.setZero(3);
  EXPECT_CONFIGURATION_ERROR_NAMES((void)observer.update(short_f), "sample.f");
  EXPECT_EQ(observer.step(), 0);
  EXPECT_NE(configuration_error_of([&] {
              adaptobs::DiscreteLtiModel<DynDims> m(Eigen::MatrixXd::Identity(3, 3), Eigen::MatrixXd::Zero(3, 1),
                                                    Eigen::MatrixXd::Zero(1, 4), 1);
            }).find("'C'"),
            std::string::npos);
}

static_assert(adaptobs::Observer<decltype(make_satellite_observer<double>())>);
static_assert(adaptobs::Observer<decltype(make_satellite_observer<float>())>);

}  // namespace
