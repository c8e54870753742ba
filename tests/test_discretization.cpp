// Matrix exponential and zero-order-hold discretization: closed forms, the
// satellite matrices printed in Guyader & Zhang (2003) §4, and configuration errors.

#include <adaptobs/core/discretization.hpp>
#include <adaptobs/core/matrix_exponential.hpp>

#include "models/satellite.hpp"
#include "support/eigen_testing.hpp"

#include <gtest/gtest.h>
#include <Eigen/SVD>

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

namespace {

using adaptobs::ConfigurationError;
using adaptobs::discretize_zoh;
using adaptobs::integral_of_exponential;
using adaptobs::matrix_exponential;
using adaptobs::testing::configuration_error_of;
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
    const Eigen::Matrix<double, 5, 5> q = adaptobs::testing::random_orthogonal(rng, 5);
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

// Large-norm cases with closed forms: scaling by ‖A‖ alone squares a rounding
// error up to 2^s ≈ ‖A‖ times, so these fail by many digits without the
// ‖Aᵏ‖^{1/k} bounds, the exact triangular bands, balancing and block splitting.
double worst_relative_error(const Eigen::MatrixXd& got, const Eigen::MatrixXd& exact) {
  double worst = 0;
  for (Eigen::Index i = 0; i < exact.size(); ++i) {
    const double e = exact.data()[i];
    const double error = std::abs(got.data()[i] - e);
    worst =
        std::max(worst, e == 0 ? (error == 0 ? 0.0 : std::numeric_limits<double>::infinity()) : error / std::abs(e));
  }
  return worst;
}

TEST(MatrixExponential, LargeNilpotentIsExact) {
  for (double b : {1e4, 1e10, 1e16, 1e300}) {
    Eigen::Matrix2d a;
    a << 0, b, 0, 0;
    EXPECT_LE(worst_relative_error(matrix_exponential(a), Eigen::Matrix2d::Identity() + a), 1e-12) << "b = " << b;
    // Not triangular, already balanced, and A² = 0 exactly in floating point: only
    // the ‖Aᵏ‖^{1/k} bound sees that no scaling is needed.
    Eigen::Matrix2d full;
    full << b, -b, b, -b;
    EXPECT_LE(worst_relative_error(matrix_exponential(full), Eigen::Matrix2d::Identity() + full), 1e-12)
        << "[[b, -b], [b, -b]], b = " << b;
  }
}

TEST(MatrixExponential, StiffTriangularMatchesDividedDifferences) {
  for (double b : {1.0, 1e8, 1e16}) {
    // Distinct eigenvalues λ = −1, −2, −3: entry (i, j) of e^A is the product of the
    // superdiagonal entries times the divided difference of exp over λ_i … λ_j.
    Eigen::Matrix3d a;
    a << -1, b, 0, 0, -2, b, 0, 0, -3;
    const double e1 = std::exp(-1.0), e2 = std::exp(-2.0), e3 = std::exp(-3.0);
    const double d12 = e1 - e2, d23 = e2 - e3, d123 = (d12 - d23) / 2;
    Eigen::Matrix3d expected;
    expected << e1, b * d12, b * b * d123, 0, e2, b * d23, 0, 0, e3;
    EXPECT_LE(worst_relative_error(matrix_exponential(a), expected), 1e-12) << "b = " << b;
    EXPECT_LE(worst_relative_error(matrix_exponential(Eigen::Matrix3d(a.transpose())), expected.transpose()), 1e-12)
        << "lower triangular, b = " << b;
  }
  for (double b : {1e16, 1e100, 1e300})
    for (double lambda : {-1.0, -10.0, -400.0}) {
      // A Jordan block: e^A = e^λ(I + N). Its ‖Aᵏ‖^{1/k} ≈ (kb)^{1/k} asks for
      // hundreds of squarings, each of which would double the error of the
      // diagonal. With b = 1e300 and |λ| > 1 the powers of A / ‖A‖ underflow to
      // zero while A² overflows, which was once taken for nilpotency
      // (e^A(0, 0) read 1342.59 for 4.54e-5 at λ = −10).
      Eigen::Matrix2d a;
      a << lambda, b, 0, lambda;
      Eigen::Matrix2d expected;
      expected << 1, b, 0, 1;
      EXPECT_LE(worst_relative_error(matrix_exponential(a), std::exp(lambda) * expected), 1e-12)
          << "Jordan, λ = " << lambda << ", b = " << b;
    }
  for (double k : {1e3, 1e10, 1e16, 1e300}) {
    const Eigen::Matrix2d a = Eigen::Vector2d(-k, 0).asDiagonal();
    EXPECT_LE(worst_relative_error(matrix_exponential(a), Eigen::Vector2d(std::exp(-k), 1).asDiagonal()), 1e-12)
        << "diag(-" << k << ", 0)";
  }
}

TEST(MatrixExponential, StiffBlockDiagonalKeepsEveryBlockAccurate) {
  for (double k : {1e2, 1e8, 1e16}) {
    // A stiff triangular block beside a rotation block (permuted): the rotation
    // must not pay for the stiff block's scaling.
    Eigen::Matrix4d block;
    block << -k, 0, k, 0, 0, 0, 0, 3, 0, 0, -1, 0, 0, -3, 0, 0;
    Eigen::Matrix4d expected = Eigen::Matrix4d::Zero();
    expected(0, 0) = std::exp(-k);
    expected(0, 2) = k * (std::exp(-k) - std::exp(-1.0)) / (1 - k);
    expected(2, 2) = std::exp(-1.0);
    expected(1, 1) = expected(3, 3) = std::cos(3.0);
    expected(1, 3) = std::sin(3.0);
    expected(3, 1) = -std::sin(3.0);
    EXPECT_LE(worst_relative_error(matrix_exponential(block), expected), 1e-12) << "k = " << k;
  }
}

TEST(MatrixExponential, BadlyScaledSimilarityIsBalanced) {
  // M has eigenvalues −2 and −3: e^M = e^{−2}(M + 3I) − e^{−3}(M + 2I), and e^{DMD⁻¹} = D e^M D⁻¹.
  Eigen::Matrix2d m;
  m << -1, 2, -1, -4;
  const Eigen::Matrix2d i2 = Eigen::Matrix2d::Identity();
  const Eigen::Matrix2d em = std::exp(-2.0) * (m + 3 * i2) - std::exp(-3.0) * (m + 2 * i2);
  for (double s : {1e2, 1e10, 1e15}) {
    const Eigen::DiagonalMatrix<double, 2> d(1, s), d_inverse(1, 1 / s);
    const Eigen::Matrix2d a = d * m * d_inverse;
    EXPECT_LE(worst_relative_error(matrix_exponential(a), Eigen::Matrix2d(d * em * d_inverse)), 1e-12) << "s = " << s;
  }
  // A² = 2⁻⁵¹I, so e^A = cosh(w)I + sinh(w)/w A with w = 2^{−25.5}: its (2, 1) entry,
  // 9e307, is representable, but the balancing's ratio 2^1049 of D's entries is
  // not, which once refused the result as beyond the floating-point range.
  {
    const double tiny = std::ldexp(1.0, -1074), huge = std::ldexp(1.0, 1023);
    Eigen::Matrix2d a;
    a << 0, tiny, huge, 0;
    const double w = std::sqrt(tiny * huge);  // tiny · huge = 2⁻⁵¹ exactly
    const double cosh = std::cosh(w), sinh_over = std::sinh(w) / w;
    const Eigen::Matrix2d e = matrix_exponential(a);
    EXPECT_NEAR(e(0, 0), cosh, 1e-15);
    EXPECT_NEAR(e(1, 1), cosh, 1e-15);
    EXPECT_NEAR(e(1, 0) / huge, sinh_over, 1e-15);
  }
  // Symmetric M = Q Λ Qᵀ, so e^M = Q e^Λ Qᵀ independently of the exponential; seen through
  // D = diag(1, s, s²) its entries span up to 1e32 in magnitude.
  Eigen::Matrix3d sym;
  sym << -2, 1, 0.5, 1, -3, 1, 0.5, 1, -1;
  const Eigen::Matrix3d e_sym = adaptobs::testing::symmetric_exponential(sym);
  for (double s : {1e4, 1e8, 1e16}) {
    const Eigen::Vector3d d(1, s, s * s);
    const Eigen::Matrix3d a = d.asDiagonal() * sym * d.cwiseInverse().asDiagonal();
    const Eigen::Matrix3d expected = d.asDiagonal() * e_sym * d.cwiseInverse().asDiagonal();
    EXPECT_LE(worst_relative_error(matrix_exponential(a), expected), 1e-12) << "s = " << s;
  }
  for (double b : {1e8, 1e16}) {
    // [[0, b], [−1/b, 0]]² = −I: e^A = cos 1·I + sin 1·A, a rotation seen through diag(1, 1/b).
    Eigen::Matrix2d a;
    a << 0, b, -1 / b, 0;
    EXPECT_LE(worst_relative_error(matrix_exponential(a), std::cos(1.0) * i2 + std::sin(1.0) * a), 1e-12) << b;
  }
}

TEST(MatrixExponential, OverflowIsRefusedNamingA) {
  const Eigen::Matrix2d big = 1000 * Eigen::Matrix2d::Identity();
  const std::string message = configuration_error_of([&] { (void)matrix_exponential(big); });
  EXPECT_NE(message.find("'A'"), std::string::npos) << message;
  EXPECT_NE(message.find("range"), std::string::npos) << message;
  // e^700 ≈ 1.0e304 is still representable.
  const Eigen::Matrix2d near_limit = Eigen::Vector2d(700, -700).asDiagonal();
  EXPECT_LE(worst_relative_error(matrix_exponential(near_limit),
                                 Eigen::Vector2d(std::exp(700.0), std::exp(-700.0)).asDiagonal()),
            1e-12);
}

// Finite entries whose column sums overflow: ‖A‖₁ = ∞ once ran the choice of
// the Padé degree and the squarings on infinities (an int cast of ∞ and about
// 2³¹ squarings). Every eigenvalue is below −10³⁰⁷, so e^A is 0 to the last bit.
TEST(MatrixExponential, ANormBeyondTheFloatingPointRangeStillGivesTheExponential) {
  Eigen::Matrix2d triangular, full;
  triangular << -1e308, 1e308, 0, -1e308;
  full << -1.5e308, 1e308, 1e308, -1.5e308;  // eigenvalues −0.5e308 and −2.5e308
  EXPECT_MATRIX_NEAR(matrix_exponential(triangular), Eigen::Matrix2d::Zero(), 0.0, 0.0);
  EXPECT_MATRIX_NEAR(matrix_exponential(full), Eigen::Matrix2d::Zero(), 0.0, 0.0);
}

// Two nonnormal families A = S T S⁻¹ with S = [[1, 0], [1, 1]], of condition growing as b²:
// T = [[−1, b], [0, −2]] (real eigenvalues −1, −2; A's entries are integers, exact in double
// for b = 2^k up to 2^52) and T = [[−1, b], [−1/b, −1]] (eigenvalues −1 ± i, which no
// diagonal scaling makes normal once seen through S). e^A = S e^T S⁻¹, and the 2 × 2
// closed form e^M = e^τ (cosh δ I + sinh δ / δ (M − τI)), τ = tr M / 2,
// δ² = ((m₁₁ − m₂₂)/2)² + m₁₂ m₂₁, gives e^T without cancellation (δ² = 1/4, resp. −1;
// even in δ, so the branch of the root is immaterial).
Eigen::Matrix<std::complex<long double>, 2, 2> exponential_2x2(
    const Eigen::Matrix<std::complex<long double>, 2, 2>& m) {
  using C = std::complex<long double>;
  const C tau = (m(0, 0) + m(1, 1)) / 2.0L;
  const C delta = std::sqrt((m(0, 0) - m(1, 1)) * (m(0, 0) - m(1, 1)) / 4.0L + m(0, 1) * m(1, 0));
  const Eigen::Matrix<C, 2, 2> identity = Eigen::Matrix<C, 2, 2>::Identity();
  return std::exp(tau) * (std::cosh(delta) * identity + std::sinh(delta) / delta * (m - tau * identity));
}

struct NonnormalFamily {
  long double b;
  Eigen::Matrix<long double, 2, 2> s, s_inverse, t;
  NonnormalFamily(long double b_, bool complex_eigenvalues) : b(b_) {
    s << 1, 0, 1, 1;
    s_inverse << 1, 0, -1, 1;
    if (complex_eigenvalues) {
      t << -1, b, -1 / b, -1;
    } else {
      t << -1, b, 0, -2;
    }
  }
  [[nodiscard]] Eigen::Matrix<long double, 2, 2> a() const { return s * t * s_inverse; }
  [[nodiscard]] Eigen::Matrix<long double, 2, 2> exponential() const {
    const Eigen::Matrix<long double, 2, 2> e = exponential_2x2(t.cast<std::complex<long double>>()).real();
    return s * e * s_inverse;
  }
  // The Fréchet derivative L(A, E) = S L(T, S⁻¹ E S) S⁻¹ by the complex step
  // L(T, F) = Im e^{T + ihF} / h + O(h²), free of cancellation.
  [[nodiscard]] Eigen::Matrix<long double, 2, 2> frechet(const Eigen::Matrix<long double, 2, 2>& e) const {
    using C = std::complex<long double>;
    const long double h = 1e-200L;
    const Eigen::Matrix<long double, 2, 2> f = s_inverse * e * s;
    const Eigen::Matrix<C, 2, 2> m = t.cast<C>() + C(0, h) * f.cast<C>();
    return s * Eigen::Matrix<long double, 2, 2>(exponential_2x2(m).imag() / h) * s_inverse;
  }
  // κ_exp(A) = ‖K(A)‖₂ ‖A‖_F / ‖e^A‖_F, K(A) the 4 × 4 Kronecker form of L(A, ·)
  // (Higham, Functions of Matrices, eqs. (3.16) and (3.20)).
  [[nodiscard]] long double condition() const {
    Eigen::Matrix<long double, 4, 4> k;
    for (int j = 0; j < 4; ++j) {
      Eigen::Matrix<long double, 2, 2> e = Eigen::Matrix<long double, 2, 2>::Zero();
      e(j % 2, j / 2) = 1;
      const Eigen::Matrix<long double, 2, 2> l = frechet(e);
      k.col(j) = Eigen::Map<const Eigen::Matrix<long double, 4, 1>>(l.data());
    }
    const long double k2 = Eigen::JacobiSVD<Eigen::Matrix<long double, 4, 4>>(k).singularValues()(0);
    return k2 * a().norm() / exponential().norm();
  }
};

// e^A in Scalar of the family's A rounded to Scalar (exact in double; in float from
// b = 2^24 on, the entries −1 − b, 1 − b and b − 2 are not all representable).
template <typename Scalar>
Eigen::Matrix<Scalar, 2, 2> nonnormal_family_exponential(const NonnormalFamily& family) {
  const Eigen::Matrix<Scalar, 2, 2> a = family.a().template cast<Scalar>();
  return matrix_exponential(a);
}

// The normwise relative error of e^A in double and in float stays within
// 4 κ_exp(A)·u, u = ε/2 of the precision, wherever that bound says anything (below 1):
// the largest ratio error / (κ_exp u) measured is 0.31 in double and 0.41 in float
// (table in docs/design_routines.md). The squarings of r_m(2^{−s}A) lost up to
// 10⁴ κ_exp u. Where κ_exp u ≥ 1/4 no digit of e^A is determined by the rounded
// input; the exponential, finite with entries below 1e16, must still be returned
// and not as the zero matrix (the squarings returned 0 at b = 2^30, 2^36, 2^49 and
// 2^51, and refused at 2^29 and 2^31…2^52 in double and from 2^16 in float).
TEST(MatrixExponential, NonnormalFamilyIsAccurateToItsConditioning) {
  constexpr long double multiple = 4;
  const auto check = [&](const auto& e, long double u, const NonnormalFamily& family, const char* precision) {
    const long double bound = multiple * family.condition() * u;
    ASSERT_TRUE(e.allFinite()) << precision << ", b = " << double(family.b) << ", T = " << family.t;
    EXPECT_FALSE(e.isZero(0)) << precision << ", b = " << double(family.b) << ", T = " << family.t;
    const long double error =
        (e.template cast<long double>() - family.exponential()).norm() / family.exponential().norm();
    if (bound < 1) {
      EXPECT_LE(error, bound) << precision << ", b = " << double(family.b) << ", T = " << family.t;
    }
  };
  for (const bool complex_eigenvalues : {false, true})
    for (int k = 4; k <= 52; ++k) {
      const NonnormalFamily family(std::ldexp(1.0L, k), complex_eigenvalues);
      Eigen::Matrix2d e_double = Eigen::Matrix2d::Zero();
      Eigen::Matrix2f e_float = Eigen::Matrix2f::Zero();
      ASSERT_NO_THROW(e_double = nonnormal_family_exponential<double>(family)) << "b = 2^" << k << complex_eigenvalues;
      ASSERT_NO_THROW(e_float = nonnormal_family_exponential<float>(family))
          << "float, b = 2^" << k << complex_eigenvalues;
      check(e_double, std::numeric_limits<double>::epsilon() / 2.0L, family, "double");
      check(e_float, std::numeric_limits<float>::epsilon() / 2.0L, family, "float");
    }
}

TEST(ZeroOrderHold, StiffPoleBesideAnIntegrator) {
  for (double k : {1e4, 1e8, 1e16}) {
    // ẋ₁ = −k x₁ + u, ẋ₂ = u over one second: A_d = diag(e^{−k}, 1), B_d = ((1 − e^{−k})/k, 1).
    const Eigen::Matrix2d a = Eigen::Vector2d(-k, 0).asDiagonal();
    const auto zoh = discretize_zoh(a, Eigen::Vector2d(1, 1), 1.0);
    EXPECT_LE(worst_relative_error(zoh.Ad, Eigen::Vector2d(std::exp(-k), 1).asDiagonal()), 1e-12) << k;
    EXPECT_LE(worst_relative_error(zoh.Bd, Eigen::Vector2d(-std::expm1(-k) / k, 1)), 1e-12) << k;
  }
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

// One printed entry of Guyader & Zhang (2003) §4 and the number of significant digits printed.
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

// A_d and H as printed in §4; A(1,0) = 3.66e-8 included.
const Printed satellite_a_printed[] = {
    {0, 0, 1, 1},         {0, 1, 0.1, 1},      {0, 2, 0, 1}, {0, 3, 3.49e-6, 3},
    {1, 0, 3.66e-8, 3},   {1, 1, 1, 1},        {1, 2, 0, 1}, {1, 3, 6.98e-5, 3},
    {2, 0, -4.25e-14, 3}, {2, 1, -3.49e-6, 3}, {2, 2, 1, 1}, {2, 3, 0.1, 1},
    {3, 0, -1.28e-12, 3}, {3, 1, -6.98e-5, 3}, {3, 2, 0, 1}, {3, 3, 1, 1},
};
const Printed satellite_h_printed[] = {
    {0, 0, 0.1, 1},       {0, 1, 0.005, 1},    {0, 2, 0, 1},   {0, 3, 1.16e-7, 3},
    {1, 0, 1.83e-9, 3},   {1, 1, 0.1, 1},      {1, 2, 0, 1},   {1, 3, 3.49e-6, 3},
    {2, 0, -1.06e-15, 3}, {2, 1, -1.16e-7, 3}, {2, 2, 0.1, 1}, {2, 3, 0.005, 1},
    {3, 0, -4.25e-14, 3}, {3, 1, -3.49e-6, 3}, {3, 2, 0, 1},   {3, 3, 0.1, 1},
};

// Printed entries that the discretization with angular velocity w misses.
std::vector<std::string> satellite_misses(double w) {
  const auto zoh = discretize_zoh(satellite::continuous_dynamics<double>(w), Eigen::Matrix4d::Identity(),
                                  satellite::sampling_period);
  std::vector<std::string> misses;
  for (const Printed& p : satellite_a_printed)
    if (!(std::abs(zoh.Ad(p.row, p.col) - p.value) <= printed_tolerance(p)))
      misses.push_back("A(" + std::to_string(p.row) + "," + std::to_string(p.col) + ")");
  for (const Printed& p : satellite_h_printed)
    if (!(std::abs(zoh.Bd(p.row, p.col) - p.value) <= printed_tolerance(p)))
      misses.push_back("H(" + std::to_string(p.row) + "," + std::to_string(p.col) + ")");
  return misses;
}

// The paper prints ω = 3.49e-4 rounded: with exactly that value A(1,0) = 3ω²Ts is
// 3.654e-8, not the printed 3.66e-8. Every printed entry, this one included, is
// reproduced by any ω in about [3.4905, 3.4911]·10⁻⁴, 2π/18000 (a 5-hour orbit) for one.
TEST(ZeroOrderHold, SatelliteMatchesEveryPrintedEntryForTheUnroundedOmega) {
  for (double w : {3.4906e-4, 2 * std::numbers::pi / 18000, 3.4910e-4}) {
    const std::vector<std::string> misses = satellite_misses(w);
    EXPECT_TRUE(misses.empty()) << "w = " << w << " misses " << misses.front();
  }
  EXPECT_EQ(satellite_misses(3.49e-4), std::vector<std::string>{"A(1,0)"});
  EXPECT_FALSE(satellite_misses(3.4895e-4).empty());
  EXPECT_FALSE(satellite_misses(3.4920e-4).empty());
  // The model the examples use keeps the printed ω = 3.49e-4: A(1,0) = 3ω sin(ωTs).
  const auto zoh = satellite::discretized<double>();
  const double w = satellite::omega, ts = satellite::sampling_period;
  EXPECT_NEAR(zoh.Ad(1, 0), 3 * w * std::sin(w * ts), 1e-14 * zoh.Ad(1, 0));
}

TEST(ZeroOrderHold, FloatAgreesWithDouble) {
  const auto d = satellite::discretized<double>();
  const auto f = satellite::discretized<float>();
  EXPECT_MATRIX_NEAR(f.Ad.cast<double>(), d.Ad, 1e-6, 0.0);
  EXPECT_MATRIX_NEAR(f.Bd.cast<double>(), d.Bd, 1e-7, 0.0);
}

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
  // discretize_zoh names itself, not the exponential it calls.
  const std::string zoh_message = configuration_error_of([&] { (void)discretize_zoh(nan_a, b, 0.1); });
  EXPECT_NE(zoh_message.find("discretize_zoh: argument 'A'"), std::string::npos) << zoh_message;
  // A ts overflowing (e^{A ts} would be 0 here, but A ts is not representable),
  // and e^{A ts} overflowing: both refused under discretize_zoh's name, naming A and ts.
  const Eigen::Matrix<double, 1, 1> one(1.0);
  for (const auto& [a_value, period] : {std::pair{-1e300, 1e10}, std::pair{1000.0, 1.0}}) {
    const Eigen::Matrix<double, 1, 1> a_scalar(a_value);
    const double ts = period;
    const std::string message = configuration_error_of([&] { (void)discretize_zoh(a_scalar, one, ts); });
    EXPECT_EQ(message.rfind("discretize_zoh: argument 'A, ts'", 0), 0u) << message;
  }
}

}  // namespace
