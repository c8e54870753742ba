// Takagi–Sugeno polytopic model and adaptive observer (Srinivasarengan et al. 2018): sector
// weights (10)–(11) and Remark 1, the vertices of the waste water plant of §6
// against the printed ones, exactness of the polytopic model, observer (65) and
// its time-varying variant (21), the paper's gains on the plant, missing outputs,
// bad input and bad configuration, fixed and dynamic sizes.

#include <adaptobs/core/observer.hpp>
#include <adaptobs/models/takagi_sugeno_model.hpp>
#include <adaptobs/observers/takagi_sugeno.hpp>
#include <adaptobs/simulation/discrete_nonlinear_plant.hpp>
#include <adaptobs/simulation/runner.hpp>

#include "models/wwtp.hpp"
#include "support/eigen_testing.hpp"
#include "support/observer_contract.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <random>
#include <string>
#include <vector>

namespace {

using adaptobs::Index;
using adaptobs::UpdateStatus;
namespace wwtp = adaptobs::examples::wwtp;

template <typename S>
auto make_wwtp_observer(adaptobs::TakagiSugenoGains<wwtp::Dims<S>> gains = wwtp::paper_gains<S>(),
                        Eigen::Matrix<S, 2, 1> x0 = wwtp::initial_state_estimate<S>(),
                        wwtp::Vector1<S> theta0 = wwtp::initial_parameter_estimate<S>()) {
  return adaptobs::TakagiSugenoObserver(wwtp::model<S>(), gains, x0, theta0);
}

static_assert(adaptobs::TakagiSugenoSystem<wwtp::Model<double>>);
static_assert(!adaptobs::TakagiSugenoSystem<adaptobs::DiscreteLtiModel<adaptobs::Dimensions<double, 2, 1, 1, 1>>>);
static_assert(adaptobs::Observer<decltype(make_wwtp_observer<double>())>);
static_assert(adaptobs::Observer<decltype(make_wwtp_observer<float>())>);

ADAPTOBS_TYPED_SUITE_IN_BOTH_PRECISIONS(TakagiSugenoTyped);

// --- Sector weights, eq. (9)–(11) and Remark 1 ---------------------------------

// Three premise variables and two parameters: 32 vertices, checked at random
// points inside and far outside the sectors.
TYPED_TEST(TakagiSugenoTyped, SectorWeightsAreAConvexSumThatReproducesTheClippedPoint) {
  using S = TypeParam;
  using V3 = Eigen::Matrix<S, 3, 1>;
  using V2 = Eigen::Matrix<S, 2, 1>;
  const adaptobs::SectorBounds<S, 3> zb{V3(-1, 0, 2), V3(1, 0.5, 7)};
  const adaptobs::SectorBounds<S, 2> tb{V2(-0.3, 10), V2(0.3, 20)};
  adaptobs::testing::RandomMatrices random(6);
  const S tol = 64 * std::numeric_limits<S>::epsilon();
  for (int draw = 0; draw < 500; ++draw) {
    const double spread = draw % 2 == 0 ? 1.0 : 4.0;  // odd draws land mostly outside the sectors
    V3 z;
    V2 th;
    for (int j = 0; j < 3; ++j) {
      const double mid = 0.5 * double(zb.lower(j) + zb.upper(j)), half = 0.5 * double(zb.upper(j) - zb.lower(j));
      z(j) = S(random.scalar(mid - spread * half, mid + spread * half));
    }
    for (int j = 0; j < 2; ++j) {
      const double mid = 0.5 * double(tb.lower(j) + tb.upper(j)), half = 0.5 * double(tb.upper(j) - tb.lower(j));
      th(j) = S(random.scalar(mid - spread * half, mid + spread * half));
    }
    Eigen::Matrix<S, 32, 1> h;
    adaptobs::sector_weights(z, zb, th, tb, h);
    ASSERT_GE(h.minCoeff(), S(0)) << "draw " << draw;
    ASSERT_NEAR(h.sum(), S(1), tol) << "draw " << draw;
    // Σ h_i v^(i) = clip(v), coordinate by coordinate (eq. (9) for each variable).
    V3 z_blend = V3::Zero();
    V2 th_blend = V2::Zero();
    for (Index i = 0; i < 32; ++i) {
      V3 zi;
      V2 ti;
      adaptobs::vertex_point(i, zb, tb, zi, ti);
      z_blend += h(i) * zi;
      th_blend += h(i) * ti;
    }
    EXPECT_MATRIX_NEAR(z_blend, zb.clip(z), 16 * tol, 16 * tol);
    EXPECT_MATRIX_NEAR(th_blend, tb.clip(th), 16 * tol, 16 * tol);
  }
}

// Each vertex point has weight 1 on its own vertex: the weights and the vertex
// construction share one order (z_1 most significant, last parameter least).
TEST(TakagiSugeno, VertexPointsCarryTheirOwnWeightAndFollowTheDocumentedOrder) {
  const auto zb = wwtp::premise_bounds<double>();
  const auto tb = wwtp::parameter_bounds<double>();
  for (Index i = 0; i < 8; ++i) {
    Eigen::Vector2d z;
    wwtp::Vector1<double> th;
    adaptobs::vertex_point(i, zb, tb, z, th);
    Eigen::Matrix<double, 8, 1> h;
    adaptobs::sector_weights(z, zb, th, tb, h);
    EXPECT_EQ(h, (Eigen::Matrix<double, 8, 1>::Unit(i))) << "vertex " << i;
    const Index j1 = i / 4, j2 = (i / 2) % 2, j3 = i % 2;  // i = 4 j(z1) + 2 j(z2) + j(θ)
    EXPECT_EQ(z(0), j1 ? zb.upper(0) : zb.lower(0));
    EXPECT_EQ(z(1), j2 ? zb.upper(1) : zb.lower(1));
    EXPECT_EQ(th(0), j3 ? tb.upper(0) : tb.lower(0));
  }
}

// --- The waste water plant of §6 ---------------------------------------------

// True when `printed` is `value` rounded or truncated to `decimals` decimals.
bool matches_printed(double value, double printed, int decimals) {
  const double scale = std::pow(10.0, decimals);
  const double scaled = value * scale;
  const double target = printed * scale;
  return std::abs(std::round(scaled) - target) < 1e-6 || std::abs(std::trunc(scaled) - target) < 1e-6;
}

TEST(TakagiSugeno, WwtpVerticesMatchThePrintedMatricesToThePrintedDigits) {
  const auto model = wwtp::model<double>();
  ASSERT_EQ(model.vertex_count(), 8);
  const auto printed = wwtp::printed_vertex_matrices();
  for (Index i = 0; i < 8; ++i) {
    const Eigen::Matrix2d a = model.A(i);
    for (int e = 0; e < 4; ++e) {
      const auto& p = printed[std::size_t(i)][std::size_t(e)];
      const double v = a(e / 2, e % 2);
      EXPECT_TRUE(matches_printed(v, p.value, p.decimals))
          << "A_" << i + 1 << "(" << e / 2 + 1 << "," << e % 2 + 1 << ") = " << v << ", printed " << p.value;
      EXPECT_LT(std::abs(v - p.value), std::pow(10.0, -p.decimals)) << "A_" << i + 1;
    }
    EXPECT_EQ(Eigen::Vector2d(model.B(i)), Eigen::Vector2d(0, 2)) << "B_" << i + 1;
  }
  // The printed 2.92 (A_3) and 2.93 (A_7) are one number, a z2max with a = 0.2: 0.2 · 600/41.
  EXPECT_NEAR(model.A(2)(0, 1), 0.2 * 600.0 / 41.0, 1e-14);
  EXPECT_EQ(model.A(2)(0, 1), model.A(6)(0, 1));
  // Sectors (76): z2 ∈ [0.01/3.4, 6/0.41], printed [0.003, 14.63].
  EXPECT_NEAR(model.premise_bounds().lower(1), 1.0 / 340.0, 1e-16);
  EXPECT_NEAR(model.premise_bounds().upper(1), 600.0 / 41.0, 1e-13);
}

TEST(TakagiSugeno, WwtpPolytopicModelIsExactInsideTheSectors) {
  const auto model = wwtp::model<double>();
  adaptobs::testing::RandomMatrices random(72);
  for (int draw = 0; draw < 200; ++draw) {
    const Eigen::Vector2d x(random.scalar(wwtp::x1_min, wwtp::x1_max), random.scalar(wwtp::x2_min, wwtp::x2_max));
    const wwtp::Vector1<double> u(random.scalar(wwtp::u_min, wwtp::u_max));
    const wwtp::Vector1<double> th(random.scalar(wwtp::theta_min, wwtp::theta_max));
    // Σ h_i A_i = A(z, θ), and the polytopic step is the nonlinear plant (72).
    const Eigen::Vector2d z = model.premises(x, u, th);
    const auto h = model.weights(z, th);
    EXPECT_MATRIX_NEAR(model.blended_A(h), wwtp::quasi_lpv<double>(z, th).A, 1e-13, 1e-13);
    EXPECT_MATRIX_NEAR(model.step(x, u, th), wwtp::transition<double>(x, u, th), 1e-12, 1e-12);
  }
}

// --- Observer (65) -----------------------------------------------------------

// With exact vertices, an observer started at the truth stays on it.
TYPED_TEST(TakagiSugenoTyped, ObserverStartedAtTheTruthStaysOnIt) {
  using S = TypeParam;
  const S theta = S(0.1);
  auto plant = wwtp::make_plant<S>(theta);
  auto observer = make_wwtp_observer<S>(wwtp::paper_gains<S>(), wwtp::initial_state<S>(), wwtp::Vector1<S>(theta));
  double worst = 0;
  for (Index k = 0; k < 1000; ++k) {
    ASSERT_EQ(observer.update(plant.sample()), UpdateStatus::accepted);
    plant.advance();
    worst = std::max({worst, double((observer.state() - plant.state()).cwiseAbs().maxCoeff()),
                      double(std::abs(observer.parameters()(0) - theta))});
  }
  EXPECT_LT(worst, (std::is_same_v<S, float> ? 1e-4 : 1e-12));
}

// One step against eq. (65) written out with the model's vertices and weights.
TEST(TakagiSugeno, UpdateIsEquation65) {
  const auto model = wwtp::model<double>();
  auto gains = wwtp::paper_gains<double>();
  for (std::size_t i = 0; i < 8; ++i) gains.K[i](0) = 0.01 * double(i + 1);  // distinct K_i
  const Eigen::Vector2d x0(3, 0.6);
  const wwtp::Vector1<double> th0(0.05);
  adaptobs::TakagiSugenoObserver observer(model, gains, x0, th0);
  const adaptobs::InputOutputSample<wwtp::Dims<double>> sample{wwtp::Vector1<double>(0.2), wwtp::Vector1<double>(4.1)};
  ASSERT_EQ(observer.update(sample), UpdateStatus::accepted);

  const wwtp::Vector1<double> u = sample.u;
  const Eigen::Vector2d z(u(0), x0(0) / (x0(1) + wwtp::b));  // ẑ at the estimates
  const auto h = model.weights(z, th0);
  const double e = sample.y(0) - x0(0);
  Eigen::Vector2d x1 = Eigen::Vector2d::Zero();
  double dtheta = 0;
  for (Index i = 0; i < 8; ++i) {
    x1 += h(i) * (model.A(i) * x0 + model.B(i) * u + gains.L[std::size_t(i)] * e);
    dtheta += h(i) * gains.K[std::size_t(i)](0) * e;
  }
  EXPECT_MATRIX_NEAR(observer.state(), x1, 1e-14, 1e-14);
  EXPECT_NEAR(observer.parameters()(0), th0(0) + dtheta, 1e-15);
  EXPECT_MATRIX_NEAR(observer.weights(), h, 0, 0);
  EXPECT_MATRIX_NEAR(observer.premises(), z, 0, 0);
  EXPECT_TRUE(observer.premises_in_sectors());
}

// (65) with every block of V_i = [[A_i, B_i, L_i], [0, 0, K_{y,i}]] distinct between
// vertices and non-square (nx = 3, nu = 2, ny = 2): the update reads each from its
// own place. The reference goes through the model's A(i), B(i), one vertex at a time.
TEST(TakagiSugeno, UpdateIsEquation65WithVertexDependentInputMatricesAndSeveralChannels) {
  using Dims = adaptobs::Dimensions<double, 3, 2, 2, 1>;
  using Vector1 = Eigen::Matrix<double, 1, 1>;
  const Eigen::Matrix3d A0{{0.5, 0.1, 0}, {-0.2, 0.6, 0.1}, {0.05, 0, 0.7}};
  const Eigen::Matrix3d A1{{0.1, 0, 0.2}, {0, -0.1, 0}, {0.3, 0.1, 0}};
  const Eigen::Matrix3d A2{{0, 0.2, 0}, {0.1, 0, -0.3}, {0, 0.2, 0.1}};
  const Eigen::Matrix<double, 3, 2> B0{{1, 0}, {0, 0.5}, {0.2, 0.3}};
  const Eigen::Matrix<double, 3, 2> B1{{0, 0.4}, {-0.6, 0}, {0.1, 0}};
  const Eigen::Matrix<double, 3, 2> B2{{0.3, 0}, {0, -0.2}, {0, 0.7}};
  // z = u1 ∈ [0, 1], θ ∈ [−1, 1]: 4 vertices.
  const auto matrices_at = [&](const Eigen::Matrix<double, 1, 1>& z, const Vector1& theta) {
    adaptobs::TakagiSugenoVertex<Dims> m;
    m.A = A0 + z(0) * A1 + theta(0) * A2;
    m.B = B0 + z(0) * B1 + theta(0) * B2;
    return m;
  };
  const auto premises = [](const Eigen::Vector3d&, const Eigen::Vector2d& u, const Vector1&) { return Vector1(u(0)); };
  const Eigen::Matrix<double, 2, 3> C{{1, 0, 0.5}, {0, 1, -0.25}};
  const adaptobs::SectorBounds<double, 1> z_bounds{Vector1(0), Vector1(1)};
  const adaptobs::SectorBounds<double, 1> theta_bounds{Vector1(-1), Vector1(1)};
  const auto model = adaptobs::make_takagi_sugeno_model<Dims, 1>(matrices_at, C, premises, z_bounds, theta_bounds);

  adaptobs::TakagiSugenoGains<Dims> gains;
  for (int i = 0; i < 4; ++i) {
    gains.L.push_back(Eigen::Matrix<double, 3, 2>{{0.1 * i, 0.2}, {0.05, -0.1 * i}, {0.3, 0.02 * i}});
    gains.K.push_back(Eigen::RowVector2d(0.01 * (i + 1), -0.02 * i));
  }
  const Eigen::Vector3d x0(1, -2, 0.5);
  const Vector1 th0(0.3);
  adaptobs::TakagiSugenoObserver observer(model, gains, x0, th0);
  const adaptobs::InputOutputSample<Dims> sample{Eigen::Vector2d(0.25, -1.5), Eigen::Vector2d(1.4, -2.2)};
  ASSERT_EQ(observer.update(sample), UpdateStatus::accepted);

  const auto h = model.weights(Vector1(sample.u(0)), th0);
  ASSERT_GT(h.minCoeff(), 0.05);  // every vertex takes part
  const Eigen::Vector2d e = sample.y - C * x0;
  Eigen::Vector3d x1 = Eigen::Vector3d::Zero();
  double dtheta = 0;
  for (Index i = 0; i < 4; ++i) {
    x1 += h(i) * (model.A(i) * x0 + model.B(i) * sample.u + gains.L[std::size_t(i)] * e);
    dtheta += h(i) * gains.K[std::size_t(i)].dot(e);
  }
  // The affine model: Σ h_i A_i = A(ẑ, θ̂) and Σ h_i B_i = B(ẑ, θ̂).
  const auto at_estimates = matrices_at(Vector1(sample.u(0)), th0);
  EXPECT_MATRIX_NEAR(model.blended_A(h), at_estimates.A, 1e-15, 1e-15);
  EXPECT_MATRIX_NEAR(model.blended_B(h), at_estimates.B, 1e-15, 1e-15);
  EXPECT_MATRIX_NEAR(observer.state(), x1, 1e-14, 1e-14);
  EXPECT_NEAR(observer.parameters()(0), th0(0) + dtheta, 1e-15);
  EXPECT_MATRIX_NEAR(observer.output_error(), e, 0, 0);
  // gains() reads back what the update runs on: every L_i and K_{y,i} as given.
  const auto in_use = observer.gains();
  ASSERT_EQ(in_use.L.size(), 4u);
  ASSERT_EQ(in_use.K.size(), 4u);
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_EQ(in_use.L[i], gains.L[i]) << i;
    EXPECT_EQ(in_use.K[i], gains.K[i]) << i;
  }
  EXPECT_FALSE(in_use.K_theta);
}

