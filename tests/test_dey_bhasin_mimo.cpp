// Dey–Bhasin observer (Dey & Bhasin 2022) on the MIMO example of §5 and on random
// dimensions: the reading of the example, eq. (7) and (12), the structured
// filters against the literal (8)–(11), convergence with a sufficiently rich
// input (theorem 6), the proof step of theorem 5, batch least squares (18),
// missing and partial outputs, the excitation diagnostics of definition 1 (15),
// bad input and configuration. The bounds of
// theorem 5 over 10⁵ steps are in test_dey_bhasin_long_runs.cpp.

#include <adaptobs/adaptation/recursive_least_squares.hpp>
#include <adaptobs/core/observer.hpp>
#include <adaptobs/core/snapshot.hpp>
#include <adaptobs/core/spectral_norm.hpp>
#include <adaptobs/core/symmetric_eigenvalues.hpp>
#include <adaptobs/design/stability.hpp>
#include <adaptobs/observers/dey_bhasin.hpp>

#include <Eigen/LU>

#include "models/dey_bhasin.hpp"
#include "support/eigen_testing.hpp"
#include "support/observer_contract.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <vector>

namespace {

using adaptobs::Index;
using adaptobs::UpdateStatus;
using adaptobs::testing::RandomMatrices;
namespace db = adaptobs::examples::dey_bhasin;
namespace mimo = db::mimo;

using Observer = mimo::Observer<double>;
using DynamicObserver = adaptobs::DeyBhasinObserver<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::Dynamic>;
static_assert(adaptobs::Observer<Observer>);
static_assert(adaptobs::Observer<DynamicObserver>);
static_assert(adaptobs::Observer<adaptobs::SuzukiObserver<double, 3, 2, 2>>);
static_assert(Observer::np == 15 && Observer::nx == 6 && Observer::nu == 2 && Observer::ny == 2);

using Matrix6 = Eigen::Matrix<double, 6, 6>;
using Vector15 = Eigen::Matrix<double, 15, 1>;

Vector15 true_p(const Observer& o) { return o.parameters_of(mimo::a(), mimo::B()); }

// --- The reading of §5 --------------------------------------------------------

TEST(DeyBhasinExample, FirstBlockOfAIsReadAsZeroPointFour) {
  const Matrix6 a = adaptobs::block_companion_matrix<2>(mimo::a());
  const Matrix6 printed = adaptobs::block_companion_matrix<2>(mimo::printed_a());
  const Matrix6 f = adaptobs::block_companion_matrix<2>(mimo::f());
  EXPECT_NEAR(adaptobs::spectral_radius(a), 0.8962, 1e-4);
  EXPECT_NEAR(adaptobs::spectral_radius(printed), 4.0455, 1e-4);
  EXPECT_NEAR(adaptobs::spectral_radius(f), 0.8892, 1e-4);
  // Under the bounded input of figure 3 the printed plant overflows; the read one stays bounded.
  auto overflowing = mimo::make_plant(mimo::RichInput{}, mimo::printed_a());
  Index overflow_step = -1;
  for (Index t = 0; t < 1000 && overflow_step < 0; ++t) {
    if (!overflowing.state().allFinite()) overflow_step = t;
    overflowing.advance();
  }
  EXPECT_GT(overflow_step, 100);
  EXPECT_LT(overflow_step, 600);
  auto plant = mimo::make_plant(mimo::RichInput{});
  double largest = 0;
  for (Index t = 0; t < 3000; ++t) {
    largest = std::max(largest, plant.state().norm());
    plant.advance();
  }
  EXPECT_LT(largest, 100.0);
  // (A, C) observable and (A, B) controllable: the transfer matrix (1) is coprime, p identifiable.
  Eigen::Matrix<double, 12, 6> observability;
  Eigen::Matrix<double, 6, 12> controllability;
  Matrix6 power = Matrix6::Identity();
  const auto c = db::canonical_output_matrix<double>(3, 2);
  for (int k = 0; k < 6; ++k) {
    observability.middleRows<2>(2 * k) = c * power;
    controllability.middleCols<2>(2 * k) = power * mimo::B();
    power = a * power;
  }
  EXPECT_EQ(adaptobs::testing::lu_rank(observability), 6);
  EXPECT_EQ(adaptobs::testing::lu_rank(controllability), 6);
  // p's first entry a₁ − f₁ is exactly 0: normalizing p̂ by p is undefined, â by a is not.
  const auto observer = mimo::make_observer();
  EXPECT_EQ(true_p(observer)(0), 0.0);
  EXPECT_NEAR((true_p(observer) - observer.parameters()).norm(), 7.563729, 1e-6);
}

// (7): x_{t+1} = F x_t + (I_r ⊗ y_t)(a − f) + B u_t.
TEST(DeyBhasin, Equation7RewritesThePlant) {
  auto plant = mimo::make_plant(mimo::RichInput{});
  const Matrix6 f = adaptobs::block_companion_matrix<2>(mimo::f());
  const Eigen::Vector3d a_minus_f = mimo::a() - mimo::f();
  for (Index t = 0; t < 200; ++t) {
    const Eigen::Matrix<double, 6, 1> x = plant.state();
    const auto sample = plant.sample();
    Eigen::Matrix<double, 6, 3> y_kron = Eigen::Matrix<double, 6, 3>::Zero();
    for (int k = 0; k < 3; ++k) y_kron.block<2, 1>(2 * k, k) = sample.y;
    const Eigen::Matrix<double, 6, 1> expected = f * x + y_kron * a_minus_f + mimo::B() * sample.u;
    plant.advance();
    EXPECT_MATRIX_NEAR(plant.state(), expected, 1e-12 * (1 + x.norm()), 0.0) << "step " << t;
  }
}

// (12): x_t = S_t p + F^t x_0 and y_t = φ_tᵀ p + C F^t x_0 on the simulated plant.
TEST(DeyBhasin, Equation12HoldsOnTheSimulatedPlant) {
  auto observer = Observer(mimo::f(), mimo::x0(), mimo::a_hat0(), mimo::B_hat0(), mimo::law_options());
  const Vector15 p = true_p(observer);
  auto plant = mimo::make_plant(mimo::RichInput{});
  for (Index t = 0; t < 400; ++t) {
    const Eigen::Matrix<double, 6, 1> x = plant.state();
    ASSERT_EQ(observer.update(plant.sample()), UpdateStatus::accepted);
    const double scale = std::max(1.0, x.cwiseAbs().maxCoeff());
    EXPECT_MATRIX_NEAR(observer.state_with(p), x, 1e-10 * scale, 0.0) << "step " << t;
    // With x̂_0 = x_0, z_t = y_t − C F^t x_0 = φ_tᵀ p.
    EXPECT_MATRIX_NEAR(observer.measurement(), Eigen::Vector2d(observer.regressor().transpose() * p), 1e-10 * scale,
                       0.0);
    plant.advance();
  }
  // Started at the truth, the observer stays on it: x̂_t = x_t and the prediction is x_{t+1}.
  auto exact = Observer(mimo::f(), mimo::x0(), mimo::a(), mimo::B(), mimo::law_options());
  auto replay = mimo::make_plant(mimo::RichInput{});
  for (Index t = 0; t < 400; ++t) {
    ASSERT_EQ(exact.update(replay.sample()), UpdateStatus::accepted);
    EXPECT_MATRIX_NEAR(exact.current_state(), replay.state(), 1e-10, 1e-10);
    replay.advance();
    EXPECT_MATRIX_NEAR(exact.state(), replay.state(), 1e-10, 1e-10);
  }
  EXPECT_MATRIX_NEAR(exact.A_hat(), adaptobs::block_companion_matrix<2>(mimo::a()), 1e-12, 0.0);
  EXPECT_MATRIX_NEAR(exact.B_hat(), mimo::B(), 1e-12, 0.0);
}

// --- The structured filters against the literal (8)–(11) ------------------------

// S_y, S_u^(i) and F^t x̂_0 as printed, with dense matrices.
struct LiteralFilters {
  Eigen::MatrixXd F, Sy;
  std::vector<Eigen::MatrixXd> Su;
  Eigen::VectorXd free;
  Index r, q, m, n;
  LiteralFilters(const Eigen::VectorXd& f, Index q_, Index m_, const Eigen::VectorXd& x0)
      : r(f.size()), q(q_), m(m_), n(f.size() * q_) {
    F = adaptobs::block_companion_matrix(f, q);
    Sy = Eigen::MatrixXd::Zero(n, r);
    Su.assign(std::size_t(m), Eigen::MatrixXd::Zero(n, n));
    free = x0;
  }
  Eigen::MatrixXd S() const {
    Eigen::MatrixXd s(n, r + m * n);
    s.leftCols(r) = Sy;
    for (Index i = 0; i < m; ++i) s.middleCols(r + i * n, n) = Su[std::size_t(i)];
    return s;
  }
  void advance(const Eigen::VectorXd& y, const Eigen::VectorXd& u) {
    Eigen::MatrixXd y_kron = Eigen::MatrixXd::Zero(n, r);  // Y_t = I_r ⊗ y_t
    for (Index k = 0; k < r; ++k) y_kron.block(k * q, k, q, 1) = y;
    Sy = F * Sy + y_kron;  // (8)
    for (Index i = 0; i < m; ++i)
      Su[std::size_t(i)] = F * Su[std::size_t(i)] + u(i) * Eigen::MatrixXd::Identity(n, n);  // (9)
    free = F * free;
  }
};

TEST(DeyBhasin, StructuredFiltersEqualTheLiteralOnesOnRandomDimensions) {
  RandomMatrices rng(811);
  const std::vector<std::array<Index, 3>> dimensions = {{1, 1, 1}, {1, 3, 2}, {2, 1, 1}, {3, 2, 2},
                                                        {4, 3, 1}, {2, 2, 3}, {5, 1, 2}};
  double worst = 0;
  for (const auto& [r, q, m] : dimensions) {
    Eigen::VectorXd f;
    do {
      f = rng.uniform<Eigen::VectorXd>(r, 1, -0.6, 0.6);
    } while (adaptobs::spectral_radius(adaptobs::companion_matrix(f)) > 0.95);
    const Index n = r * q, np = r + m * n;
    const Eigen::VectorXd x0 = rng.uniform<Eigen::VectorXd>(n, 1);
    DynamicObserver observer(f, x0, rng.uniform<Eigen::VectorXd>(r, 1), rng.uniform<Eigen::MatrixXd>(n, m),
                             {.k0 = 10, .kmin = 1e-3, .R = Eigen::MatrixXd::Identity(q, q)});
    ASSERT_EQ(observer.sizes(), (adaptobs::Sizes{n, m, q, np}));
    LiteralFilters literal(f, q, m, x0);
    const Eigen::MatrixXd c = db::canonical_output_matrix<double>(r, q);
    Eigen::VectorXd y_previous, u_previous;
    for (Index t = 0; t < 60; ++t) {
      if (t > 0) literal.advance(y_previous, u_previous);
      const Eigen::VectorXd y = rng.uniform<Eigen::VectorXd>(q, 1), u = rng.uniform<Eigen::VectorXd>(m, 1);
      ASSERT_EQ(observer.update(DynamicObserver::Sample{u, y}), UpdateStatus::accepted);
      const Eigen::MatrixXd s = literal.S();
      const Eigen::MatrixXd phi = s.transpose() * c.transpose();  // φ_t = S_tᵀCᵀ
      const Eigen::VectorXd p = rng.uniform<Eigen::VectorXd>(np, 1);
      const Eigen::VectorXd x = s * p + literal.free;  // (13) with any p
      const double phi_scale = std::max(1.0, phi.cwiseAbs().maxCoeff());
      const double x_scale = std::max(1.0, x.cwiseAbs().maxCoeff());
      ASSERT_MATRIX_NEAR(observer.regressor(), phi, 1e-12 * phi_scale, 0.0) << "(r,q,m) = " << r << q << m;
      ASSERT_MATRIX_NEAR(observer.state_with(p), x, 1e-12 * x_scale, 0.0) << "(r,q,m) = " << r << q << m;
      // The estimate (13) itself, and the prediction S_{t+1}p̂_t + F^{t+1}x̂_0.
      ASSERT_MATRIX_NEAR(observer.current_state(), Eigen::VectorXd(s * observer.parameters() + literal.free),
                         1e-12 * x_scale, 1e-12);
      worst = std::max({worst, (observer.regressor() - phi).cwiseAbs().maxCoeff() / phi_scale,
                        (observer.state_with(p) - x).cwiseAbs().maxCoeff() / x_scale});
      y_previous = y;
      u_previous = u;
    }
    LiteralFilters next = literal;
    next.advance(y_previous, u_previous);
    EXPECT_MATRIX_NEAR(observer.state(), Eigen::VectorXd(next.S() * observer.parameters() + next.free), 1e-11, 1e-11);
  }
  RecordProperty("worst_relative_difference", std::to_string(worst));
}

// --- Theorem 6: convergence with a sufficiently rich input ------------------------

struct RunSummary {
  Index within_one_percent_from = -1;  // first step after which every normalized estimate stays within 1 % of 1
  Index state_error_small_from = -1;   // first step after which ‖x̃_t‖ < 1e-6 ‖x̃_0‖ stays true
  double initial_state_error = 0;
  double final_state_error = 0;
  double final_deviation = 0;      // max |θ̂/θ − 1| at the end
  double max_parameter_error = 0;  // max_t ‖p̃_t‖
  Index resets = 0;
};

using Mask = adaptobs::OutputMask<Observer::Dims>;

// Which output channels each sample carries: by default all of them.
struct EveryChannel {
  Mask operator()(Index /*t*/) const { return Mask::Constant(true); }
};

template <class Input, class Presence = EveryChannel>
RunSummary run_example(Observer& observer, Input input, Index steps, Presence presence = {}) {
  auto plant = mimo::make_plant(input);
  const Vector15 p = true_p(observer);
  RunSummary s;
  s.initial_state_error = (plant.state() - observer.current_state()).norm();
  s.max_parameter_error = (p - observer.parameters()).norm();
  for (Index t = 0; t < steps; ++t) {
    const Mask present = presence(t);
    EXPECT_EQ(present.all() ? observer.update(plant.sample()) : observer.update(plant.sample(), present),
              UpdateStatus::accepted)
        << "step " << t;
    const double deviation = (db::normalized_estimates(observer, mimo::a(), mimo::B()).array() - 1.0).abs().maxCoeff();
    const double state_error = (plant.state() - observer.current_state()).norm();
    s.max_parameter_error = std::max(s.max_parameter_error, (p - observer.parameters()).norm());
    if (deviation >= 0.01)
      s.within_one_percent_from = -1;
    else if (s.within_one_percent_from < 0)
      s.within_one_percent_from = t;
    if (state_error >= 1e-6 * s.initial_state_error)
      s.state_error_small_from = -1;
    else if (s.state_error_small_from < 0)
      s.state_error_small_from = t;
    s.final_deviation = deviation;
    s.final_state_error = state_error;
    plant.advance();
  }
  s.resets = observer.law().reset_count();
  return s;
}

TEST(DeyBhasin, Theorem6RichInputIdentifiesEveryEntryOfAAndB) {
  auto observer = mimo::make_observer();
  const RunSummary s = run_example(observer, mimo::RichInput{}, 1000);
  EXPECT_NEAR(s.initial_state_error, 4.682948, 1e-6);
  EXPECT_LT(s.final_deviation, 0.01);  // the issue's criterion ...
  EXPECT_LT(s.final_deviation, 1e-9);  // ... met with a wide margin
  EXPECT_GE(s.within_one_percent_from, 0);
  EXPECT_LT(s.within_one_percent_from, 100);  // settles at step 68
  EXPECT_LT(s.final_state_error, 1e-6 * s.initial_state_error);
  EXPECT_GE(s.state_error_small_from, 0);
  EXPECT_LT(s.state_error_small_from, 200);  // settles at step 127
  EXPECT_MATRIX_NEAR(observer.A_hat(), adaptobs::block_companion_matrix<2>(mimo::a()), 1e-9, 0.0);
  EXPECT_MATRIX_NEAR(observer.B_hat(), mimo::B(), 1e-9, 0.0);
  EXPECT_GT(s.resets, 20);
  // The eigenvalue bound settles most reset decisions without a factorization.
  EXPECT_LT(observer.law().reset_tests_run(), 1000 / 2);
}

// Without a rich input the estimates settle at wrong values, but stay bounded.
TEST(DeyBhasin, Theorem6NotRichInputDoesNotIdentify) {
  auto observer = mimo::make_observer();
  const RunSummary s = run_example(observer, mimo::NotRichInput{}, 1000);
  EXPECT_GT(s.final_deviation, 1.0);
  EXPECT_LT(s.within_one_percent_from, 0);
  EXPECT_TRUE(observer.parameters().allFinite());
}

// --- Missing and partial outputs (file comment of observers/dey_bhasin.hpp) ---------

TEST(DeyBhasinMissing, AllChannelsPresentIsTheUpdateBitForBit) {
  auto plain = mimo::make_observer();
  auto masked = mimo::make_observer();
  auto plant = mimo::make_plant(mimo::RichInput{});
  for (Index t = 0; t < 300; ++t) {
    ASSERT_EQ(plain.update(plant.sample()), UpdateStatus::accepted);
    ASSERT_EQ(masked.update(plant.sample(), Mask::Constant(true)), UpdateStatus::accepted);
    plant.advance();
  }
  EXPECT_TRUE(adaptobs::testing::bitwise_equal(masked.parameters(), plain.parameters()));
  EXPECT_TRUE(adaptobs::testing::bitwise_equal(masked.state(), plain.state()));
  EXPECT_TRUE(adaptobs::testing::bitwise_equal(masked.current_state(), plain.current_state()));
  EXPECT_TRUE(adaptobs::testing::bitwise_equal(masked.law().covariance(), plain.law().covariance()));
}

// Started at the truth, the outputs predicted for the absent channels are the
// measured ones: through dropped samples and dropped channels (absent entries
// NaN) the observer stays on the plant, and no channel present is the prediction.
TEST(DeyBhasinMissing, ExactModelStaysOnThePlantThroughMissingOutputs) {
  auto observer = Observer(mimo::f(), mimo::x0(), mimo::a(), mimo::B(), mimo::law_options());
  const Vector15 p = true_p(observer);
  auto plant = mimo::make_plant(mimo::RichInput{});
  std::mt19937_64 generator(31);
  std::uniform_int_distribution<int> pattern(0, 3);
  Index time_updates = 0;
  for (Index t = 0; t < 400; ++t) {
    const int bits = pattern(generator);
    const Mask present((bits & 1) != 0, (bits & 2) != 0);
    auto sample = plant.sample();
    for (Index i = 0; i < 2; ++i)
      if (!present(i)) sample.y(i) = std::numeric_limits<double>::quiet_NaN();
    const Eigen::Matrix<double, 6, 1> predicted = observer.state();
    ASSERT_EQ(observer.update(sample, present), UpdateStatus::accepted) << "step " << t;
    if (!present.any()) {
      ++time_updates;
      EXPECT_MATRIX_NEAR(observer.current_state(), predicted, 1e-12, 1e-12) << "step " << t;
    }
    EXPECT_MATRIX_NEAR(observer.current_state(), plant.state(), 1e-10, 1e-10) << "step " << t;
    plant.advance();
    EXPECT_MATRIX_NEAR(observer.state(), plant.state(), 1e-10, 1e-10) << "step " << t;
  }
  EXPECT_EQ(observer.step(), 400);
  EXPECT_GT(time_updates, 50);
  EXPECT_MATRIX_NEAR(observer.parameters(), p, 1e-12, 0.0);
}

// The example of theorem 6 with 20 % of the samples lost at random, and with the
// second output lost half of the time: still every entry of A and B to 1 %.
TEST(DeyBhasinMissing, RichInputStillIdentifiesWithDroppedSamplesAndChannels) {
  std::mt19937_64 generator(20);
  std::bernoulli_distribution lost(0.2), second_present(0.5);
  auto dropped = [&](Index /*t*/) { return Mask::Constant(!lost(generator)); };
  auto observer = mimo::make_observer();
  const RunSummary s = run_example(observer, mimo::RichInput{}, 1000, dropped);
  EXPECT_LT(s.final_deviation, 0.01);
  EXPECT_GE(s.within_one_percent_from, 0);
  EXPECT_LT(s.within_one_percent_from, 200);  // every sample present: step 68
  EXPECT_LT(s.final_state_error, 1e-6 * s.initial_state_error);
  RecordProperty("dropped_within_one_percent_from", std::to_string(s.within_one_percent_from));

  auto half = [&](Index /*t*/) { return Mask(true, second_present(generator)); };
  auto partial = mimo::make_observer();
  const RunSummary h = run_example(partial, mimo::RichInput{}, 1000, half);
  EXPECT_LT(h.final_deviation, 0.01);
  EXPECT_GE(h.within_one_percent_from, 0);
  EXPECT_LT(h.within_one_percent_from, 200);
  EXPECT_LT(h.final_state_error, 1e-6 * h.initial_state_error);
  RecordProperty("half_within_one_percent_from", std::to_string(h.within_one_percent_from));
}

// With run-time sizes, a mask of the wrong length is refused naming 'present'
// (the rest of the masked contract: DeyBhasinContract below).
TEST(DeyBhasinMissing, RunTimeSizedMaskOfTheWrongLengthNamesPresent) {
  static_assert(adaptobs::PartialOutputObserver<Observer>);
  DynamicObserver dynamic(Eigen::VectorXd(mimo::f()), Eigen::VectorXd(mimo::x_hat0()), Eigen::VectorXd(mimo::a_hat0()),
                          Eigen::MatrixXd(mimo::B_hat0()),
                          {.k0 = 10, .kmin = 1e-3, .R = Eigen::MatrixXd::Identity(2, 2)});
  const std::string message = adaptobs::testing::configuration_error_of([&] {
    (void)dynamic.update(DynamicObserver::Sample{Eigen::VectorXd::Zero(2), Eigen::VectorXd::Zero(2)},
                         adaptobs::OutputMask<DynamicObserver::Dims>::Constant(3, true));
  });
  EXPECT_NE(message.find("'present'"), std::string::npos) << message;
  EXPECT_EQ(dynamic.step(), 0);
}

// A sample of the user's own type may hold run-time-sized vectors even for a
// fixed-size observer: a wrong length is refused naming it, nothing read past it.
TEST(DeyBhasinMissing, ASampleOfAnyTypeWithVectorsOfTheWrongLengthIsRefusedByName) {
  auto observer = mimo::make_observer();
  struct RunTimeSample {
    Eigen::VectorXd u, y;
  };
  const auto readings = [&] { return std::pair{Eigen::VectorXd(observer.state()), observer.step()}; };
  const auto before = readings();
  EXPECT_CONFIGURATION_ERROR_NAMES(
      (void)observer.update(RunTimeSample{Eigen::VectorXd::Zero(2), Eigen::VectorXd::Zero(1)}), "sample.y");
  EXPECT_CONFIGURATION_ERROR_NAMES(
      (void)observer.update(RunTimeSample{Eigen::VectorXd::Zero(3), Eigen::VectorXd::Zero(2)}), "sample.u");
  EXPECT_TRUE(readings() == before);
  EXPECT_EQ(observer.update(RunTimeSample{Eigen::VectorXd::Zero(2), Eigen::VectorXd::Zero(2)}), UpdateStatus::accepted);
}

// output_error(): the a-priori error z_t − φ_tᵀ p̂_{t−1} that RLS (22) corrects
// with, equal to y_t − C x̂_{t|t−1} (the state() before the update), not the
// a-posteriori error; zero in an absent channel (the rest of its contract:
// DeyBhasinContract below).
TEST(DeyBhasinMissing, OutputErrorIsTheAPrioriPredictionError) {
  static_assert(adaptobs::DiagnosableObserver<Observer> && adaptobs::DiagnosableObserver<DynamicObserver>);
  auto observer = mimo::make_observer();
  auto plant = mimo::make_plant(mimo::RichInput{});
  const auto C = db::canonical_output_matrix<double>(3, 2);
  EXPECT_TRUE(observer.output_error() == Eigen::Vector2d::Zero());
  double largest_posterior_gap = 0;
  for (Index t = 0; t < 60; ++t) {
    const Mask present(true, t % 5 != 3);
    auto sample = plant.sample();
    if (!present(1)) sample.y(1) = std::numeric_limits<double>::quiet_NaN();
    const Eigen::Matrix<double, 6, 1> before = observer.state();
    const Vector15 p_before = observer.parameters();
    ASSERT_EQ(observer.update(sample, present), UpdateStatus::accepted) << "step " << t;
    const Eigen::Vector2d& e = observer.output_error();
    EXPECT_NEAR(e(0), sample.y(0) - (C * before)(0), 1e-12 * (1 + std::abs(sample.y(0)))) << "step " << t;
    if (present(1)) {
      EXPECT_NEAR(e(1), sample.y(1) - (C * before)(1), 1e-12 * (1 + std::abs(sample.y(1)))) << "step " << t;
    } else {
      EXPECT_EQ(e(1), 0.0) << "step " << t;
    }
    // The same as z_t − φ_tᵀ p̂_{t−1} (absent entries of z are 0), not the a-posteriori error.
    Eigen::Vector2d prior = observer.measurement() - observer.regressor().transpose() * p_before;
    Eigen::Vector2d posterior = observer.measurement() - observer.regressor().transpose() * observer.parameters();
    if (!present(1)) prior(1) = posterior(1) = 0;
    EXPECT_MATRIX_NEAR(e, prior, 1e-12, 1e-12) << "step " << t;
    largest_posterior_gap = std::max(largest_posterior_gap, (e - posterior).cwiseAbs().maxCoeff());
    plant.advance();
  }
  EXPECT_GT(largest_posterior_gap, 1e-3);
  ASSERT_EQ(observer.update(plant.sample(), Mask(false, false)), UpdateStatus::accepted);
  EXPECT_TRUE(observer.output_error() == Eigen::Vector2d::Zero());
}

// "Sufficiently rich" here: every input channel needs two sinusoids at frequencies
// the other channel does not use. Rank of Σ φ_tφ_tᵀ over the stationary part of a run.
template <class Input>
Index regressor_rank(Input input) {
  auto observer = mimo::make_observer();
  auto plant = mimo::make_plant(input);
  Eigen::MatrixXd gram = Eigen::MatrixXd::Zero(15, 15), phi(15, 2);
  for (Index t = 0; t < 3000; ++t) {
    EXPECT_EQ(observer.update(plant.sample()), UpdateStatus::accepted);
    if (t >= 500) {
      phi = observer.regressor();
      gram.noalias() += phi * phi.transpose();
    }
    plant.advance();
  }
  const Eigen::VectorXd lambda = adaptobs::symmetric_eigenvalues(gram);
  return (lambda.array() > 1e-9 * lambda.maxCoeff()).count();
}

TEST(DeyBhasin, SufficientRichnessNeedsTwoSinusoidsPerChannel) {
  using Input = mimo::Input;
  EXPECT_EQ(regressor_rank(mimo::RichInput{}), 15);
  EXPECT_EQ(regressor_rank(mimo::NotRichInput{}), 8);
  EXPECT_EQ(regressor_rank([](Index k) {  // two sinusoids on one channel, one on the other
              const double t = double(k);
              return Input(std::sin(0.3 * t) + std::sin(1.3 * t), std::sin(0.7 * t));
            }),
            12);
  EXPECT_LT(regressor_rank([](Index k) {  // three sinusoids, the same on both channels
              const double t = double(k);
              const double s = std::sin(0.3 * t) + std::sin(1.1 * t) + std::sin(2.3 * t);
              return Input(s, s);
            }),
            15);
}

// Step (26) of the proof of theorem 5 uses ‖(I + ΓφR⁻¹φᵀ)⁻¹‖₂ ≤ 1, false for a
// non-symmetric product; the weighted norm N_t = ‖p̃_t‖_{Γ_t⁻¹} obeys the corrected
// step N_t ≤ N_{t−1} + ‖R^{-1/2} C F^t x̃_0‖ at every step, resets included.
TEST(DeyBhasin, Theorem5Step26FailsButTheWeightedNormStepHolds) {
  const Eigen::Matrix2d gamma = Eigen::Vector2d(1, 100).asDiagonal();
  const Eigen::Vector2d phi(1, 1);
  const Eigen::Matrix2d m = (Eigen::Matrix2d::Identity() + gamma * phi * phi.transpose()).inverse();
  EXPECT_NEAR(adaptobs::spectral_norm(m), 1.394, 1e-3);
  // Lemma 4(2), (I + M₁)⁻¹ ⪯ I, is itself false: its appendix B bounds the quadratic
  // form by the largest eigenvalue of a non-symmetric matrix. The symmetric part of
  // this (I + M₁)⁻¹ has the eigenvalue (103 + √(103² + 4·2348.25))/204 = 1.19818.
  const Eigen::Matrix2d symmetric_part = 0.5 * (m + m.transpose());
  EXPECT_NEAR(adaptobs::symmetric_eigenvalues(symmetric_part)(1), 1.19818, 1e-5);

  auto observer = mimo::make_observer();
  auto plant = mimo::make_plant(mimo::RichInput{});
  const Vector15 p = true_p(observer);
  const Matrix6 f = observer.filters().transition_matrix();
  Eigen::Matrix<double, 6, 1> free_error = mimo::x0() - mimo::x_hat0();  // F^t x̃_0
  const auto weighted = [&](const Vector15& e, const Eigen::MatrixXd& g) {
    return std::sqrt(e.dot(adaptobs::testing::solve_by_llt(g, Eigen::VectorXd(e)).col(0)));
  };
  Index violations_26 = 0;
  ASSERT_EQ(observer.update(plant.sample()), UpdateStatus::accepted);  // t = 0: no adaptation
  plant.advance();
  for (Index t = 1; t < 3000; ++t) {
    free_error = f * free_error;
    const Vector15 before = p - observer.parameters();
    const Eigen::Matrix<double, 15, 15> gamma_before = observer.law().covariance();
    ASSERT_EQ(observer.update(plant.sample()), UpdateStatus::accepted);
    const Vector15 after = p - observer.parameters();
    const auto& phi_t = observer.regressor();
    const Eigen::Vector2d perturbation = free_error.head<2>();  // C F^t x̃_0
    const Eigen::Matrix2d w = (Eigen::Matrix2d::Identity() + phi_t.transpose() * gamma_before * phi_t).inverse();
    if (after.norm() > before.norm() + (gamma_before * phi_t * w * perturbation).norm() + 1e-12) ++violations_26;
    const double n_before = weighted(before, gamma_before);
    EXPECT_LE(weighted(after, observer.law().covariance()), n_before + perturbation.norm() + 1e-8 * (1 + n_before))
        << "step " << t;
    plant.advance();
  }
  EXPECT_GT(violations_26, 0) << "(26) held at every step of this run";
  RecordProperty("violations_of_26", std::to_string(violations_26));
}

// --- Batch least squares (18) ------------------------------------------------------

TEST(DeyBhasin, WithoutResettingEqualsBatchLeastSquares18) {
  using RlsObserver = adaptobs::DeyBhasinObserver<double, 3, 2, 2, adaptobs::RecursiveLeastSquares>;
  static_assert(adaptobs::Observer<RlsObserver>);
  using Matrix15 = Eigen::Matrix<double, 15, 15>;
  const Matrix15 gamma0 = mimo::k0 * Matrix15::Identity();
  // The batch solution on dynamic matrices (one factorization compiled for the whole file).
  RlsObserver observer(mimo::f(), mimo::x_hat0(), mimo::a_hat0(), mimo::B_hat0(),
                       {.gamma0 = gamma0, .R = Eigen::Matrix2d::Identity()});
  const Vector15 p0 = observer.parameters();
  Eigen::MatrixXd information = Eigen::MatrixXd::Identity(15, 15) / mimo::k0;
  Eigen::VectorXd rhs = information * Eigen::VectorXd(p0);
  auto plant = mimo::make_plant(mimo::RichInput{});
  for (Index t = 0; t < 400; ++t) {
    ASSERT_EQ(observer.update(plant.sample()), UpdateStatus::accepted);
    if (t >= 1) {  // (18) sums from i = 1 (φ_0 = 0 anyway)
      const Eigen::MatrixXd phi = observer.regressor();
      information += phi * phi.transpose();
      rhs += phi * Eigen::VectorXd(observer.measurement());
    }
    plant.advance();
  }
  const Vector15 batch = adaptobs::testing::solve_by_llt(information, rhs).col(0);
  EXPECT_MATRIX_NEAR(observer.parameters(), batch, 1e-9 * batch.norm(), 0.0);
  const Matrix15 inverse = adaptobs::testing::solve_by_llt(information, Eigen::MatrixXd::Identity(15, 15));
  EXPECT_MATRIX_NEAR(observer.law().covariance(), inverse, 1e-9 * observer.law().covariance().norm(), 0.0);
}

// --- Persistent excitation, definition 1 (15) -------------------------------------

using Information = Eigen::Matrix<double, 15, 15>;

Observer make_monitored_observer(const Eigen::Matrix2d& R = Eigen::Matrix2d::Identity()) {
  return Observer(mimo::f(), mimo::x_hat0(), mimo::a_hat0(), mimo::B_hat0(),
                  {.k0 = mimo::k0, .kmin = mimo::kmin, .R = R}, {.information = true, .excitation_window = 100});
}

// φ_P R_PP⁻¹ φ_Pᵀ of the present channels P, from dense matrices.
Eigen::MatrixXd present_information(const Eigen::MatrixXd& phi, const Eigen::MatrixXd& R, const Mask& present) {
  std::vector<Index> rows;
  for (Index i = 0; i < present.size(); ++i)
    if (present(i)) rows.push_back(i);
  const Index n = Index(rows.size());
  if (n == 0) return Eigen::MatrixXd::Zero(phi.rows(), phi.rows());
  Eigen::MatrixXd phi_p(phi.rows(), n), r_pp(n, n);
  for (Index j = 0; j < n; ++j) {
    phi_p.col(j) = phi.col(rows[std::size_t(j)]);
    for (Index i = 0; i < n; ++i) r_pp(i, j) = R(rows[std::size_t(i)], rows[std::size_t(j)]);
  }
  return phi_p * adaptobs::testing::solve_by_llt(r_pp, phi_p.transpose());
}

// The §5 example with the rich input, R = I: I_t = Σ_{i≤t} φ_iφ_iᵀ (t the sample
// index, φ_0 = 0) grows linearly, λ_min(I_t) = 1.0316, 1.9663, 3.3983, 6.1682 at
// t = 100, 250, 500, 1000; the window of the last 100 samples (t = 901…1000) has
// λ_min = 5.662e-3 and full rank 15. Until the first covariance reset (23) I_t is
// Γ_t⁻¹ − Γ_0⁻¹ of RLS (20).
TEST(DeyBhasinExcitation, RichInputInformationGrowsLinearlyAndTheWindowHasFullRank) {
  auto observer = make_monitored_observer();
  auto plant = mimo::make_plant(mimo::RichInput{});
  const std::array<Index, 4> at = {100, 250, 500, 1000};
  const std::array<double, 4> printed = {1.032, 1.966, 3.398, 6.168};
  const std::array<double, 4> measured = {1.0316, 1.9663, 3.3983, 6.1682};
  std::array<double, 4> level{};
  std::size_t next = 0;
  bool identity_checked = false;
  for (Index t = 0; t <= 1000; ++t) {
    ASSERT_EQ(observer.update(plant.sample()), UpdateStatus::accepted);
    if (t == 98 || t == 99) {
      EXPECT_EQ(observer.excitation_level().has_value(), t == 99);  // the 100th sample fills the window
    }
    if (observer.law().reset_count() == 0 && t > 0) {
      const Eigen::MatrixXd inverse = adaptobs::testing::solve_by_llt(Eigen::MatrixXd(observer.law().covariance()),
                                                                      Eigen::MatrixXd::Identity(15, 15));
      const Information expected = inverse - Information::Identity() / mimo::k0;
      EXPECT_MATRIX_NEAR(observer.information(), expected, 1e-10 * expected.norm(), 0.0) << "step " << t;
      identity_checked = true;
    }
    if (next < at.size() && t == at[next]) level[next++] = observer.information_level().value();
    plant.advance();
  }
  EXPECT_TRUE(identity_checked);
  EXPECT_GT(observer.law().reset_count(), 0);  // I_t is kept through the resets
  for (std::size_t i = 0; i < at.size(); ++i) {
    EXPECT_GE(level[i], 0.9 * printed[i]) << "t = " << at[i];
    EXPECT_NEAR(level[i], measured[i], 1e-4) << "t = " << at[i];
  }
  EXPECT_GE(level[3] / level[2], 1.6);
  EXPECT_LE(level[3] / level[2], 2.0);
  EXPECT_NEAR(observer.excitation_level().value(), 5.662e-3, 1e-6);
  EXPECT_EQ(observer.excitation_rank(), 15);
}

// One sinusoid per input channel: the regressor spans 8 of the 15 directions.
// The window's λ_min is rounding (below 1e-10 λ_max), its rank 8, and λ_min(I_t)
// stays at rounding level however long the run: φ is not PE.
TEST(DeyBhasinExcitation, NotRichInputLeavesSevenDirectionsUnexcited) {
  auto observer = make_monitored_observer();
  auto plant = mimo::make_plant(mimo::NotRichInput{});
  double largest_level = 0;
  for (Index t = 0; t <= 1000; ++t) {
    ASSERT_EQ(observer.update(plant.sample()), UpdateStatus::accepted);
    if (t % 100 == 0) largest_level = std::max(largest_level, observer.information_level().value());
    plant.advance();
  }
  const Eigen::VectorXd lambda =
      adaptobs::symmetric_eigenvalues(Eigen::MatrixXd(observer.excitation_monitor()->average()));
  EXPECT_LT(observer.excitation_level().value(), 1e-10 * lambda(14));
  EXPECT_GT(lambda(7), 1e-5 * lambda(14));  // the eighth direction: excited (1.97e-4 λ_max)
  EXPECT_EQ(observer.excitation_rank(), 8);
  EXPECT_LT(largest_level, 1e-8);
  EXPECT_GT(adaptobs::symmetric_eigenvalues(observer.information())(14), 1e6);  // while λ_max grows
}

// Under a mask a sample adds φ_P R_PP⁻¹ φ_Pᵀ of its present channels P (here with
// an R that couples them), and a fully masked sample adds 0; a channel masked for
// the whole run leaves the B-rows it alone measures unexcited: rank 8, not 15.
TEST(DeyBhasinExcitation, AMaskedSampleContributesItsPresentRowsOnly) {
  Eigen::Matrix2d R;
  R << 2.0, 0.6, 0.6, 0.5;
  auto observer = make_monitored_observer(R);
  auto plant = mimo::make_plant(mimo::RichInput{});
  std::mt19937_64 generator(50);
  std::uniform_int_distribution<int> pattern(0, 3);
  Eigen::MatrixXd expected = Eigen::MatrixXd::Zero(15, 15);
  for (Index t = 0; t < 300; ++t) {
    const int bits = pattern(generator);
    const Mask present((bits & 1) != 0, (bits & 2) != 0);
    ASSERT_EQ(present.all() ? observer.update(plant.sample()) : observer.update(plant.sample(), present),
              UpdateStatus::accepted);
    expected += present_information(observer.regressor(), R, present);
    plant.advance();
  }
  EXPECT_MATRIX_NEAR(observer.information(), expected, 1e-12 * expected.norm(), 0.0);

  auto single = make_monitored_observer();
  auto replay = mimo::make_plant(mimo::RichInput{});
  for (Index t = 0; t <= 1000; ++t) {
    ASSERT_EQ(single.update(replay.sample(), Mask(true, false)), UpdateStatus::accepted);
    replay.advance();
  }
  EXPECT_EQ(single.excitation_rank(), 8);
  EXPECT_LT(single.information_level().value(), 1e-8);
}

// The diagnostics cost nothing unless asked for, are emptied by reset, survive a
// snapshot, and an observer without them keeps the field list of version 1.
TEST(DeyBhasinExcitation, OffByDefaultClearedByResetAndCarriedBySnapshots) {
  auto plain = mimo::make_observer();
  auto monitored = make_monitored_observer();
  auto plant = mimo::make_plant(mimo::RichInput{});
  for (Index t = 0; t < 150; ++t) {
    ASSERT_EQ(plain.update(plant.sample()), UpdateStatus::accepted);
    ASSERT_EQ(monitored.update(plant.sample()), UpdateStatus::accepted);
    plant.advance();
  }
  EXPECT_FALSE(plain.information_level() || plain.excitation_level() || plain.excitation_rank());
  EXPECT_TRUE(adaptobs::testing::bitwise_equal(plain.parameters(), monitored.parameters()));
  const auto plain_state = adaptobs::snapshot(plain);
  EXPECT_EQ(plain_state.find_integer("information"), nullptr);
  EXPECT_EQ(plain_state.find_matrix("information_sum"), nullptr);

  auto restored = make_monitored_observer();
  adaptobs::restore(restored, adaptobs::snapshot(monitored));
  auto plant_copy = plant;
  for (Index t = 0; t < 60; ++t) {
    ASSERT_EQ(monitored.update(plant.sample()), UpdateStatus::accepted);
    ASSERT_EQ(restored.update(plant_copy.sample()), UpdateStatus::accepted);
    plant.advance();
    plant_copy.advance();
  }
  EXPECT_TRUE(adaptobs::testing::bitwise_equal(restored.information(), monitored.information()));
  EXPECT_EQ(restored.excitation_level(), monitored.excitation_level());
  // With and without the diagnostics, neither restores the other's snapshot.
  EXPECT_CONFIGURATION_ERROR_NAMES(adaptobs::restore(restored, plain_state), "snapshot");
  auto other = mimo::make_observer();
  EXPECT_CONFIGURATION_ERROR_NAMES(adaptobs::restore(other, adaptobs::snapshot(monitored)), "snapshot");
  adaptobs::restore(other, plain_state);  // a version-1 field list restores as before
  EXPECT_TRUE(adaptobs::testing::bitwise_equal(other.parameters(), plain.parameters()));

  monitored.reset(mimo::x_hat0(), monitored.parameters());
  EXPECT_EQ(monitored.information_level(), 0.0);
  EXPECT_FALSE(monitored.excitation_level());
  EXPECT_CONFIGURATION_ERROR_NAMES(Observer(mimo::f(), mimo::x_hat0(), mimo::a_hat0(), mimo::B_hat0(),
                                            mimo::law_options(), {.excitation_window = -1}),
                                   "diagnostics.excitation_window");
}

// --- Implementation properties ------------------------------------------------------

// The observer contract (support/observer_contract.hpp) on the MIMO example
// with the rich input.
struct DeyBhasinContract {
  using Observer = ::Observer;
  using Sample = Observer::Sample;
  static Observer make() { return mimo::make_observer(); }
  static std::vector<Sample> samples() {
    return adaptobs::testing::first_samples<Sample>(mimo::make_plant(mimo::RichInput{}), 40,
                                                    [](const auto& s) { return Sample{s.u, s.y}; });
  }
  static auto readings(const auto& o) {
    return std::make_tuple(o.state(), o.current_state(), o.parameters(), o.regressor(), o.measurement(),
                           o.filter_bank(), o.law().covariance(), o.law().reset_count(), o.step());
  }
  static Observer::Output expected_output_error(const Observer& before, const Observer&, const Sample& s) {
    return s.y - db::canonical_output_matrix<double>(3, 2) * before.state();
  }
};

// The same observer and run with Eigen::Dynamic sizes.
struct DeyBhasinDynamicContract : DeyBhasinContract {
  using Observer = DynamicObserver;
  using Sample = Observer::Sample;
  using InFixed = DeyBhasinContract;
  // The a-priori error z − φᵀp̂ cancels terms far larger than itself: after this
  // run it differs from the fixed-size one by 3e-12, the rest by less than 1e-12.
  static constexpr double dynamic_tolerance = 1e-11;
  static Observer make() {
    return Observer(Eigen::VectorXd(mimo::f()), Eigen::VectorXd(mimo::x_hat0()), Eigen::VectorXd(mimo::a_hat0()),
                    Eigen::MatrixXd(mimo::B_hat0()),
                    {.k0 = mimo::k0, .kmin = mimo::kmin, .R = Eigen::MatrixXd::Identity(2, 2)});
  }
  static std::vector<Sample> samples() {
    return adaptobs::testing::first_samples<Sample>(mimo::make_plant(mimo::RichInput{}), 40,
                                                    [](const auto& s) { return Sample{s.u, s.y}; });
  }
};

}  // namespace

