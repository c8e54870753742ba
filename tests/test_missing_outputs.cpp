// Missing and partial outputs (`OutputMask`). Guyader–Zhang (file comment of
// observers/guyader_zhang.hpp): all channels present is the plain update bit
// for bit; no channel is the time update of the error analysis; the satellite
// of Guyader & Zhang (2003) §4 keeps its accuracy with random drops and an outage, where
// skipping the samples does not; an LTV model stays in phase. The augmented
// Kalman filter: a mask is the Kalman correction with the present rows of C
// and the present block of R. `update_finite_outputs`: a glitch in y is the
// masked update without that channel. (Dey–Bhasin: test_dey_bhasin_mimo.cpp.)
#include <adaptobs/baselines/augmented_kalman.hpp>
#include <adaptobs/core/discrete_model.hpp>
#include <adaptobs/core/observer.hpp>
#include <adaptobs/observers/guyader_zhang.hpp>
#include <adaptobs/simulation/discrete_plant.hpp>

#include "models/satellite.hpp"
#include "support/eigen_testing.hpp"
#include "support/ltv_test_system.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <string>
#include <vector>

namespace {

using adaptobs::Index;
using adaptobs::UpdateStatus;
namespace satellite = adaptobs::examples::satellite;
using SatelliteDims = adaptobs::Dimensions<double, 4, 2, 2, 2>;
using Mask = adaptobs::OutputMask<SatelliteDims>;

auto make_observer(adaptobs::GuyaderZhangOptions options = {}) {
  return adaptobs::GuyaderZhangObserver(satellite::model<double>(), satellite::paper_gain<double>(), satellite::mu,
                                        satellite::initial_state_estimate<double>(),
                                        satellite::initial_parameter_estimate<double>(), options);
}

using adaptobs::testing::bitwise_equal;

// What happens to the samples marked missing: a time update, or no call at all.
enum class Gap { time_update, skip };

struct SatelliteRun {
  Eigen::Vector2d mean_parameters;  // θ̂ averaged over the last 100 s
  double mean_state_error = 0;      // ‖x̂ − x‖ averaged over the last 100 s
  std::vector<double> state_error;  // ‖x̂_k − x_k‖ before each sample
  double worst_assumption2 = 0;     // largest ‖√μ_k C̄_kΥ_k‖₂
};

// 300 s of the noisy satellite (σ = 0.01, the paper's seed); `missing(k)` marks
// the samples whose outputs are lost.
template <class Missing>
SatelliteRun run_satellite(Missing missing, Gap gap, adaptobs::GuyaderZhangOptions options = {}) {
  auto observer = make_observer(options);
  auto plant = satellite::make_plant<double>();
  constexpr Index steps = 3000, tail = 1000;
  SatelliteRun r;
  r.mean_parameters.setZero();
  for (Index k = 0; k < steps; ++k) {
    r.state_error.push_back((observer.state() - plant.state()).norm());
    if (!missing(k)) {
      EXPECT_EQ(observer.update(plant.sample()), UpdateStatus::accepted);
    } else if (gap == Gap::time_update) {
      EXPECT_EQ(observer.update(plant.sample(), Mask::Constant(false)), UpdateStatus::accepted);
    }
    r.worst_assumption2 = std::max(r.worst_assumption2, observer.assumption2_norm());
    plant.advance();
    if (k >= steps - tail) {
      r.mean_parameters += observer.parameters() / double(tail);
      r.mean_state_error += (observer.state() - plant.state()).norm() / double(tail);
    }
  }
  return r;
}

TEST(GuyaderZhangMissing, AllChannelsPresentIsTheUpdateBitForBit) {
  auto plain = make_observer(), masked = make_observer();
  auto plant = satellite::make_plant<double>();
  for (Index k = 0; k < 500; ++k) {
    ASSERT_EQ(plain.update(plant.sample()), UpdateStatus::accepted);
    ASSERT_EQ(masked.update(plant.sample(), Mask::Constant(true)), UpdateStatus::accepted);
    plant.advance();
  }
  EXPECT_TRUE(bitwise_equal(plain.state(), masked.state()));
  EXPECT_TRUE(bitwise_equal(plain.parameters(), masked.parameters()));
  EXPECT_TRUE(bitwise_equal(plain.upsilon(), masked.upsilon()));
  EXPECT_EQ(plain.step(), masked.step());
}

// No channel: Υ ← AΥ + Ψ (not A − KC), θ̂ kept, x̂ ← Ax̂ + Bu + Ψθ̂, the counter advances.
TEST(GuyaderZhangMissing, NoChannelIsTheTimeUpdateOfTheErrorAnalysis) {
  auto observer = make_observer();
  auto plant = satellite::make_plant<double>();
  for (Index k = 0; k < 57; ++k) {  // inside a pulse: Ψ ≠ 0, Υ ≠ 0
    ASSERT_EQ(observer.update(plant.sample()), UpdateStatus::accepted);
    plant.advance();
  }
  const Eigen::Matrix4d A = satellite::model<double>().system().A;
  const Eigen::Matrix<double, 4, 2> psi = plant.sample().Psi;
  ASSERT_GT(psi.norm(), 0.0);
  const Eigen::Vector4d x = observer.state();
  const Eigen::Vector2d theta = observer.parameters();
  const Eigen::Matrix<double, 4, 2> upsilon = observer.upsilon();
  auto sample = plant.sample();
  sample.y.setConstant(std::numeric_limits<double>::quiet_NaN());  // absent entries are ignored
  ASSERT_EQ(observer.update(sample, Mask::Constant(false)), UpdateStatus::accepted);
  EXPECT_EQ(observer.step(), 58);
  EXPECT_TRUE(bitwise_equal(observer.parameters(), theta));
  EXPECT_LE((observer.upsilon() - (A * upsilon + psi)).norm(), 1e-15 * (A * upsilon).norm());
  EXPECT_LE((observer.state() - (A * x + psi * theta)).norm(), 1e-15 * x.norm());  // B = 0
}

TEST(GuyaderZhangMissing, RunTimeSizedMaskOfTheWrongLengthNamesPresent) {
  using Dynamic = adaptobs::DynamicDimensions<double>;
  const auto fixed = satellite::model<double>().system();
  adaptobs::DiscreteLtiModel<Dynamic> model(Eigen::MatrixXd(fixed.A), Eigen::MatrixXd(fixed.B),
                                            Eigen::MatrixXd(fixed.C), 2);
  adaptobs::GuyaderZhangObserver observer(model, Eigen::MatrixXd(satellite::paper_gain<double>()), satellite::mu,
                                          Eigen::VectorXd::Zero(4), Eigen::VectorXd::Zero(2));
  const adaptobs::DiscreteSample<Dynamic> sample{Eigen::VectorXd::Zero(2), Eigen::VectorXd::Zero(2),
                                                 Eigen::MatrixXd::Zero(4, 2)};
  try {
    (void)observer.update(sample, adaptobs::OutputMask<Dynamic>::Constant(3, true));
    ADD_FAILURE() << "a 3-entry mask for 2 outputs was accepted";
  } catch (const adaptobs::ConfigurationError& e) {
    EXPECT_NE(std::string(e.what()).find("'present'"), std::string::npos) << e.what();
  }
  EXPECT_EQ(observer.step(), 0);
}

// Guyader & Zhang (2003) §4 with 30 % of the output samples lost at random, and separately a
// 20-s outage from t = 100 s: θ̂ over the last 100 s stays within 0.05 of (1, 1.5).
// Skipping the lost samples instead leaves x̂ behind the plant at each one.
TEST(GuyaderZhangMissing, SatelliteWithDroppedSamplesAndAnOutage) {
  std::mt19937_64 generator(14);
  std::bernoulli_distribution lost(0.3);
  std::vector<bool> dropped(3000);
  for (auto&& d : dropped) d = lost(generator);
  const auto random_drops = [&](Index k) { return bool(dropped[std::size_t(k)]); };
  const auto outage = [](Index k) { return k >= 1000 && k < 1200; };
  const adaptobs::GuyaderZhangOptions normalized{.normalized_step = true};

  const auto complete = run_satellite([](Index) { return false; }, Gap::time_update);
  const auto drops = run_satellite(random_drops, Gap::time_update, normalized);
  const auto gap = run_satellite(outage, Gap::time_update, normalized);
  for (const auto* r : {&drops, &gap}) {
    EXPECT_NEAR(r->mean_parameters(0), 1.0, 0.05);
    EXPECT_NEAR(r->mean_parameters(1), 1.5, 0.05);
  }
  EXPECT_LE(drops.worst_assumption2, 1.0 + 1e-12);
  // Once the first sample after the outage is in, the state error is within 10×
  // its level over the 10 s before the outage. (Before that sample it is the
  // 20-s open-loop prediction error, 12× that level.)
  double before = 0;
  for (Index k = 900; k < 1000; ++k) before += gap.state_error[std::size_t(k)] / 100;
  EXPECT_LE(gap.state_error[1201], 10 * before) << "before " << before;

  // Over the outage Υ grows through A (a double integrator) without the output
  // injection: with μ as given the first step after it breaks assumption 2 and
  // the observer diverges; the normalized step keeps assumption 2. (Random
  // drops of up to a few samples push ‖√μ C̄Υ‖ to about 2 with μ as given.)
  const auto unnormalized_gap = run_satellite(outage, Gap::time_update);
  EXPECT_GT(unnormalized_gap.worst_assumption2, 2.0);
  EXPECT_FALSE(std::abs(unnormalized_gap.mean_parameters(0) - 1.0) < 0.05);
  EXPECT_LE(gap.worst_assumption2, 1.0 + 1e-12);

  const auto skipped_drops = run_satellite(random_drops, Gap::skip, normalized);
  const auto skipped_gap = run_satellite(outage, Gap::skip, normalized);
  std::printf(
      "  mean state error over the last 100 s: complete %.3g, drops %.3g (skipped %.3g), outage %.3g (skipped %.3g)\n",
      complete.mean_state_error, drops.mean_state_error, skipped_drops.mean_state_error, gap.mean_state_error,
      skipped_gap.mean_state_error);
  std::printf("  theta over the last 100 s with drops: %.4f %.4f (skipped %.4f %.4f); after the outage: %.4f %.4f\n",
              drops.mean_parameters(0), drops.mean_parameters(1), skipped_drops.mean_parameters(0),
              skipped_drops.mean_parameters(1), gap.mean_parameters(0), gap.mean_parameters(1));
  std::printf("  state error before the outage %.3g, before its first sample %.3g, after it %.3g\n", before,
              gap.state_error[1200], gap.state_error[1201]);
  EXPECT_GT(skipped_drops.mean_state_error, 100 * drops.mean_state_error);
  EXPECT_GT((skipped_drops.mean_parameters - Eigen::Vector2d(1, 1.5)).norm(), 1.0);
}

// A two-output LTV system with one parameter per state row: with samples and
// channels dropped, the observer must use A_k, C_k of the sample's own step.
using TwoOutputLtv = adaptobs::Dimensions<double, 3, 1, 2, 2>;

adaptobs::DiscreteSystem<TwoOutputLtv> two_output_system(Index k) {
  const Eigen::Matrix3d a = adaptobs::testing::rotating_ltv_dynamics(k);
  Eigen::Matrix<double, 2, 3> c;
  c << 1.0, 0.3 * std::cos(0.1 * double(k)), 0.5,  //
      0.0, 1.0, -0.4 * std::sin(0.07 * double(k));
  return {a, Eigen::Vector3d(0, 0, 1), c};
}

Eigen::Matrix<double, 3, 2> two_output_regressor(Index k, const Eigen::Matrix<double, 1, 1>& /*u*/) {
  const double t = double(k);
  Eigen::Matrix<double, 3, 2> psi;
  psi << std::sin(0.11 * t), 0.0,  //
      0.0, std::cos(0.07 * t),     //
      0.3, 0.2 * std::sin(0.31 * t);
  return psi;
}

// The masked equations written out with C̄_k = D_kC_k, independently of the observer.
struct ReferenceStep {
  Eigen::Vector3d x = Eigen::Vector3d::Zero();
  Eigen::Vector2d theta = Eigen::Vector2d::Zero();
  Eigen::Matrix<double, 3, 2> upsilon = Eigen::Matrix<double, 3, 2>::Zero();