// The weights use ẑ and θ̂ clipped to their sectors; the unclipped ẑ stays visible.
TEST(TakagiSugeno, WeightsAtEstimatedPremisesAreClippedToTheSectors) {
  const Eigen::Vector2d far_x(100, 0.01);  // ẑ2 = 100/0.41 ≫ 14.63
  const wwtp::Vector1<double> far_theta(0.5);
  auto observer = make_wwtp_observer<double>(wwtp::paper_gains<double>(), far_x, far_theta);
  const adaptobs::InputOutputSample<wwtp::Dims<double>> sample{wwtp::Vector1<double>(0.7), wwtp::Vector1<double>(4)};
  ASSERT_EQ(observer.update(sample), UpdateStatus::accepted);
  EXPECT_FALSE(observer.premises_in_sectors());
  EXPECT_NEAR(observer.premises()(1), 100 / 0.41, 1e-12);
  EXPECT_EQ(observer.premises()(0), 0.7);
  // Every premise at its upper bound: all the weight on the last vertex.
  EXPECT_EQ(observer.weights(), (Eigen::Matrix<double, 8, 1>::Unit(7)));
}

struct Criterion {
  double worst_parameter_error = 0;  // max |θ̂_k − θ| over k ∈ [from, to]
  double worst_state_error = 0;      // max ‖x_k − x̂_k‖∞ over k ∈ [from, to]
  bool plant_in_sector = true;       // the plant stayed in the box of (76)
};

