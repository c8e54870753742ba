// snapshot() and restore() (core/snapshot.hpp): an observer restored from a
// snapshot continues bit for bit like the original; a snapshot of another
// class, version or configuration is refused with the object unchanged.

#include <adaptobs/baselines/augmented_kalman.hpp>
#include <adaptobs/core/snapshot.hpp>
#include <adaptobs/diagnostics/fault_monitor.hpp>
#include <adaptobs/observers/guiro.hpp>
#include <adaptobs/observers/guyader_zhang.hpp>
#include <adaptobs/observers/takagi_sugeno.hpp>

#include "models/dey_bhasin.hpp"
#include "models/guiro.hpp"
#include "models/satellite.hpp"
#include "models/unified_designs.hpp"
#include "models/wwtp.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <string>

// A named namespace: in the unity build of the test executable, the anonymous
// namespaces of its files are one.
namespace snapshot_test {

using adaptobs::Index;
using adaptobs::UpdateStatus;
namespace satellite = adaptobs::examples::satellite;

auto make_observer(Index window = 50) {
  return adaptobs::GuyaderZhangObserver(satellite::model<double>(), satellite::paper_gain<double>(), satellite::mu,
                                        satellite::initial_state_estimate<double>(),
                                        satellite::initial_parameter_estimate<double>(),
                                        {.excitation_window = window, .normalized_step = true});
}

auto make_filter() {
  using Matrix6 = Eigen::Matrix<double, 6, 6>;
  Matrix6 p0 = Matrix6::Zero();
  p0.diagonal() << 0.1, 1e-4, 0.1, 1e-4, 1.0, 1.0;
  const Matrix6 q = Matrix6::Identity() * 1e-10;
  return adaptobs::AugmentedKalmanFilter(satellite::model<double>(), satellite::initial_state_estimate<double>(),
                                         satellite::initial_parameter_estimate<double>(),
                                         {p0, q, Eigen::Matrix2d::Identity() * 1e-4});
}

// Runs `observer` over `steps` samples of `plant`, every 7th missing its second output.
template <class Observer, class Plant>
void run(Observer& observer, Plant& plant, Index steps) {
  for (Index k = 0; k < steps; ++k) {
    const adaptobs::OutputMask<satellite::Dims<double>> present(true, plant.step() % 7 != 3);
    ASSERT_EQ(observer.update(plant.sample(), present), UpdateStatus::accepted);
    plant.advance();
  }
}

template <class Observer>
void expect_identical(const Observer& a, const Observer& b) {
  EXPECT_EQ(a.state(), b.state());
  EXPECT_EQ(a.parameters(), b.parameters());
  EXPECT_EQ(a.output_error(), b.output_error());
  EXPECT_EQ(a.step(), b.step());
}

TEST(Snapshot, ARestoredGuyaderZhangObserverContinuesBitForBit) {
  auto plant = satellite::make_plant();
  auto original = make_observer();
  run(original, plant, 700);  // past the excitation window, so its ring has wrapped
  const auto state = adaptobs::snapshot(original);
  EXPECT_EQ(state.type, "GuyaderZhangObserver");
  EXPECT_EQ(state.version, 1);

  // Restored into an observer built with other estimates (same sizes and options).
  auto restored = adaptobs::GuyaderZhangObserver(satellite::model<double>(), satellite::paper_gain<double>(), 1.0,
                                                 Eigen::Vector4d::Zero(), Eigen::Vector2d::Zero(),
                                                 {.excitation_window = 50, .normalized_step = true});
  adaptobs::restore(restored, state);
  expect_identical(original, restored);
  EXPECT_EQ(restored.mu(), satellite::mu);
  EXPECT_EQ(restored.assumption2_norm(), original.assumption2_norm());
  EXPECT_EQ(restored.excitation_level(), original.excitation_level());

  auto plant_copy = plant;
  run(original, plant, 900);
  run(restored, plant_copy, 900);
  expect_identical(original, restored);
  EXPECT_EQ(original.upsilon(), restored.upsilon());
  EXPECT_EQ(original.assumption2_norm(), restored.assumption2_norm());
  ASSERT_TRUE(original.excitation_level().has_value());
  EXPECT_EQ(*original.excitation_level(), *restored.excitation_level());
}

TEST(Snapshot, ARestoredAugmentedKalmanFilterContinuesBitForBit) {
  auto plant = satellite::make_plant();
  auto original = make_filter();
  run(original, plant, 300);
  auto restored = make_filter();
  adaptobs::restore(restored, adaptobs::snapshot(original));
  auto plant_copy = plant;
  run(original, plant, 300);
  run(restored, plant_copy, 300);
  expect_identical(original, restored);
  EXPECT_EQ(original.covariance(), restored.covariance());
}

// Every refusal names its reason, and the observer is exactly as before.
template <class Mutate>
std::string refusal(Mutate mutate) {
  auto plant = satellite::make_plant();
  auto source = make_observer();
  run(source, plant, 120);
  auto state = adaptobs::snapshot(source);
  mutate(state);
  auto target = make_observer();
  const auto before = adaptobs::snapshot(target);
  std::string message;
  try {
    adaptobs::restore(target, state);
  } catch (const adaptobs::ConfigurationError& e) {
    message = e.what();
  }
  const auto after = adaptobs::snapshot(target);
  EXPECT_EQ(before.matrices.size(), after.matrices.size());
  for (std::size_t i = 0; i < before.matrices.size(); ++i)
    EXPECT_EQ(before.matrices[i].values, after.matrices[i].values) << before.matrices[i].name;
  for (std::size_t i = 0; i < before.integers.size(); ++i)
    EXPECT_EQ(before.integers[i].value, after.integers[i].value) << before.integers[i].name;
  return message;
}

TEST(Snapshot, ASnapshotOfAnotherClassVersionOrConfigurationIsRefusedAndChangesNothing) {
  EXPECT_EQ(refusal([](auto& s) { s.type = "AugmentedKalmanFilter"; }),
            "restore: argument 'snapshot' is of a AugmentedKalmanFilter, not of a GuyaderZhangObserver");
  EXPECT_EQ(refusal([](auto& s) { s.version = 2; }),
            "restore: argument 'snapshot' is version 2 of GuyaderZhangObserver; this build reads version 1");
  EXPECT_EQ(refusal([](auto& s) { s.integers.pop_back(); }),
            "restore: argument 'snapshot' has no field 'health.consecutive_refusals'");
  EXPECT_EQ(refusal([](auto& s) {
              for (auto& i : s.integers)
                if (i.name == "excitation_window") i.value = 10;
            }),
            "restore: argument 'snapshot' holds 'excitation_window' = 10 where this GuyaderZhangObserver has 50: "
            "restore into an object built with the same configuration");
  EXPECT_EQ(refusal([](auto& s) {
              for (auto& m : s.matrices)
                if (m.name == "theta") m = {"theta", 3, 1, {1, 2, 3}};
            }),
            "restore: argument 'snapshot' holds field 'theta' of 3x1 where this GuyaderZhangObserver has 2x1");
  // A field read late (the excitation window's position) refused after earlier ones were read.
  EXPECT_EQ(refusal([](auto& s) {
              for (auto& i : s.integers)
                if (i.name == "excitation.next") i.value = 50;
            }),
            "restore: argument 'snapshot' holds an excitation window position outside the window");
}

// What an observer hands a fault monitor: its parameters and output error.
struct FakeObserver {
  using Scalar = double;
  using State = Eigen::Vector2d;
  using Parameters = Eigen::Vector2d;
  using Dims = adaptobs::Dimensions<double, 2, 2, 2, 2>;
  using Sample = int;
  Eigen::Vector2d theta, error;
  const State& state() const { return theta; }
  const Parameters& parameters() const { return theta; }
  const Eigen::Vector2d& output_error() const { return error; }
  UpdateStatus update(const Sample&) { return UpdateStatus::accepted; }
  void reset(const State&, const Parameters&) {}
};

TEST(Snapshot, ARestoredFaultMonitorContinuesBitForBit) {
  adaptobs::FaultMonitorDesign<double, 2, 2> design;
  design.nominal = Eigen::Vector2d(1.0, 1.5);
  design.cusum.scale = Eigen::Vector2d(0.01, 0.02);
  design.cusum.drift = 0.5;
  design.cusum.threshold = 6.0;
  design.cusum_options = {.stride = 3, .hold_off = 2, .reanchor = false};
  design.glr_window = 7;
  design.glr_threshold = 9.0;
  design.output_error_covariance = Eigen::Matrix2d::Identity() * 1e-4;
  design.window = 5;
  design.false_alarm_probability = 0.01;
  std::mt19937_64 rng(11);
  std::normal_distribution<double> normal;
  // Normal around nominal; from sample 300 on, the second parameter shifted by two
  // scales and the output errors three times as large.
  std::vector<FakeObserver> values;
  for (int k = 0; k < 900; ++k) {
    const double shift = k >= 300 ? 2.0 : 0.0;
    values.push_back({design.nominal + Eigen::Vector2d(0.01 * normal(rng), 0.02 * (normal(rng) + shift)),
                      Eigen::Vector2d(0.01 * normal(rng), 0.01 * normal(rng) * (1 + shift))});
  }
  adaptobs::FaultMonitor<double, 2, 2> original(design);
  for (int k = 0; k < 400; ++k) ASSERT_EQ(original.observe(values[k]), UpdateStatus::accepted);
  adaptobs::FaultMonitor<double, 2, 2> restored(design);
  adaptobs::restore(restored, adaptobs::snapshot(original));
  Index alarms = 0;
  for (int k = 400; k < 900; ++k) {
    ASSERT_EQ(original.observe(values[k]), restored.observe(values[k]));
    ASSERT_EQ(original.cusum().alarm(), restored.cusum().alarm()) << k;
    ASSERT_EQ(original.glr().alarm(), restored.glr().alarm()) << k;
    ASSERT_EQ(original.chi_square().alarm(), restored.chi_square().alarm()) << k;
    ASSERT_EQ(original.cusum().statistic(), restored.cusum().statistic()) << k;
    ASSERT_EQ(original.glr().statistic(), restored.glr().statistic()) << k;
    ASSERT_EQ(original.chi_square().statistic(), restored.chi_square().statistic()) << k;
    alarms += original.cusum().alarm() + original.glr().alarm() + original.chi_square().alarm();
  }
  EXPECT_GT(alarms, 10);  // the shift is seen: the comparison covers alarms and their hold-off
  EXPECT_EQ(original.cusum().isolated(), restored.cusum().isolated());
  EXPECT_EQ(original.cusum().alarm_count(), restored.cusum().alarm_count());
  // Estimates of the wrong size are refused by name, with the monitor unchanged.
  const auto before = adaptobs::snapshot(restored);
  EXPECT_THROW((void)restored.observe(Eigen::VectorXd::Zero(3), Eigen::VectorXd::Zero(2)),
               adaptobs::ConfigurationError);
  EXPECT_EQ(adaptobs::snapshot(restored).integers.back().value, before.integers.back().value);
  // A snapshot from a monitor of another stride is refused.
  auto other_design = design;
  other_design.cusum_options.stride = 4;
  adaptobs::FaultMonitor<double, 2, 2> other(other_design);
  EXPECT_THROW(adaptobs::restore(other, adaptobs::snapshot(original)), adaptobs::ConfigurationError);
}

// Dey–Bhasin (covariance resetting) and Suzuki (forgetting) on the MIMO example
// of Dey & Bhasin (2022) §5: restored at step 150, past the first covariance resets.
template <class Observer>
void expect_filter_observer_continues(Observer original) {
  namespace mimo = adaptobs::examples::dey_bhasin::mimo;
  auto plant = mimo::make_plant(mimo::RichInput{});
  const auto feed = [&](Observer& o, auto& p, Index steps) {
    for (Index k = 0; k < steps; ++k, p.advance()) ASSERT_EQ(o.update(p.sample()), UpdateStatus::accepted);
  };
  feed(original, plant, 150);
  Observer restored = original;
  restored.reset(Observer::State::Zero(), Observer::Parameters::Zero());
  adaptobs::restore(restored, adaptobs::snapshot(original));
  EXPECT_EQ(restored.state(), original.state());
  EXPECT_EQ(restored.step(), original.step());
  auto plant_copy = plant;
  feed(original, plant, 200);
  feed(restored, plant_copy, 200);
  EXPECT_EQ(original.state(), restored.state());
  EXPECT_EQ(original.parameters(), restored.parameters());
  EXPECT_EQ(original.law().covariance(), restored.law().covariance());
  EXPECT_EQ(original.output_error(), restored.output_error());
  if constexpr (requires { original.law().reset_count(); }) {
    EXPECT_GT(original.law().reset_count(), 0);
    EXPECT_EQ(original.law().reset_count(), restored.law().reset_count());
    EXPECT_EQ(original.law().reset_tests_run(), restored.law().reset_tests_run());
  }
}

TEST(Snapshot, RestoredDeyBhasinAndSuzukiObserversContinueBitForBit) {
  namespace mimo = adaptobs::examples::dey_bhasin::mimo;
  expect_filter_observer_continues(mimo::make_observer());
  const auto dey_bhasin = mimo::make_observer();
  using Suzuki = adaptobs::SuzukiObserver<double, mimo::order, mimo::outputs, mimo::inputs>;
  const Suzuki suzuki(mimo::f(), mimo::x_hat0(), mimo::a_hat0(), mimo::B_hat0(),
                      {.gamma0 = Suzuki::Parameters::Constant(1.0).asDiagonal() * 1000.0,
                       .R = Eigen::Matrix2d::Identity(),
                       .lambda = 0.98});
  expect_filter_observer_continues(suzuki);
  EXPECT_EQ(adaptobs::snapshot(suzuki).type, "SuzukiObserver");
  EXPECT_EQ(adaptobs::snapshot(dey_bhasin).type, "DeyBhasinObserver");
}

TEST(Snapshot, ARestoredGuiroObserverContinuesBitForBit) {
  namespace g = adaptobs::examples::guiro;
  const auto make = [] {
    return adaptobs::GuiroObserver(g::model<double>(), Eigen::Vector2d(g::printed_K()),
                                   Eigen::Matrix<double, 1, 1>(g::corrected_printed_Gamma),
                                   g::initial_state_estimate<double>(), g::initial_parameter_estimate<double>());
  };
  auto plant = g::make_plant();
  auto original = make();
  for (int k = 0; k < 7; ++k, plant.advance()) ASSERT_EQ(original.update(plant.sample()), UpdateStatus::accepted);
  auto restored = make();  // not started: the first sample's correction would differ
  adaptobs::restore(restored, adaptobs::snapshot(original));
  auto plant_copy = plant;
  for (int k = 0; k < 30; ++k, plant.advance(), plant_copy.advance()) {
    ASSERT_EQ(original.update(plant.sample()), restored.update(plant_copy.sample()));
    ASSERT_EQ(original.state(), restored.state());
    ASSERT_EQ(original.corrected_state(), restored.corrected_state());
    ASSERT_EQ(original.parameters(), restored.parameters());
  }
}

// The four continuous-time observers of the unified formulation (Zhang 2005), on
// the third-order plant: restored after 120 samples, past the learned step limit.
template <class Observer>
void expect_continuous_observer_continues(Observer original, Observer restored) {
  namespace siso = adaptobs::examples::siso;
  auto plant = siso::make_plant<double>();
  ASSERT_EQ(original.update(plant.sample()), UpdateStatus::accepted);
  for (int k = 0; k < 120; ++k) {
    plant.advance();
    ASSERT_EQ(original.update(plant.sample()), UpdateStatus::accepted);
  }
  adaptobs::restore(restored, adaptobs::snapshot(original));
  EXPECT_EQ(restored.internal_state(), original.internal_state());
  EXPECT_EQ(restored.time(), original.time());
  for (int k = 0; k < 200; ++k) {
    plant.advance();
    ASSERT_EQ(original.update(plant.sample()), restored.update(plant.sample()));
    ASSERT_EQ(original.internal_state(), restored.internal_state()) << k;
  }
  EXPECT_EQ(original.state(), restored.state());
  EXPECT_EQ(original.parameters(), restored.parameters());
  EXPECT_EQ(original.output_error(), restored.output_error());
  if constexpr (requires { original.excitation_level(); }) {
    EXPECT_EQ(original.excitation_level(), restored.excitation_level());
  }
}

TEST(Snapshot, RestoredContinuousTimeObserversContinueBitForBit) {
  namespace designs = adaptobs::examples::designs;
  const adaptobs::UnifiedObserverOptions options{.sampling = designs::quadratic(), .excitation_window = 30};
  expect_continuous_observer_continues(designs::bastin_gevers_observer<double>(options),
                                       designs::bastin_gevers_observer<double>(options));
  expect_continuous_observer_continues(designs::marino_tomei_observer<double>(options),
                                       designs::marino_tomei_observer<double>(options));
  expect_continuous_observer_continues(designs::siso_besancon_observer<double>(options),
                                       designs::siso_besancon_observer<double>(options));
  expect_continuous_observer_continues(designs::siso_zhang_observer<double>(options),
                                       designs::siso_zhang_observer<double>(options));
  expect_continuous_observer_continues(designs::kalman_bucy_filter<double>(1e-2),
                                       designs::kalman_bucy_filter<double>(1e-2));
  EXPECT_EQ(adaptobs::snapshot(designs::marino_tomei_observer<double>()).type, "MarinoTomeiObserver");
  // An observer of another sampling option refuses the snapshot.
  auto hold = designs::bastin_gevers_observer<double>({.sampling = {}, .excitation_window = 30});
  EXPECT_THROW(adaptobs::restore(hold, adaptobs::snapshot(designs::bastin_gevers_observer<double>(options))),
               adaptobs::ConfigurationError);
}

}  // namespace snapshot_test

