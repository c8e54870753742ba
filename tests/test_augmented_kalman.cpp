// Augmented-state Kalman filter baseline (paper 000 §1, paper 001 appendix).

#include <adaptobs/baselines/augmented_kalman.hpp>
#include <adaptobs/core/observer.hpp>

#include <Eigen/Eigenvalues>

#include "models/satellite.hpp"
#include "support/eigen_testing.hpp"

#include <gtest/gtest.h>

#include <limits>
#include <string>
#include <utility>

namespace {

using adaptobs::Index;
using adaptobs::UpdateStatus;
namespace satellite = adaptobs::examples::satellite;
using Dims = satellite::Dims<double>;
using Matrix6 = Eigen::Matrix<double, 6, 6>;

adaptobs::AugmentedKalmanCovariances<Dims> satellite_covariances() {
  Matrix6 p0 = Matrix6::Zero();
  p0.diagonal() << 0.1, 1e-4, 0.1, 1e-4, 1.0, 1.0;
  Matrix6 q = Matrix6::Zero();
  q.diagonal() << 1e-10, 1e-10, 1e-10, 1e-10, 0.0, 0.0;
  return {p0, q, Eigen::Matrix2d::Identity() * 1e-4};
}

auto make_filter() {
  return adaptobs::AugmentedKalmanFilter(satellite::model<double>(), satellite::initial_state_estimate<double>(),
                                         satellite::initial_parameter_estimate<double>(), satellite_covariances());
}

TEST(AugmentedKalman, SatelliteConvergesToTrueParameters) {
  auto filter = make_filter();
  auto plant = satellite::make_plant<double>();  // σ = 0.01
  Eigen::Vector2d sum = Eigen::Vector2d::Zero();
  for (Index k = 0; k < 3000; ++k) {
    ASSERT_EQ(filter.update(plant.sample()), UpdateStatus::accepted);
    plant.advance();
    if (k >= 2000) sum += filter.parameters();
  }
  EXPECT_MATRIX_NEAR(Eigen::Vector2d(sum / 1000.0), satellite::true_parameters<double>(), 0.02, 0.0);
  // The covariance stays symmetric positive definite.
  const Matrix6 p = filter.covariance();
  EXPECT_LE((p - p.transpose()).norm(), 1e-15 * p.norm());
  EXPECT_GT(Eigen::SelfAdjointEigenSolver<Matrix6>(p).eigenvalues()(0), 0.0);
}

// With run-time sizes every entry of the sample is checked before it is read: a
// wrong shape throws naming the entry, and the filter is bit-for-bit unchanged.
TEST(AugmentedKalman, WrongSampleSizesThrowNamingTheEntryAndChangeNothing) {
  using DynDims = adaptobs::DynamicDimensions<double>;
  using DynamicSample = adaptobs::DiscreteSample<DynDims>;
  const auto fixed_model = satellite::model<double>();
  const adaptobs::DiscreteLtiModel<DynDims> model(fixed_model.system().A, fixed_model.system().B,
                                                  fixed_model.system().C, 2);
  const auto fixed_covariances = satellite_covariances();
  adaptobs::AugmentedKalmanFilter dynamic(
      model, Eigen::VectorXd(satellite::initial_state_estimate<double>()),
      Eigen::VectorXd(satellite::initial_parameter_estimate<double>()),
      adaptobs::AugmentedKalmanCovariances<DynDims>{fixed_covariances.P0, fixed_covariances.Q, fixed_covariances.R});
  auto fixed = make_filter();
  auto plant = satellite::make_plant<double>();
  for (Index k = 0; k < 50; ++k) {
    const auto& s = plant.sample();
    ASSERT_EQ(fixed.update(s), UpdateStatus::accepted);
    ASSERT_EQ(dynamic.update(DynamicSample{s.u, s.y, s.Psi}), UpdateStatus::accepted);
    plant.advance();
  }
  const Eigen::VectorXd x = dynamic.state(), theta = dynamic.parameters();
  const Eigen::MatrixXd p = dynamic.covariance();
  const auto& s = plant.sample();
  const Eigen::VectorXd u = s.u, y = s.y;
  const Eigen::MatrixXd psi = s.Psi;
  const auto expect_rejected = [&](const DynamicSample& bad, const char* entry) {
    const std::string message = adaptobs::testing::configuration_error_of([&] { (void)dynamic.update(bad); });
    EXPECT_NE(message.find(std::string("'") + entry + "'"), std::string::npos) << message;
    EXPECT_NE(message.find("AugmentedKalmanFilter::update"), std::string::npos) << message;
    EXPECT_EQ(dynamic.step(), 50);
    EXPECT_TRUE(dynamic.state() == x && dynamic.parameters() == theta && dynamic.covariance() == p) << entry;
  };
  expect_rejected({Eigen::VectorXd::Ones(200), y, psi}, "sample.u");
  expect_rejected({u, Eigen::VectorXd::Ones(1), psi}, "sample.y");
  expect_rejected({u, y, Eigen::MatrixXd::Ones(4, 1)}, "sample.Psi");
  expect_rejected({u, y, Eigen::MatrixXd::Ones(3, 2)}, "sample.Psi");
  // The good sample is still accepted and gives the fixed-size filter's numbers.
  ASSERT_EQ(fixed.update(s), UpdateStatus::accepted);
  ASSERT_EQ(dynamic.update(DynamicSample{u, y, psi}), UpdateStatus::accepted);
  EXPECT_MATRIX_NEAR(dynamic.state(), fixed.state(), 1e-12, 1e-12);
  EXPECT_MATRIX_NEAR(dynamic.parameters(), fixed.parameters(), 1e-12, 1e-12);
  EXPECT_MATRIX_NEAR(dynamic.output_error(), fixed.output_error(), 1e-12, 1e-12);
}

TEST(AugmentedKalman, NoiseFreeAgreesWithExactState) {
  auto filter = make_filter();
  auto plant = satellite::make_plant<double>(0.0);
  for (Index k = 0; k < 3000; ++k) {
    ASSERT_EQ(filter.update(plant.sample()), UpdateStatus::accepted);
    plant.advance();
  }
  EXPECT_MATRIX_NEAR(filter.parameters(), plant.parameters(), 1e-4, 0.0);
  EXPECT_MATRIX_NEAR(filter.state(), plant.state(), 1e-4, 1e-6);
}

// A filter and its plant after 50 accepted samples.
auto filter_after_50_samples() {
  auto filter = make_filter();
  auto plant = satellite::make_plant<double>();
  for (Index k = 0; k < 50; ++k) {
    EXPECT_EQ(filter.update(plant.sample()), UpdateStatus::accepted);
    plant.advance();
  }
  return std::pair(std::move(filter), std::move(plant));
}

// The filter's estimates and covariance, compared bit for bit.
struct Snapshot {
  template <class Filter>
  explicit Snapshot(const Filter& f) : x(f.state()), theta(f.parameters()), p(f.covariance()), step(f.step()) {}
  bool operator==(const Snapshot& o) const {
    using adaptobs::testing::bitwise_equal;
    return bitwise_equal(x, o.x) && bitwise_equal(theta, o.theta) && bitwise_equal(p, o.p) && step == o.step;
  }
  Eigen::Vector4d x;
  Eigen::Vector2d theta;
  Matrix6 p;
  Index step;
};

TEST(AugmentedKalman, NonFiniteSamplesAreRejectedAndChangeNothing) {
  auto [filter, plant] = filter_after_50_samples();
  const Snapshot before(filter);
  auto s = plant.sample();
  s.y(0) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(filter.update(s), UpdateStatus::nonfinite_input);
  s = plant.sample();
  s.Psi(1, 0) = std::numeric_limits<double>::infinity();
  EXPECT_EQ(filter.update(s), UpdateStatus::nonfinite_input);
  s = plant.sample();
  s.y.setConstant(std::numeric_limits<double>::max());
  s.Psi.setConstant(std::numeric_limits<double>::max());
  EXPECT_EQ(filter.update(s), UpdateStatus::nonfinite_result);
  EXPECT_TRUE(Snapshot(filter) == before);
  EXPECT_EQ(filter.step(), 50);
}

TEST(AugmentedKalman, AStepThatWouldLeaveTheCovarianceIndefiniteIsRejected) {
  auto [filter, plant] = filter_after_50_samples();
  const Snapshot before(filter);
  // Finite, but Ψ P Ψᵀ ≈ 1e300 swamps P: in floating point P⁺ is no longer positive
  // definite, and accepting it would make every later step overflow.
  auto s = plant.sample();
  s.Psi.setConstant(1e150);
  EXPECT_EQ(filter.update(s), UpdateStatus::indefinite_covariance);
  EXPECT_TRUE(Snapshot(filter) == before);
  // The filter goes on from where it was and still converges.
  Eigen::Vector2d sum = Eigen::Vector2d::Zero();
  for (Index k = 0; k < 3000; ++k) {
    ASSERT_EQ(filter.update(plant.sample()), UpdateStatus::accepted) << "step " << k;
    plant.advance();
    if (k >= 2000) sum += filter.parameters();
  }
  EXPECT_MATRIX_NEAR(Eigen::Vector2d(sum / 1000.0), satellite::true_parameters<double>(), 0.02, 0.0);
}

// output_error(): the innovation y_k − C x̂_{k|k−1} of the correction, from the
// state() before the update; zero in an absent channel, before the first update
// and after a reset, and unchanged by a rejected sample (three kinds).
TEST(AugmentedKalman, OutputErrorIsTheInnovationOfTheCorrection) {
  static_assert(adaptobs::DiagnosableObserver<decltype(make_filter())>);
  using Mask = adaptobs::OutputMask<Dims>;
  auto filter = make_filter();
  auto plant = satellite::make_plant<double>();
  const Eigen::Matrix<double, 2, 4> c = satellite::model<double>().system().C;
  EXPECT_TRUE(filter.output_error() == Eigen::Vector2d::Zero());
  double largest = 0;
  for (Index k = 0; k < 40; ++k) {
    const Mask present(true, k % 4 != 2);
    auto sample = plant.sample();
    if (!present(1)) sample.y(1) = std::numeric_limits<double>::quiet_NaN();
    const Eigen::Vector4d predicted = filter.state();
    ASSERT_EQ(filter.update(sample, present), UpdateStatus::accepted);
    Eigen::Vector2d expected = sample.y - c * predicted;
    if (!present(1)) {
      expected(1) = 0;
      EXPECT_EQ(filter.output_error()(1), 0.0) << "step " << k;
    }
    EXPECT_MATRIX_NEAR(filter.output_error(), expected, 1e-12, 1e-12) << "step " << k;
    largest = std::max(largest, expected.cwiseAbs().maxCoeff());
    plant.advance();
  }
  EXPECT_GT(largest, 1e-3);

  const Eigen::Vector2d accepted = filter.output_error();
  auto s = plant.sample();
  s.y(0) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(filter.update(s), UpdateStatus::nonfinite_input);
  EXPECT_TRUE(adaptobs::testing::bitwise_equal(filter.output_error(), accepted));
  s = plant.sample();
  s.y.setConstant(std::numeric_limits<double>::max());
  s.Psi.setConstant(std::numeric_limits<double>::max());
  EXPECT_EQ(filter.update(s), UpdateStatus::nonfinite_result);
  EXPECT_TRUE(adaptobs::testing::bitwise_equal(filter.output_error(), accepted));
  s = plant.sample();
  s.Psi.setConstant(1e150);
  EXPECT_EQ(filter.update(s), UpdateStatus::indefinite_covariance);
  EXPECT_TRUE(adaptobs::testing::bitwise_equal(filter.output_error(), accepted));
  filter.reset(satellite::initial_state_estimate<double>(), satellite::initial_parameter_estimate<double>());
  EXPECT_TRUE(filter.output_error() == Eigen::Vector2d::Zero());
}

TEST(AugmentedKalman, BadCovariancesNameTheArgument) {
  auto message_of = [](adaptobs::AugmentedKalmanCovariances<Dims> c) -> std::string {
    try {
      adaptobs::AugmentedKalmanFilter f(satellite::model<double>(), Eigen::Vector4d::Zero().eval(),
                                        Eigen::Vector2d::Zero().eval(), c);
    } catch (const adaptobs::ConfigurationError& e) {
      return e.what();
    }
    return "<no exception>";
  };
  auto c = satellite_covariances();
  c.P0(4, 4) = -1;
  EXPECT_NE(message_of(c).find("'covariances.P0'"), std::string::npos);
  c = satellite_covariances();
  c.Q(0, 0) = -1;
  EXPECT_NE(message_of(c).find("'covariances.Q'"), std::string::npos);
  c = satellite_covariances();
  c.R(0, 1) = 0.5;
  EXPECT_NE(message_of(c).find("'covariances.R'"), std::string::npos);
}

static_assert(adaptobs::Observer<decltype(make_filter())>);

}  // namespace