  void step(const adaptobs::DiscreteSystem<TwoOutputLtv>& s, const Eigen::Matrix<double, 3, 2>& K, double mu,
            const adaptobs::DiscreteSample<TwoOutputLtv>& sample, const Eigen::Array2<bool>& present) {
    Eigen::Matrix2d d = Eigen::Matrix2d::Zero();
    for (int i = 0; i < 2; ++i) d(i, i) = present(i) ? 1.0 : 0.0;
    const Eigen::Matrix<double, 2, 3> c_bar = d * s.C;
    Eigen::Vector2d y_bar = Eigen::Vector2d::Zero();
    for (int i = 0; i < 2; ++i)
      if (present(i)) y_bar(i) = sample.y(i);
    const Eigen::Vector2d error = y_bar - c_bar * x;
    const Eigen::Vector2d theta_next = theta + mu * upsilon.transpose() * c_bar.transpose() * error;      // (2b)
    const Eigen::Matrix<double, 3, 2> upsilon_next = (s.A - K * c_bar) * upsilon + sample.Psi;            // (2a)
    x = s.A * x + s.B * sample.u + sample.Psi * theta + K * error + upsilon_next * (theta_next - theta);  // (2c)
    theta = theta_next;
    upsilon = upsilon_next;
  }
};

// A regressor spike of 10^200 makes ‖C̄Υ‖²_F overflow at the next steps: the
// normalized step must still move θ̂ on the error the spike left, with √μ_k‖C̄Υ‖₂ = ‖C̄Υ‖₂/‖C̄Υ‖_F in
// [1/√2, 1], and its excitation contribution must stay in range.
TEST(GuyaderZhangMissing, TheNormalizedStepHoldsForARegressorBeyondTheSquareRootOfTheRange) {
  auto observer = make_observer({.excitation_window = 5, .normalized_step = true});
  auto plant = satellite::make_plant<double>();
  for (Index k = 0; k < 50; ++k, plant.advance()) ASSERT_EQ(observer.update(plant.sample()), UpdateStatus::accepted);
  auto spike = plant.sample();
  spike.Psi.setConstant(1e200);
  ASSERT_EQ(observer.update(spike), UpdateStatus::accepted);
  plant.advance();
  for (int k = 0; k < 5; ++k, plant.advance()) {
    const Eigen::Vector2d before = observer.parameters();
    ASSERT_EQ(observer.update(plant.sample()), UpdateStatus::accepted);
    ASSERT_GT(observer.upsilon().cwiseAbs().maxCoeff(), 1e154);  // ‖C̄Υ‖² beyond the range
    if (k == 0) {
      EXPECT_GT((observer.parameters() - before).norm(), 1e-3);  // the spike's error acts on θ̂
    }
    EXPECT_GE(observer.assumption2_norm(), std::sqrt(0.5) - 1e-12) << k;
    EXPECT_LE(observer.assumption2_norm(), 1.0 + 1e-12) << k;
  }
  const auto level = observer.excitation_level();
  ASSERT_TRUE(level.has_value());
  EXPECT_TRUE(std::isfinite(*level));
}

TEST(GuyaderZhangMissing, TimeVaryingModelStaysInPhaseThroughDroppedSamplesAndChannels) {
  const auto model = adaptobs::make_discrete_ltv_model<TwoOutputLtv>(two_output_system);
  auto input = [](Index k) { return Eigen::Matrix<double, 1, 1>(std::sin(0.02 * double(k))); };
  adaptobs::DiscreteLinearPlant plant(model, Eigen::Vector3d(1, -1, 0.5), Eigen::Vector2d(0.7, -1.2), input,
                                      two_output_regressor);
  Eigen::Matrix<double, 3, 2> K;
  K << 0.5, 0.0, 0.1, 0.4, 0.2, -0.1;
  const double mu = 0.05;
  adaptobs::GuyaderZhangObserver observer(model, K, mu, Eigen::Vector3d::Zero().eval(), Eigen::Vector2d::Zero().eval());
  ReferenceStep reference;
  std::mt19937_64 generator(7);
  std::uniform_int_distribution<int> pattern(0, 3);  // both, first only, second only, none
  double worst = 0, scale = 0;
  for (Index k = 0; k < 2000; ++k) {
    const int p = pattern(generator);
    const Eigen::Array2<bool> present(p == 0 || p == 1, p == 0 || p == 2);
    reference.step(model.at(k), K, mu, plant.sample(), present);
    ASSERT_EQ(observer.update(plant.sample(), present), UpdateStatus::accepted);
    worst = std::max({worst, (observer.state() - reference.x).norm(), (observer.parameters() - reference.theta).norm(),
                      (observer.upsilon() - reference.upsilon).norm()});
    scale = std::max({scale, reference.x.norm(), reference.upsilon.norm()});
    plant.advance();
  }
  EXPECT_EQ(observer.step(), 2000);
  EXPECT_LE(worst, 1e-12 * scale) << "scale " << scale;
}

// The satellite's second output (the tangential position) missing half of the
// time, noise free: the estimates still converge to the true values.
TEST(GuyaderZhangMissing, SatelliteConvergesWithOneOutputMissingHalfOfTheTime) {
  auto observer = make_observer();
  auto plant = satellite::make_plant<double>(0.0);
  std::mt19937_64 generator(21);
  std::bernoulli_distribution second_present(0.5);
  for (Index k = 0; k < 6000; ++k) {
    ASSERT_EQ(observer.update(plant.sample(), Mask(true, second_present(generator))), UpdateStatus::accepted);
    plant.advance();
  }
  EXPECT_LT((observer.parameters() - plant.parameters()).norm(), 1e-6) << observer.parameters().transpose();
  EXPECT_LT((observer.state() - plant.state()).norm(), 1e-6);
}

// The second output masked at every sample is the observer built with the
// first output alone (C's first row, K's first column), to rounding.
TEST(GuyaderZhangMissing, PermanentlyMaskedChannelEqualsTheObserverWithoutIt) {
  using SingleDims = adaptobs::Dimensions<double, 4, 2, 1, 2>;
  const auto full = satellite::model<double>();
  const adaptobs::DiscreteLtiModel<SingleDims> first(full.system().A, full.system().B, full.system().C.topRows<1>());
  auto masked = make_observer({.normalized_step = true});
  adaptobs::GuyaderZhangObserver single(first, satellite::paper_gain<double>().leftCols<1>().eval(), satellite::mu,
                                        satellite::initial_state_estimate<double>(),
                                        satellite::initial_parameter_estimate<double>(), {.normalized_step = true});
  auto plant = satellite::make_plant<double>();
  for (Index k = 0; k < 3000; ++k) {
    const auto& s = plant.sample();
    ASSERT_EQ(masked.update(s, Mask(true, false)), UpdateStatus::accepted);
    ASSERT_EQ(single.update({s.u, s.y.topRows<1>(), s.Psi}), UpdateStatus::accepted);
    plant.advance();
  }
  const double scale = std::max(1.0, single.state().cwiseAbs().maxCoeff());
  EXPECT_LT((masked.state() - single.state()).cwiseAbs().maxCoeff(), 1e-12 * scale);
  EXPECT_LT((masked.parameters() - single.parameters()).cwiseAbs().maxCoeff(), 1e-12);
}

// The augmented Kalman filter against the textbook correction on the measured
// sub-vector (rows of C, block of R selected explicitly), then the prediction.
TEST(AugmentedKalmanMissing, MaskedStepIsTheCorrectionWithThePresentChannelsOnly) {
  using Matrix6 = Eigen::Matrix<double, 6, 6>;
  Matrix6 p0 = Matrix6::Zero(), q = Matrix6::Zero();
  p0.diagonal() << 0.1, 1e-4, 0.1, 1e-4, 1.0, 1.0;
  q.diagonal() << 1e-10, 1e-10, 1e-10, 1e-10, 0.0, 0.0;
  Eigen::Matrix2d r;
  r << 1e-4, 3e-5, 3e-5, 2e-4;  // correlated channels: the present block is not a diagonal entry
  const auto model = satellite::model<double>();
  const auto make = [&] {
    return adaptobs::AugmentedKalmanFilter(model, satellite::initial_state_estimate<double>(),
                                           satellite::initial_parameter_estimate<double>(),
                                           adaptobs::AugmentedKalmanCovariances<SatelliteDims>{p0, q, r});
  };
  auto filter = make(), plain = make();
  auto plant = satellite::make_plant<double>();
  const auto& sys = model.system();
  std::mt19937_64 generator(5);
  std::uniform_int_distribution<int> pattern(0, 3);
  double worst = 0;
  for (Index k = 0; k < 200; ++k) {
    const auto& sample = plant.sample();
    const int code = k < 100 ? 0 : pattern(generator);
    const Mask present(code == 0 || code == 1, code == 0 || code == 2);
    std::vector<Index> rows;
    for (Index i = 0; i < 2; ++i)
      if (present(i)) rows.push_back(i);
    const Index m = Index(rows.size());
    Eigen::MatrixXd c(m, 4), r_s(m, m);
    Eigen::VectorXd y(m);
    for (Index i = 0; i < m; ++i) {
      c.row(i) = sys.C.row(rows[std::size_t(i)]);
      y(i) = sample.y(rows[std::size_t(i)]);
      for (Index j = 0; j < m; ++j) r_s(i, j) = r(rows[std::size_t(i)], rows[std::size_t(j)]);
    }
    Eigen::MatrixXd p = filter.covariance(), h = Eigen::MatrixXd::Zero(m, 6);
    h.leftCols(4) = c;
    Eigen::VectorXd xi(6);
    xi << filter.state(), filter.parameters();
    if (m > 0) {
      const Eigen::MatrixXd gain =
          adaptobs::testing::solve_by_llt(h * p * h.transpose() + r_s, h * p).transpose();  // P symmetric
      xi += gain * (y - c * filter.state());
      const Eigen::MatrixXd joseph = Eigen::MatrixXd::Identity(6, 6) - gain * h;
      p = (joseph * p * joseph.transpose() + gain * r_s * gain.transpose()).eval();
    }
    Eigen::MatrixXd f = Eigen::MatrixXd::Identity(6, 6);
    f.topLeftCorner(4, 4) = sys.A;
    f.topRightCorner(4, 2) = sample.Psi;
    const Eigen::VectorXd xi_next = f * xi;  // B = 0
    const Eigen::MatrixXd p_next = f * p * f.transpose() + Eigen::MatrixXd(q);

    auto with_gaps = sample;  // absent entries are ignored, NaN or not
    for (Index i = 0; i < 2; ++i)
      if (!present(i)) with_gaps.y(i) = std::numeric_limits<double>::quiet_NaN();
    ASSERT_EQ(filter.update(with_gaps, present), UpdateStatus::accepted);
    if (k < 100) {
      ASSERT_EQ(plain.update(sample), UpdateStatus::accepted);
      ASSERT_TRUE(bitwise_equal(filter.covariance(), plain.covariance()) &&
                  bitwise_equal(filter.state(), plain.state()))
          << "all channels present differs from update(sample) at step " << k;
    }
    Eigen::VectorXd estimate(6);
    estimate << filter.state(), filter.parameters();
    worst = std::max(
        {worst, (estimate - xi_next).norm() / xi_next.norm(), (filter.covariance() - p_next).norm() / p_next.norm()});
    plant.advance();
  }
  EXPECT_LE(worst, 1e-10);
}

}  // namespace