// Runs the plant and the observer for `to` samples and records the errors from `from` on.
// Which samples carry the output: by default all of them.
struct EverySample {
  bool operator()(Index /*k*/) const { return true; }
};

template <class Observer, class Plant, class Present = EverySample>
Criterion run(Observer& observer, Plant& plant, Index from, Index to, Present present = {}) {
  Criterion c;
  for (Index k = 0; k <= to; ++k) {
    c.plant_in_sector = c.plant_in_sector && wwtp::in_state_sector(plant.state());
    if (k >= from) {
      c.worst_parameter_error =
          std::max(c.worst_parameter_error, std::abs(observer.parameters()(0) - plant.parameters()(0)));
      c.worst_state_error = std::max(c.worst_state_error, (observer.state() - plant.state()).cwiseAbs().maxCoeff());
    }
    if (k == to) break;
    const auto status = present(k) ? observer.update(plant.sample())
                                   : observer.update(plant.sample(), adaptobs::OutputMask<wwtp::Dims<double>>(false));
    if (status != UpdateStatus::accepted) return {1e300, 1e300, c.plant_in_sector};
    plant.advance();
  }
  return c;
}

// The criterion with the printed gains L_i, K_i = 0.03: at the nominal
// dilution rate 0.225 ± 0.05, θ ∈ {−0.1, 0, 0.1} give |θ̂ − θ| < 0.01 and state
// errors below 1e-3 from sample 300 on (checked up to 400).
TEST(TakagiSugeno, PaperGainsMeetTheCriterionAroundTheNominalDilutionRate) {
  for (double theta : {-0.1, 0.0, 0.1}) {
    auto plant = wwtp::make_plant<double>(theta);
    auto observer = make_wwtp_observer<double>();
    const Criterion c = run(observer, plant, 300, 400);
    EXPECT_TRUE(c.plant_in_sector) << "theta " << theta;
    EXPECT_LT(c.worst_parameter_error, 0.01) << "theta " << theta;
    EXPECT_LT(c.worst_state_error, 1e-3) << "theta " << theta;
  }
}

