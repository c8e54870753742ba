// Matrix exponential and zero-order-hold discretization: closed forms, the
// satellite matrices printed in paper 000 §4, and configuration errors.

#include <adaptobs/core/discretization.hpp>
#include <adaptobs/core/matrix_exponential.hpp>

#include "models/satellite.hpp"
#include "support/eigen_testing.hpp"

#include <gtest/gtest.h>

#include <Eigen/QR>

#include <cmath>
#include <string>

namespace {

using adaptobs::ConfigurationError;
using adaptobs::discretize_zoh;
using adaptobs::integral_of_exponential;
using adaptobs::matrix_exponential;
using adaptobs::testing::RandomMatrices;
namespace satellite = adaptobs::examples::satellite;

TEST(MatrixExponential, NilpotentMatchesFiniteSeries) {
  RandomMatrices rng(11);
  for (int trial = 0; trial < 20; ++trial) {
    // Strictly upper triangular, so N⁴ = 0 and e^N = I + N + N²/2 + N³/6 exactly.
    Eigen::Matrix4d n = rng.uniform<Eigen::Matrix4d>(4, 4, -3, 3).triangularView<Eigen::StrictlyUpper>();
    const Eigen::Matrix4d expected = Eigen::Matrix4d::Identity() + n + n * n / 2 + n * n * n / 6;
    EXPECT_MATRIX_NEAR(matrix_exponential(n), expected, 1e-12, 1e-12) << "trial " << trial;
  }
}

TEST(MatrixExponential, DiagonalizableMatchesSpectralForm) {
  RandomMatrices rng(12);
  for (double scale : {1e-3, 0.1, 1.0, 4.0, 20.0}) {
    // Symmetric A = Q D Qᵀ with Q orthogonal: e^A = Q e^D Qᵀ, well conditioned.
    const Eigen::Matrix<double, 5, 5> q = rng.uniform<Eigen::Matrix<double, 5, 5>>().householderQr().householderQ();
    const Eigen::Matrix<double, 5, 1> d = rng.uniform<Eigen::Matrix<double, 5, 1>>(5, 1, -scale, scale);
    const Eigen::Matrix<double, 5, 5> a = q * d.asDiagonal() * q.transpose();
    const Eigen::Matrix<double, 5, 5> expected = q * d.array().exp().matrix().asDiagonal() * q.transpose();
    const double size = expected.cwiseAbs().maxCoeff();
    EXPECT_MATRIX_NEAR(matrix_exponential(a), expected, 1e-12 * size, 0.0) << "scale " << scale;
  }
}

TEST(MatrixExponential, RotationGenerator) {
  for (double w : {1e-6, 0.3, 2.0, 50.0}) {
    Eigen::Matrix2d a;
    a << 0, w, -w, 0;
    Eigen::Matrix2d expected;
    expected << std::cos(w), std::sin(w), -std::sin(w), std::cos(w);
    EXPECT_MATRIX_NEAR(matrix_exponential(a), expected, 1e-12, 0.0) << "w = " << w;
  }
}

TEST(MatrixExponential, FloatAgreesWithDouble) {
  RandomMatrices rng(13);
  const Eigen::Matrix3d a = rng.uniform<Eigen::Matrix3d>(3, 3, -2, 2);
  const Eigen::Matrix3f af = a.cast<float>();
  EXPECT_MATRIX_NEAR(matrix_exponential(af).cast<double>(), matrix_exponential(a), 1e-5, 1e-5);
}

TEST(MatrixExponential, DynamicSizeEqualsFixedSize) {
  RandomMatrices rng(14);
  const Eigen::Matrix4d a = rng.uniform<Eigen::Matrix4d>(4, 4, -5, 5);
  const Eigen::MatrixXd ad = a;
  EXPECT_TRUE(adaptobs::testing::bitwise_equal(Eigen::MatrixXd(matrix_exponential(a)), matrix_exponential(ad)));
}

TEST(ZeroOrderHold, DoubleIntegratorClosedForm) {
  const double ts = 0.37;
  Eigen::Matrix2d a;
  a << 0, 1, 0, 0;
  const Eigen::Vector2d b(0, 1);
  const auto zoh = discretize_zoh(a, b, ts);
  Eigen::Matrix2d ad;
  ad << 1, ts, 0, 1;
  EXPECT_MATRIX_NEAR(zoh.Ad, ad, 1e-15, 0.0);
  EXPECT_MATRIX_NEAR(zoh.Bd, Eigen::Vector2d(ts * ts / 2, ts), 1e-15, 0.0);
}

TEST(ZeroOrderHold, DiagonalSystemClosedForm) {
  const double ts = 0.25;
  const Eigen::Vector3d lambda(-2.0, 0.5, -0.1);
  const Eigen::Matrix3d a = lambda.asDiagonal();
  const Eigen::Matrix3d h = integral_of_exponential(a, ts);
  for (int i = 0; i < 3; ++i) {
    // ∫₀^Ts e^{λs} ds = (e^{λTs} − 1)/λ
    EXPECT_NEAR(h(i, i), std::expm1(lambda(i) * ts) / lambda(i), 1e-15);
  }
  EXPECT_NEAR((h - Eigen::Matrix3d(h.diagonal().asDiagonal())).norm(), 0.0, 1e-15);
}

// One printed entry of paper 000 §4 and the number of significant digits printed.
struct Printed {
  int row, col;
  double value;
  int digits;
};

// "Matches to the printed digits": half a unit in the last printed digit for
// rounded entries; values printed with one digit (1, 0.1, 0.005) and zeros are
// the exact leading terms, held to 1e-8 relative (resp. exactly zero).
double printed_tolerance(const Printed& p) {
  if (p.value == 0) return 0.0;
  if (p.digits == 1) return 1e-8 * std::abs(p.value);
  const int exponent = static_cast<int>(std::floor(std::log10(std::abs(p.value))));
  return 0.5 * std::pow(10.0, exponent - p.digits + 1);
}

TEST(ZeroOrderHold, SatelliteMatchesPaper) {
  const auto zoh = satellite::discretized<double>();
  // A_d as printed.
  const Printed a_printed[] = {
      {0, 0, 1, 1},          {0, 1, 0.1, 1},        {0, 2, 0, 1},     {0, 3, 3.49e-6, 3},
      {1, 1, 1, 1},          {1, 2, 0, 1},          {1, 3, 6.98e-5, 3},
      {2, 0, -4.25e-14, 3},  {2, 1, -3.49e-6, 3},   {2, 2, 1, 1},     {2, 3, 0.1, 1},
      {3, 0, -1.28e-12, 3},  {3, 1, -6.98e-5, 3},   {3, 2, 0, 1},     {3, 3, 1, 1},
  };
  for (const Printed& p : a_printed) {
    EXPECT_NEAR(zoh.Ad(p.row, p.col), p.value, printed_tolerance(p)) << "A(" << p.row << "," << p.col << ")";
  }
  // A(1,0) is printed 3.66e-8, but 3ω²Ts = 3.654e-8 for ω = 3.49e-4; every other
  // entry in ω² (H(1,0) = 1.83e-9 = 3ω²Ts²/2) confirms ω = 3.49e-4, so the
  // printed third digit is off by one. Hold it to one unit in the last digit.
  EXPECT_NEAR(zoh.Ad(1, 0), 3.66e-8, 1e-10);
  EXPECT_NEAR(zoh.Ad(1, 0), 3 * satellite::omega * satellite::omega * satellite::sampling_period, 1e-12);

  const Printed h_printed[] = {
      {0, 0, 0.1, 1},         {0, 1, 0.005, 1},       {0, 2, 0, 1},   {0, 3, 1.16e-7, 3},
      {1, 0, 1.83e-9, 3},     {1, 1, 0.1, 1},         {1, 2, 0, 1},   {1, 3, 3.49e-6, 3},
      {2, 0, -1.06e-15, 3},   {2, 1, -1.16e-7, 3},    {2, 2, 0.1, 1}, {2, 3, 0.005, 1},
      {3, 0, -4.25e-14, 3},   {3, 1, -3.49e-6, 3},    {3, 2, 0, 1},   {3, 3, 0.1, 1},
  };
  for (const Printed& p : h_printed) {
    EXPECT_NEAR(zoh.Bd(p.row, p.col), p.value, printed_tolerance(p)) << "H(" << p.row << "," << p.col << ")";
  }
}

TEST(ZeroOrderHold, FloatAgreesWithDouble) {
  const auto d = satellite::discretized<double>();
  const auto f = satellite::discretized<float>();
  EXPECT_MATRIX_NEAR(f.Ad.cast<double>(), d.Ad, 1e-6, 0.0);
  EXPECT_MATRIX_NEAR(f.Bd.cast<double>(), d.Bd, 1e-7, 0.0);
}

using adaptobs::testing::configuration_error_of;

TEST(ZeroOrderHold, BadConfigurationNamesTheArgument) {
  const Eigen::MatrixXd non_square = Eigen::MatrixXd::Ones(2, 3);
  const Eigen::MatrixXd b = Eigen::MatrixXd::Ones(2, 1);
  EXPECT_NE(configuration_error_of([&] { (void)discretize_zoh(non_square, b, 0.1); }).find("'A'"), std::string::npos);
  const Eigen::MatrixXd a = Eigen::MatrixXd::Identity(2, 2);
  const Eigen::MatrixXd wrong_b = Eigen::MatrixXd::Ones(3, 1);
  EXPECT_NE(configuration_error_of([&] { (void)discretize_zoh(a, wrong_b, 0.1); }).find("'B'"), std::string::npos);
  EXPECT_NE(configuration_error_of([&] { (void)discretize_zoh(a, b, -0.1); }).find("'ts'"), std::string::npos);
  Eigen::Matrix2d nan_a = Eigen::Matrix2d::Identity();
  nan_a(0, 1) = std::nan("");
  EXPECT_NE(configuration_error_of([&] { (void)matrix_exponential(nan_a); }).find("'A'"), std::string::npos);
}

}  // namespace