// `update_finite_outputs`, written once against `PartialOutputObserver`: a NaN or
// Inf in y is the masked update without that channel, bit for bit; no finite
// entry is the time update; a non-finite input is still rejected.
template <class MakeObserver>
void check_finite_outputs(MakeObserver make) {
  auto glitched = make(), masked = make();
  static_assert(adaptobs::PartialOutputObserver<decltype(glitched)>);
  auto plant = satellite::make_plant<double>();
  for (Index k = 0; k < 300; ++k) {
    auto sample = plant.sample();
    Mask present = Mask::Constant(true);
    if (k % 5 == 1) present(1) = false;
    if (k % 7 == 2) present.setConstant(false);
    for (Index i = 0; i < 2; ++i)
      if (!present(i)) sample.y(i) = k % 2 ? std::numeric_limits<double>::quiet_NaN() : -HUGE_VAL;
    ASSERT_EQ(adaptobs::update_finite_outputs(glitched, sample), UpdateStatus::accepted);
    ASSERT_EQ(masked.update(plant.sample(), present), UpdateStatus::accepted);
    ASSERT_TRUE(bitwise_equal(glitched.state(), masked.state()) &&
                bitwise_equal(glitched.parameters(), masked.parameters()))
        << "step " << k;
    plant.advance();
  }
  auto sample = plant.sample();
  sample.u(0) = std::numeric_limits<double>::quiet_NaN();
  const auto before = glitched;
  EXPECT_EQ(adaptobs::update_finite_outputs(glitched, sample), UpdateStatus::nonfinite_input);
  EXPECT_TRUE(bitwise_equal(glitched.state(), before.state()) &&
              bitwise_equal(glitched.parameters(), before.parameters()));
  EXPECT_EQ(glitched.step(), before.step());
}

TEST(FiniteOutputs, GlitchesBecomeMaskedUpdatesForGuyaderZhangAndTheKalmanFilter) {
  check_finite_outputs([] { return make_observer({.normalized_step = true}); });
  check_finite_outputs([] {
    using Matrix6 = Eigen::Matrix<double, 6, 6>;
    Matrix6 p0 = Matrix6::Identity() * 0.1, q = Matrix6::Identity() * 1e-10;
    return adaptobs::AugmentedKalmanFilter(
        satellite::model<double>(), satellite::initial_state_estimate<double>(),
        satellite::initial_parameter_estimate<double>(),
        adaptobs::AugmentedKalmanCovariances<SatelliteDims>{p0, q, Eigen::Matrix2d::Identity() * 1e-4});
  });
}