// Missing outputs (file comment of observers/takagi_sugeno.hpp). With 20 % of
// the samples lost at random the criterion above still holds, 100 samples later.
TEST(TakagiSugenoMissing, PaperGainsMeetTheCriterionWithOneSampleInFiveLost) {
  std::mt19937_64 generator(4);
  std::bernoulli_distribution lost(0.2);
  for (double theta : {-0.1, 0.0, 0.1}) {
    auto plant = wwtp::make_plant<double>(theta);
    auto observer = make_wwtp_observer<double>();
    const Criterion c = run(observer, plant, 400, 500, [&](Index) { return !lost(generator); });
    EXPECT_TRUE(c.plant_in_sector) << "theta " << theta;
    EXPECT_LT(c.worst_parameter_error, 0.01) << "theta " << theta;
    EXPECT_LT(c.worst_state_error, 1e-3) << "theta " << theta;
  }
}

// No channel present is the step with a zero output error: the update with
// y_k = C x̂_k, bit for bit (the leakage of (21) included); every channel present
// is the plain update.
TEST(TakagiSugenoMissing, NoChannelIsTheStepWithoutOutputErrorAndAllChannelsThePlainStep) {
  static_assert(adaptobs::PartialOutputObserver<decltype(make_wwtp_observer<double>())>);
  auto gains = wwtp::paper_gains<double>();
  gains.K_theta = wwtp::Vector1<double>::Constant(0.02);
  auto masked = make_wwtp_observer<double>(gains), reference = make_wwtp_observer<double>(gains);
  auto plant = wwtp::make_plant<double>(0.1);
  using Mask = adaptobs::OutputMask<wwtp::Dims<double>>;
  for (Index k = 0; k < 300; ++k) {
    auto sample = plant.sample();
    const bool present = k % 3 != 0;
    if (present) {
      ASSERT_EQ(masked.update(sample, Mask(true)), UpdateStatus::accepted);
      ASSERT_EQ(reference.update(sample), UpdateStatus::accepted);
    } else {
      auto glitch = sample;
      glitch.y(0) = std::numeric_limits<double>::quiet_NaN();
      ASSERT_EQ(adaptobs::update_finite_outputs(masked, glitch), UpdateStatus::accepted);
      sample.y = reference.model().C() * reference.state();
      ASSERT_EQ(reference.update(sample), UpdateStatus::accepted);
    }
    ASSERT_TRUE(adaptobs::testing::bitwise_equal(masked.state(), reference.state()) &&
                adaptobs::testing::bitwise_equal(masked.parameters(), reference.parameters()))
        << "step " << k;
    plant.advance();
  }
  EXPECT_EQ(masked.step(), 300);
}