ADAPTOBS_OBSERVER_CONTRACT(DeyBhasin, DeyBhasinContract);
ADAPTOBS_TWIN_CONTRACT(DeyBhasin, DynamicFollowsFixed, DeyBhasinDynamicContract);

namespace {

using adaptobs::testing::configuration_error_of;

TEST(DeyBhasin, BadConfigurationNamesTheArgument) {
  const auto options = mimo::law_options();
  EXPECT_CONFIGURATION_ERROR_NAMES(Observer(mimo::printed_a(), mimo::x_hat0(), mimo::a_hat0(), mimo::B_hat0(), options),
                                   "f");
  Eigen::Vector3d nan_a0 = mimo::a_hat0();
  nan_a0(1) = std::nan("");
  EXPECT_CONFIGURATION_ERROR_NAMES(Observer(mimo::f(), mimo::x_hat0(), nan_a0, mimo::B_hat0(), options), "a0");
  Eigen::Matrix<double, 6, 1> nan_x0 = mimo::x_hat0();
  nan_x0(4) = std::nan("");
  EXPECT_CONFIGURATION_ERROR_NAMES(Observer(mimo::f(), nan_x0, mimo::a_hat0(), mimo::B_hat0(), options), "x0");
  // Covariance and weight: indefinite or non-symmetric R, Γ0.
  auto bad_r = options;
  bad_r.R(1, 1) = -1;
  EXPECT_CONFIGURATION_ERROR_NAMES(Observer(mimo::f(), mimo::x_hat0(), mimo::a_hat0(), mimo::B_hat0(), bad_r), "R");
  bad_r = options;
  bad_r.R(0, 1) = 0.5;
  EXPECT_CONFIGURATION_ERROR_NAMES(Observer(mimo::f(), mimo::x_hat0(), mimo::a_hat0(), mimo::B_hat0(), bad_r), "R");
  auto bad_kmin = options;
  bad_kmin.kmin = 2 * bad_kmin.k0;
  EXPECT_CONFIGURATION_ERROR_NAMES(Observer(mimo::f(), mimo::x_hat0(), mimo::a_hat0(), mimo::B_hat0(), bad_kmin),
                                   "kmin");
  using RlsObserver = adaptobs::DeyBhasinObserver<double, 3, 2, 2, adaptobs::RecursiveLeastSquares>;
  Eigen::Matrix<double, 15, 15> gamma0 = Eigen::Matrix<double, 15, 15>::Identity();
  gamma0(3, 3) = -1;
  EXPECT_CONFIGURATION_ERROR_NAMES(RlsObserver(mimo::f(), mimo::x_hat0(), mimo::a_hat0(), mimo::B_hat0(),
                                               {.gamma0 = gamma0, .R = Eigen::Matrix2d::Identity()}),
                                   "gamma0");
  gamma0 = Eigen::Matrix<double, 15, 15>::Identity();
  gamma0(2, 7) = 0.1;
  EXPECT_CONFIGURATION_ERROR_NAMES(RlsObserver(mimo::f(), mimo::x_hat0(), mimo::a_hat0(), mimo::B_hat0(),
                                               {.gamma0 = gamma0, .R = Eigen::Matrix2d::Identity()}),
                                   "gamma0");
  // Dynamic sizes: shapes that do not fit together.
  const auto dyn_options = DynamicObserver::LawOptions{.k0 = 10, .kmin = 1e-3, .R = Eigen::MatrixXd::Identity(2, 2)};
  EXPECT_CONFIGURATION_ERROR_NAMES(
      DynamicObserver(Eigen::VectorXd(mimo::f()), Eigen::VectorXd::Zero(7), Eigen::VectorXd(mimo::a_hat0()),
                      Eigen::MatrixXd::Zero(7, 2), dyn_options),
      "x0");
  EXPECT_CONFIGURATION_ERROR_NAMES(DynamicObserver(Eigen::VectorXd(mimo::f()), Eigen::VectorXd::Zero(6),
                                                   Eigen::VectorXd::Zero(2), Eigen::MatrixXd::Zero(6, 2), dyn_options),
                                   "a0");
  EXPECT_CONFIGURATION_ERROR_NAMES(
      DynamicObserver(Eigen::VectorXd(mimo::f()), Eigen::VectorXd::Zero(6), Eigen::VectorXd(mimo::a_hat0()),
                      Eigen::MatrixXd::Zero(5, 2), dyn_options),
      "B0");
  EXPECT_CONFIGURATION_ERROR_NAMES(
      DynamicObserver(Eigen::VectorXd(mimo::f()), Eigen::VectorXd::Zero(6), Eigen::VectorXd(mimo::a_hat0()),
                      Eigen::MatrixXd::Zero(6, 2), {.k0 = 10, .kmin = 1e-3, .R = Eigen::MatrixXd::Identity(3, 3)}),
      "R");
  DynamicObserver observer(Eigen::VectorXd(mimo::f()), Eigen::VectorXd::Zero(6), Eigen::VectorXd(mimo::a_hat0()),
                           Eigen::MatrixXd::Zero(6, 2), dyn_options);
  EXPECT_CONFIGURATION_ERROR_NAMES(
      observer.update(DynamicObserver::Sample{Eigen::VectorXd::Zero(3), Eigen::VectorXd::Zero(2)}), "sample.u");
  EXPECT_CONFIGURATION_ERROR_NAMES(observer.reset(Eigen::VectorXd::Zero(6), Eigen::VectorXd::Zero(14)), "p0");
  EXPECT_CONFIGURATION_ERROR_NAMES(observer.state_with(Eigen::VectorXd::Zero(14)), "p");
  // A run-time order with a compile-time output count q = 2: x0 needs r·q = 6
  // entries, even where another q would divide its length.
  using RunTimeOrder = adaptobs::DeyBhasinObserver<double, Eigen::Dynamic, 2, 2>;
  EXPECT_CONFIGURATION_ERROR_NAMES(
      RunTimeOrder(Eigen::VectorXd(mimo::f()), Eigen::VectorXd::Zero(9), Eigen::VectorXd(mimo::a_hat0()),
                   Eigen::MatrixXd::Zero(6, 2), {.k0 = 10, .kmin = 1e-3, .R = Eigen::Matrix2d::Identity()}),
      "x0");
}

}  // namespace