// The Takagi–Sugeno observer (65) on the waste water plant of §6, and (21) with
// the leakage K_theta: restored mid-run into an observer of other gains and
// estimates, it continues bit for bit at every later step, samples with a lost
// output included; the gains come back as given.

namespace snapshot_test_takagi_sugeno {

using adaptobs::Index;
using adaptobs::UpdateStatus;

namespace wwtp = adaptobs::examples::wwtp;
using Mask = adaptobs::OutputMask<wwtp::Dims<double>>;

// Every 9th output lost (a time update).
Mask present_at(Index k) { return Mask::Constant(1, k % 9 != 4); }

auto make_observer(bool leakage, double gain_scale = 1.0, double x1 = 3.0) {
  auto gains = wwtp::paper_gains<double>();
  for (auto& L : gains.L) L *= gain_scale;
  if (leakage) gains.K_theta = wwtp::Vector1<double>(1e-3 * gain_scale);
  return adaptobs::TakagiSugenoObserver(wwtp::model<double>(), gains, Eigen::Vector2d(x1, 0.6),
                                        wwtp::initial_parameter_estimate<double>());
}

template <class Observer>
void expect_continues(Observer original, Observer restored) {
  auto plant = wwtp::make_plant<double>(0.1);
  for (Index k = 0; k < 150; ++k, plant.advance())
    ASSERT_EQ(original.update(plant.sample(), present_at(k)), UpdateStatus::accepted);
  const auto state = adaptobs::snapshot(original);
  EXPECT_EQ(state.type, "TakagiSugenoObserver");
  ASSERT_NE(state.find_matrix("L[7]"), nullptr);
  ASSERT_NE(state.find_matrix("K_y[0]"), nullptr);
  ASSERT_NE(state.find_matrix("model.A"), nullptr);
  adaptobs::restore(restored, state);
  const auto given = original.gains(), read = restored.gains();
  for (std::size_t i = 0; i < given.L.size(); ++i) {
    EXPECT_EQ(given.L[i], read.L[i]);
    EXPECT_EQ(given.K[i], read.K[i]);
  }
  EXPECT_EQ(given.K_theta, read.K_theta);
  EXPECT_EQ(original.weights(), restored.weights());
  EXPECT_EQ(original.premises(), restored.premises());
  for (Index k = 150; k < 500; ++k, plant.advance()) {
    const auto mask = present_at(k);
    ASSERT_EQ(original.update(plant.sample(), mask), restored.update(plant.sample(), mask));
    ASSERT_EQ(original.state(), restored.state()) << k;
    ASSERT_EQ(original.parameters(), restored.parameters()) << k;
    ASSERT_EQ(original.weights(), restored.weights()) << k;
    ASSERT_EQ(original.premises(), restored.premises()) << k;
    ASSERT_EQ(original.output_error(), restored.output_error()) << k;
    ASSERT_EQ(original.step(), restored.step()) << k;
    ASSERT_EQ(original.premises_in_sectors(), restored.premises_in_sectors()) << k;
  }
  // The run moved the estimates: θ̂ near the true 0.1, not the initial 0.
  EXPECT_LT(std::abs(original.parameters()(0) - 0.1), 0.01);
}

TEST(Snapshot, ARestoredTakagiSugenoObserverContinuesBitForBit) {
  expect_continues(make_observer(false), make_observer(false, 0.5, 1.0));
  expect_continues(make_observer(true), make_observer(true, 0.5, 1.0));
}

TEST(Snapshot, ATakagiSugenoSnapshotOfOtherGainsOrSectorsIsRefusedAndChangesNothing) {
  const auto leaky = adaptobs::snapshot(make_observer(true));
  auto plain = make_observer(false, 0.5);
  const auto before = adaptobs::snapshot(plain);
  const auto message = [&](const adaptobs::Snapshot<double>& s) {
    try {
      adaptobs::restore(plain, s);
    } catch (const adaptobs::ConfigurationError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_EQ(message(leaky),
            "restore: argument 'snapshot' holds 'has_leakage' = 1 where this TakagiSugenoObserver has 0: "
            "restore into an object built with the same configuration");
  auto bad_gain = adaptobs::snapshot(make_observer(false));
  bad_gain.matrices[static_cast<std::size_t>(bad_gain.find_matrix("L[2]") - bad_gain.matrices.data())].values[1] =
      std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(message(bad_gain), "restore: argument 'gains.L[2]' must contain only finite numbers");
  auto bad_sector = adaptobs::snapshot(make_observer(false));
  for (auto& m : bad_sector.matrices)
    if (m.name == "model.parameter_bounds.upper") m.values[0] = -0.5;  // below the lower bound
  EXPECT_NE(message(bad_sector).find("snapshot field 'parameter_bounds'"), std::string::npos);
  // Nothing changed: the gains are still the halved ones.
  const auto after = adaptobs::snapshot(plain);
  ASSERT_EQ(before.matrices.size(), after.matrices.size());
  for (std::size_t i = 0; i < before.matrices.size(); ++i)
    EXPECT_EQ(before.matrices[i].values, after.matrices[i].values) << before.matrices[i].name;
  EXPECT_EQ(plain.gains().L[0], 0.5 * wwtp::paper_gains<double>().L[0]);
}

}  // namespace snapshot_test_takagi_sugeno