// The window of θ in which the printed gains converge moves with the dilution
// rate: near the ends of [−0.3, 0.3] they meet the criterion where the plant's
// operating point suits that θ (a low rate for a slow culture, a high one for a
// fast culture).
TEST(TakagiSugeno, PaperGainsConvergeAcrossTheRangeAtMatchedDilutionRates) {
  const struct {
    double theta;
    wwtp::DilutionRate input;
  } cases[] = {{-0.25, {0.15, 0.03, 100}}, {0.25, {0.275, 0.05, 100}}};
  for (const auto& c : cases) {
    auto plant = wwtp::make_plant<double>(c.theta, wwtp::initial_state<double>(), c.input);
    auto observer = make_wwtp_observer<double>();
    const Criterion r = run(observer, plant, 300, 400);
    EXPECT_TRUE(r.plant_in_sector) << "theta " << c.theta;
    EXPECT_LT(r.worst_parameter_error, 0.01) << "theta " << c.theta;
    EXPECT_LT(r.worst_state_error, 1e-3) << "theta " << c.theta;
  }
}

// And where they do not: at the nominal rate, θ = +0.2 converges too slowly for
// the state criterion at 300 samples, and θ = −0.2 does not converge (the
// estimates leave the sectors), although the plant stays in its sector.
TEST(TakagiSugeno, PaperGainsMissTheCriterionAtTheEndsOfTheRangeAtTheNominalDilutionRate) {
  {
    auto plant = wwtp::make_plant<double>(0.2);
    auto observer = make_wwtp_observer<double>();
    const Criterion at300 = run(observer, plant, 300, 300);
    EXPECT_TRUE(at300.plant_in_sector);
    EXPECT_GT(at300.worst_state_error, 1e-3);
    const Criterion later = run(observer, plant, 700, 1000);  // 1000 more samples
    EXPECT_LT(later.worst_parameter_error, 1e-3);
    EXPECT_LT(later.worst_state_error, 1e-3);
  }
  {
    auto plant = wwtp::make_plant<double>(-0.2);
    auto observer = make_wwtp_observer<double>();
    bool left_sectors = false;
    for (Index k = 0; k < 300; ++k) {
      ASSERT_EQ(observer.update(plant.sample()), UpdateStatus::accepted);
      left_sectors = left_sectors || !observer.premises_in_sectors();
      plant.advance();
      ASSERT_TRUE(wwtp::in_state_sector(plant.state()));
    }
    EXPECT_TRUE(left_sectors);
    EXPECT_GT(std::abs(observer.parameters()(0) + 0.2), 0.01);
  }
}

// --- Observer (21): time-varying parameters ----------------------------------

TEST(TakagiSugeno, LeakageGainAddsMinusKthetaThetaAndZeroLeakageIsEquation65) {
  auto plain = make_wwtp_observer<double>();
  auto gains = wwtp::paper_gains<double>();
  gains.K_theta = wwtp::Vector1<double>(0.0);
  auto zero_leak = make_wwtp_observer<double>(gains);
  gains.K_theta = wwtp::Vector1<double>(0.02);
  EXPECT_FALSE(plain.has_leakage());
  EXPECT_TRUE(zero_leak.has_leakage());
  auto plant = wwtp::make_plant<double>(0.1);
  for (Index k = 0; k < 300; ++k) {
    const auto& s = plant.sample();
    const double theta_before = plain.parameters()(0);
    auto leaky = plain;  // one step of (21) from the same estimates
    leaky.set_gains(gains);
    ASSERT_EQ(plain.update(s), UpdateStatus::accepted);
    ASSERT_EQ(zero_leak.update(s), UpdateStatus::accepted);
    ASSERT_EQ(leaky.update(s), UpdateStatus::accepted);
    // (21): θ̂⁺ = θ̂ + Σ ĥ_i K_i e − K_θ θ̂; the state update does not see K_θ.
    EXPECT_NEAR(leaky.parameters()(0), plain.parameters()(0) - 0.02 * theta_before, 1e-15);
    EXPECT_TRUE(adaptobs::testing::bitwise_equal(leaky.state(), plain.state()));
    plant.advance();
  }
  EXPECT_TRUE(adaptobs::testing::bitwise_equal(zero_leak.state(), plain.state()));
  EXPECT_TRUE(adaptobs::testing::bitwise_equal(zero_leak.parameters(), plain.parameters()));
  auto leaky = plain;
  leaky.set_gains(gains);
  EXPECT_EQ(leaky.gains().K_theta, gains.K_theta);
  EXPECT_EQ(zero_leak.gains().K_theta, std::optional(wwtp::Vector1<double>(0.0)));
}

// --- Simulation runner --------------------------------------------------------

TEST(TakagiSugeno, RunsInTheSimulationRunnerWithTheNonlinearPlant) {
  auto plant = wwtp::make_plant<double>(0.1);
  auto paper = make_wwtp_observer<double>();
  auto truth = make_wwtp_observer<double>(wwtp::paper_gains<double>(), wwtp::initial_state<double>(),
                                          wwtp::Vector1<double>(0.1));
  adaptobs::SeriesTable table;
  const auto report = adaptobs::simulate(plant, 50, table, adaptobs::track(paper), adaptobs::track(truth, "truth"));
  EXPECT_EQ(report.rejected[0] + report.rejected[1], 0);
  EXPECT_EQ(table.names(),
            (std::vector<std::string>{"t", "u_1", "y_1", "x_1", "x_2", "xhat_1", "xhat_2", "theta_1", "thetahat_1",
                                      "xhat_truth_1", "xhat_truth_2", "thetahat_truth_1"}));
  EXPECT_NEAR(table.at(49, "xhat_truth_2"), table.at(49, "x_2"), 1e-12);
  EXPECT_EQ(table.at(10, "y_1"), table.at(10, "x_1"));
}

// --- Bad input and bad configuration ------------------------------------------

// The observer contract (support/observer_contract.hpp) on the waste water
// plant with the printed gains, in float and double.
template <typename S>
struct TakagiSugenoContract {
  using Observer = decltype(make_wwtp_observer<S>());
  using Sample = typename Observer::Sample;
  using InDouble = TakagiSugenoContract<double>;  // the twin of the float instance
  static Observer make() { return make_wwtp_observer<S>(); }
  static std::vector<Sample> samples() {
    return adaptobs::testing::first_samples<Sample>(wwtp::make_plant<S>(S(0.1)), 40);
  }
  static auto readings(const auto& o) {
    return std::make_tuple(o.state(), o.parameters(), o.weights(), o.premises(), o.premises_in_sectors(), o.step());
  }
  // ε_k = y_k − C x̂_k, from the x̂_k the update started from.
  static typename Observer::Output expected_output_error(const Observer& before, const Observer&, const Sample& s) {
    return s.y - before.model().C() * before.state();
  }
};

}  // namespace

ADAPTOBS_OBSERVER_CONTRACT(TakagiSugeno, TakagiSugenoContract<float>, TakagiSugenoContract<double>);
ADAPTOBS_TWIN_CONTRACT(TakagiSugeno, FloatFollowsDouble, TakagiSugenoContract<float>);

namespace {

// A NaN premise variable: ẑ2 = x̂1/(x̂2 + b) = 0/0 at x̂ = (0, −b), from finite samples.
TYPED_TEST(TakagiSugenoTyped, NonFinitePremisesAreRejectedAndChangeNothing) {
  using S = TypeParam;
  auto observer = make_wwtp_observer<S>();
  observer.reset(Eigen::Matrix<S, 2, 1>(S(0), -S(wwtp::b)), wwtp::Vector1<S>(S(0)));
  const auto at_reset = TakagiSugenoContract<S>::readings(observer);
  auto plant = wwtp::make_plant<S>(S(0.1));
  EXPECT_EQ(observer.update(plant.sample()), UpdateStatus::nonfinite_input);
  EXPECT_TRUE(adaptobs::testing::same_bits(TakagiSugenoContract<S>::readings(observer), at_reset));
}

TEST(TakagiSugeno, BadConfigurationNamesTheArgument) {
  using D = wwtp::Dims<double>;
  const auto zb = wwtp::premise_bounds<double>();
  const auto tb = wwtp::parameter_bounds<double>();
  auto vertices = adaptobs::sector_vertices<D, 2>(wwtp::quasi_lpv<double>, zb, tb);
  const Eigen::RowVector2d C = wwtp::output_matrix<double>();
  using Model = adaptobs::TakagiSugenoModel<D, 2, wwtp::Premises>;

  auto seven = vertices;
  seven.pop_back();
  EXPECT_CONFIGURATION_ERROR_NAMES(Model(seven, C, {}, zb, tb), "vertices");
  auto nan_vertex = vertices;
  nan_vertex[3].A(1, 1) = std::nan("");
  EXPECT_CONFIGURATION_ERROR_NAMES(Model(nan_vertex, C, {}, zb, tb), "vertices[i].A");
  auto flat = zb;
  flat.upper(1) = flat.lower(1);
  EXPECT_CONFIGURATION_ERROR_NAMES(Model(vertices, C, {}, flat, tb), "premise_bounds");
  EXPECT_CONFIGURATION_ERROR_NAMES((void)(adaptobs::sector_vertices<D, 2>(wwtp::quasi_lpv<double>, flat, tb)),
                                   "premise_bounds");
  auto reversed = tb;
  std::swap(reversed.lower, reversed.upper);
  EXPECT_CONFIGURATION_ERROR_NAMES(Model(vertices, C, {}, zb, reversed), "parameter_bounds");
  // A sector as wide as the whole range: upper − lower overflows, and the
  // memberships would read (1, 0) at its centre instead of (½, ½).
  auto unbounded = tb;
  unbounded.lower(0) = std::numeric_limits<double>::lowest();
  unbounded.upper(0) = std::numeric_limits<double>::max();
  EXPECT_CONFIGURATION_ERROR_NAMES(Model(vertices, C, {}, zb, unbounded), "parameter_bounds");

  const Model model(vertices, C, {}, zb, tb);
  const Eigen::Vector2d x0(3, 0.6);
  const wwtp::Vector1<double> th0(0);
  auto gains = wwtp::paper_gains<double>();
  gains.L.pop_back();
  EXPECT_CONFIGURATION_ERROR_NAMES(adaptobs::TakagiSugenoObserver(model, gains, x0, th0), "gains.L");
  gains = wwtp::paper_gains<double>();
  gains.K[2](0) = std::numeric_limits<double>::infinity();
  EXPECT_CONFIGURATION_ERROR_NAMES(adaptobs::TakagiSugenoObserver(model, gains, x0, th0), "gains.K[2]");
  gains = wwtp::paper_gains<double>();
  gains.K_theta = wwtp::Vector1<double>(std::nan(""));
  EXPECT_CONFIGURATION_ERROR_NAMES(adaptobs::TakagiSugenoObserver(model, gains, x0, th0), "gains.K_theta");
  EXPECT_CONFIGURATION_ERROR_NAMES(
      adaptobs::TakagiSugenoObserver(model, wwtp::paper_gains<double>(), Eigen::Vector2d(std::nan(""), 0), th0), "x0");
  auto observer = adaptobs::TakagiSugenoObserver(model, wwtp::paper_gains<double>(), x0, th0);
  EXPECT_CONFIGURATION_ERROR_NAMES(observer.reset(x0, wwtp::Vector1<double>(std::nan(""))), "theta0");
  // Bad gains given later change nothing.
  gains = wwtp::paper_gains<double>();
  gains.L[1](0) = std::nan("");
  gains.K_theta = wwtp::Vector1<double>(0.1);
  EXPECT_CONFIGURATION_ERROR_NAMES(observer.set_gains(gains), "gains.L[1]");
  EXPECT_EQ(observer.gains().L[1], wwtp::paper_gains<double>().L[1]);
  EXPECT_FALSE(observer.has_leakage());
}

// --- Dynamic sizes --------------------------------------------------------------

// The two premise variables of the plant; for a negative input, which the plant
// never sees, it returns three values: a user error the observer must catch.
struct DynamicPremises {
  Eigen::VectorXd operator()(const Eigen::VectorXd& x, const Eigen::VectorXd& u,
                             const Eigen::VectorXd& /*theta*/) const {
    if (u(0) < 0) return Eigen::Vector3d(u(0), 0, 0);
    return Eigen::Vector2d(u(0), x(0) / (x(1) + wwtp::b));
  }
};

// The same observer, vertices and run with Eigen::Dynamic sizes and premises.
struct TakagiSugenoDynamicContract : TakagiSugenoContract<double> {
  using Dims = adaptobs::DynamicDimensions<double>;
  using Model = adaptobs::TakagiSugenoModel<Dims, Eigen::Dynamic, DynamicPremises>;
  using Observer = adaptobs::TakagiSugenoObserver<Model>;
  using Sample = Observer::Sample;
  using InFixed = TakagiSugenoContract<double>;
  static Observer make() {
    const auto fixed_model = wwtp::model<double>();
    std::vector<adaptobs::TakagiSugenoVertex<Dims>> vertices;
    for (Index i = 0; i < 8; ++i) vertices.push_back({fixed_model.A(i), fixed_model.B(i)});
    const auto zb = wwtp::premise_bounds<double>();
    const auto tb = wwtp::parameter_bounds<double>();
    const Model model(vertices, Eigen::MatrixXd(fixed_model.C()), {}, {zb.lower, zb.upper}, {tb.lower, tb.upper});
    const auto fixed_gains = wwtp::paper_gains<double>();
    adaptobs::TakagiSugenoGains<Dims> gains;
    for (std::size_t i = 0; i < 8; ++i) {
      gains.L.emplace_back(fixed_gains.L[i]);
      gains.K.emplace_back(fixed_gains.K[i]);
    }
    return Observer(model, gains, Eigen::VectorXd(wwtp::initial_state_estimate<double>()),
                    Eigen::VectorXd(wwtp::initial_parameter_estimate<double>()));
  }
  static std::vector<Sample> samples() {
    return adaptobs::testing::first_samples<Sample>(wwtp::make_plant<double>(0.1), 40,
                                                    [](const auto& s) { return Sample{s.u, s.y}; });
  }
};

}  // namespace

ADAPTOBS_TWIN_CONTRACT(TakagiSugeno, DynamicFollowsFixed, TakagiSugenoDynamicContract);

namespace {

// With run-time sizes, a sample, a premise function or a mask of the wrong size
// is refused with the name the caller knows, and the observer stays as it was.
TEST(TakagiSugeno, DynamicSizesRefuseWrongRunTimeSizes) {
  using DD = adaptobs::DynamicDimensions<double>;
  auto dynamic = TakagiSugenoDynamicContract::make();
  for (const auto& s : TakagiSugenoDynamicContract::samples()) ASSERT_EQ(dynamic.update(s), UpdateStatus::accepted);
  EXPECT_CONFIGURATION_ERROR_NAMES((void)dynamic.update({Eigen::VectorXd::Zero(2), Eigen::VectorXd::Zero(1)}),
                                   "sample.u");

  // A premise function returning 3 values for nz = 2 is refused before the weights read them.
  const Eigen::VectorXd x = dynamic.state(), theta = dynamic.parameters(), h = dynamic.weights();
  EXPECT_CONFIGURATION_ERROR_NAMES((void)dynamic.update({Eigen::VectorXd::Constant(1, -0.1), Eigen::VectorXd::Zero(1)}),
                                   "premises(x, u, theta)");
  EXPECT_TRUE(dynamic.state() == x);
  EXPECT_TRUE(dynamic.parameters() == theta);
  EXPECT_TRUE(dynamic.weights() == h);
  EXPECT_EQ(dynamic.step(), 40);

  // A mask of the wrong length is refused naming it, the observer unchanged;
  // the right length with the channel absent is the time update.
  using DynamicMask = adaptobs::OutputMask<DD>;
  const adaptobs::InputOutputSample<DD> sample{Eigen::VectorXd::Constant(1, 0.2), Eigen::VectorXd::Zero(1)};
  EXPECT_CONFIGURATION_ERROR_NAMES((void)dynamic.update(sample, DynamicMask::Constant(2, true)), "present");
  EXPECT_TRUE(dynamic.state() == x);
  EXPECT_TRUE(dynamic.parameters() == theta);
  EXPECT_EQ(dynamic.step(), 40);
  EXPECT_EQ(dynamic.update(sample, DynamicMask::Constant(1, false)), UpdateStatus::accepted);
  EXPECT_EQ(dynamic.step(), 41);
}

}  // namespace
