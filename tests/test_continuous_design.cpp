// Design helpers of the continuous-time observers (Zhang 2005): polynomials and
// transfer functions, strict positive realness (exact test, frequency sweep,
// KYP certificate), the SPR gain design, the static transforms to the forms
// of Algorithms 1–3, CARE / Lyapunov / Riccati differential equation, and the
// Floquet test of periodic systems.

#include <adaptobs/core/symmetric_eigenvalues.hpp>
#include <adaptobs/design/canonical_forms.hpp>
#include <adaptobs/design/care.hpp>
#include <adaptobs/design/ltv_stability.hpp>
#include <adaptobs/design/lyapunov.hpp>
#include <adaptobs/design/polynomial.hpp>
#include <adaptobs/design/positive_real.hpp>
#include <adaptobs/design/riccati_differential.hpp>

#include "models/periodic_mimo.hpp"
#include "models/siso_third_order.hpp"
#include "support/eigen_testing.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <string>
#include <vector>

namespace {

using adaptobs::Polynomial;
using adaptobs::testing::RandomMatrices;
using Matrix = Eigen::MatrixXd;
using Vector = Eigen::VectorXd;
namespace siso = adaptobs::examples::siso;
namespace periodic = adaptobs::examples::periodic;

Vector poly(std::initializer_list<double> c) {
  Vector p(static_cast<Eigen::Index>(c.size()));
  Eigen::Index i = 0;
  for (double v : c) p(i++) = v;
  return p;
}

using adaptobs::testing::configuration_error_of;

// A realization of N/D (D monic of degree n, N of n coefficients) through a
// random similarity of the observer canonical form.
struct Realization {
  Matrix A;
  Vector b;
  Eigen::RowVectorXd c;
};

Realization realize(const Vector& num, const Vector& den, RandomMatrices& rng) {
  const Eigen::Index n = den.size() - 1;
  Matrix a = Matrix::Zero(n, n);
  a.col(0) = -den.tail(n);
  a.diagonal(1).setOnes();
  Eigen::RowVectorXd c = Eigen::RowVectorXd::Zero(n);
  c(0) = 1;
  Matrix m = rng.uniform<Matrix>(n, n) + 2.0 * Matrix::Identity(n, n);
  const Matrix m_inv = m.inverse();
  return {m * a * m_inv, m * num, c * m_inv};
}

TEST(Polynomials, CharacteristicPolynomialAndTransferFunction) {
  const Vector p = adaptobs::characteristic_polynomial(siso::dynamics<double>());
  EXPECT_MATRIX_NEAR(p, poly({1, 4, 7, 5}), 1e-13, 0);
  const auto g = adaptobs::transfer_function(siso::dynamics<double>(), siso::input_matrix<double>(),
                                             siso::output_matrix<double>());
  EXPECT_MATRIX_NEAR(g.denominator, poly({1, 4, 7, 5}), 1e-13, 0);
  // C adj(sI − A) B: C B = 0.5, then by hand (s + 1)(s + 2)/2 + ... checked against a direct evaluation.
  const std::complex<double> s(0.3, 1.7);
  const Eigen::Matrix3cd m = s * Eigen::Matrix3cd::Identity() - siso::dynamics<double>().cast<std::complex<double>>();
  const std::complex<double> direct =
      (siso::output_matrix<double>().cast<std::complex<double>>() *
       m.partialPivLu().solve(siso::input_matrix<double>().cast<std::complex<double>>()))(0, 0);
  std::complex<double> num = 0, den = 0;
  for (Eigen::Index i = 0; i < g.numerator.size(); ++i) num = num * s + g.numerator(i);
  for (Eigen::Index i = 0; i < g.denominator.size(); ++i) den = den * s + g.denominator(i);
  EXPECT_NEAR(std::abs(num / den - direct), 0.0, 1e-13);
}

// Routh–Hurwitz against polynomials with known roots, including roots on the
// imaginary axis and a pair just to the right of it.
TEST(Polynomials, RouthHurwitzAndSturmCounts) {
  using adaptobs::is_hurwitz_polynomial;
  EXPECT_TRUE(is_hurwitz_polynomial<double>(poly({1, 6, 11, 6})));        // -1, -2, -3
  EXPECT_TRUE(is_hurwitz_polynomial<double>(poly({-2, -12, -22, -12})));  // same roots, negative lead
  EXPECT_TRUE(is_hurwitz_polynomial<double>(poly({1, 0.2, 100.01})));     // -0.1 ± 10j
  EXPECT_FALSE(is_hurwitz_polynomial<double>(poly({1, -0.2, 100.01})));   // +0.1 ± 10j
  EXPECT_FALSE(is_hurwitz_polynomial<double>(poly({1, 1, 4, 4})));        // -1, ±2j
  EXPECT_FALSE(is_hurwitz_polynomial<double>(poly({1, 3, 2, 0})));        // 0, -1, -2
  EXPECT_FALSE(is_hurwitz_polynomial<double>(poly({1, 1, 1, 21})));       // -3, 1 ± 2.45j (all coefficients positive)
  EXPECT_FALSE(is_hurwitz_polynomial<double>(poly({0, 1, 1})));           // leading zero
  // (s+1)^2 (s^2 + 0.02 s + 1.0001) (s+4): a lightly damped pair, fifth order.
  const Vector lightly = adaptobs::multiply_polynomials<double>(
      adaptobs::multiply_polynomials<double>(poly({1, 2, 1}), poly({1, 0.02, 1.0001})), poly({1, 4}));
  EXPECT_TRUE(is_hurwitz_polynomial<double>(lightly));
  // Scale invariance: the roots scaled by 1e-10 or 1e15 are judged as the
  // unscaled ones (an absolute tolerance refused the first pair and the last).
  EXPECT_TRUE(is_hurwitz_polynomial<double>(poly({1, 2e-10, 1e-20})));              // -1e-10 (double)
  EXPECT_TRUE(is_hurwitz_polynomial<double>(poly({1, 1e10, 1e30})));                // Re = -5e9, |s| = 1e15
  EXPECT_TRUE(is_hurwitz_polynomial<double>(poly({1, 1e-20})));                     // -1e-20
  EXPECT_FALSE(is_hurwitz_polynomial<double>(poly({1, -2e-10, 1e-20})));            // +1e-10 (double)
  EXPECT_FALSE(is_hurwitz_polynomial<double>(poly({1e-30, 1e-30, 4e-30, 4e-30})));  // -1, ±2j, scaled
  EXPECT_TRUE(adaptobs::has_hurwitz_characteristic_polynomial(siso::dynamics<double>()));
  EXPECT_FALSE(adaptobs::has_hurwitz_characteristic_polynomial(Eigen::Matrix2d(Eigen::Matrix2d::Identity())));

  using adaptobs::count_real_roots_above;
  EXPECT_EQ(count_real_roots_above<double>(poly({1, -6, 11, -6}), 0.0), 3);  // 1, 2, 3
  EXPECT_EQ(count_real_roots_above<double>(poly({1, -6, 11, -6}), 1.5), 2);
  EXPECT_EQ(count_real_roots_above<double>(poly({1, 6, 11, 6}), 0.0), 0);  // -1, -2, -3
  EXPECT_EQ(count_real_roots_above<double>(poly({1, 0, 1}), 0.0), 0);      // ±j
  EXPECT_EQ(count_real_roots_above<double>(poly({1, -2, 1}), 0.0), 1);     // double root 1
  EXPECT_EQ(count_real_roots_above<double>(poly({1, 1, -2}), 0.0), 1);     // 1, -2
  // Scale invariance: ±1e-6 were taken for a double root (the remainder 1e-12
  // was trimmed against the leading 1), and so were roots scaled by 1e100.
  EXPECT_EQ(count_real_roots_above<double>(poly({1, 0, -1e-12}), -1.0), 2);
  EXPECT_EQ(count_real_roots_above<double>(poly({1, 0, -1e-12}), 0.0), 1);
  EXPECT_EQ(count_real_roots_above<double>(poly({1, -6e100, 11e200, -6e300}), 1.5e100), 2);
}

struct SprCase {
  const char* name;
  Vector num, den;
  bool spr;
};

std::vector<SprCase> spr_cases() {
  return {
      {"G1 (s+1)/((s+2)(s+3))", poly({1, 1}), poly({1, 5, 6}), true},
      {"G2 (s+5)/((s+2)(s+3)), Re G > 0 but w^2 Re G -> 0", poly({1, 5}), poly({1, 5, 6}), false},
      {"G3 (s+6)/((s+2)(s+3)), not PR", poly({1, 6}), poly({1, 5, 6}), false},
      {"G4 (s-1)/((s+2)(s+3)), non-minimum phase", poly({1, -1}), poly({1, 5, 6}), false},
      {"G5 1/((s+1)(s+2)), relative degree 2", poly({0, 1}), poly({1, 3, 2}), false},
      {"G6 (s^2+2s+2)/((s+1)(s+2)(s+3))", poly({1, 2, 2}), poly({1, 6, 11, 6}), true},
      {"G7 (s^2+s+4)/(s+1)^3", poly({1, 1, 4}), poly({1, 3, 3, 1}), false},
      {"G8 (s+1)(s+3)/((s+1)(s+2)(s+3)), non-minimal", poly({1, 4, 3}), poly({1, 6, 11, 6}), true},
  };
}

// The polynomial helpers took matrices of any shape: a C of the wrong width or
// a non-square m read outside them, and a NaN came back as coefficients.
TEST(Polynomials, HelpersRefuseDataOfTheWrongShapeOrNotFiniteByName) {
  const Eigen::Matrix3d a = siso::dynamics<double>();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_CONFIGURATION_ERROR_NAMES(adaptobs::observability_matrix(a, Eigen::RowVector2d(1, 0)), "C");
  EXPECT_CONFIGURATION_ERROR_NAMES(adaptobs::evaluate_polynomial(poly({1, 2}), Eigen::MatrixXd::Ones(2, 3)), "m");
  EXPECT_CONFIGURATION_ERROR_NAMES(adaptobs::evaluate_polynomial(poly({1, nan}), a), "p");
  Eigen::Matrix3d a_nan = a;
  a_nan(1, 2) = nan;
  EXPECT_CONFIGURATION_ERROR_NAMES(adaptobs::characteristic_polynomial(a_nan), "A");
  EXPECT_CONFIGURATION_ERROR_NAMES(adaptobs::count_real_roots_above(poly({1, nan, 1}), -1.0), "p");
  EXPECT_CONFIGURATION_ERROR_NAMES(adaptobs::count_real_roots_above(poly({1, 0, -1}), nan), "a");
  EXPECT_CONFIGURATION_ERROR_NAMES(adaptobs::strictly_positive_real<double>(poly({1, 1}), poly({1, nan, 6})),
                                   "denominator");
  // Finite coefficients whose product N(s)D(-s) overflows: refused, not judged.
  EXPECT_CONFIGURATION_ERROR_NAMES(
      adaptobs::strictly_positive_real<double>(poly({1e200, 1e200}), poly({1, 1e200, 1e200})), "numerator");
  EXPECT_CONFIGURATION_ERROR_NAMES((void)adaptobs::has_hurwitz_characteristic_polynomial(a_nan), "m");
  EXPECT_TRUE(adaptobs::has_hurwitz_characteristic_polynomial(Eigen::MatrixXd(0, 3)));  // empty: no eigenvalue
  EXPECT_EQ(adaptobs::observability_matrix(a, Eigen::RowVector3d(1, 0, 0)).rows(), 3);
}

TEST(PositiveReal, ExactTestSweepAndKypAgreeOnReferenceFunctions) {
  RandomMatrices rng(1);
  for (const SprCase& k : spr_cases()) {
    SCOPED_TRACE(k.name);
    const auto exact = adaptobs::strictly_positive_real<double>(k.num, k.den);
    EXPECT_EQ(exact.strictly_positive_real, k.spr);
    const Realization r = realize(k.num, k.den, rng);
    EXPECT_EQ(adaptobs::strictly_positive_real(r.A, r.b, r.c).strictly_positive_real, k.spr);
    EXPECT_EQ(adaptobs::spr_frequency_sweep(r.A, r.b, r.c).strictly_positive_real, k.spr);
    const auto kyp = adaptobs::kyp_certificate(r.A, r.b, r.c);
    EXPECT_EQ(kyp.has_value(), k.spr);
    if (kyp) {
      // The certificate is verified by its residuals, recomputed here.
      const auto check = adaptobs::kyp_residuals(kyp->P, r.A, r.b, r.c);
      EXPECT_LE(check.equality_residual, 1e-10);
      EXPECT_GT(check.min_eigenvalue_P, 0.0);
      EXPECT_LT(check.max_eigenvalue_lyapunov, 0.0);
      EXPECT_LE((kyp->P - kyp->P.transpose()).norm(), 1e-12 * kyp->P.norm());
    }
  }
  // The figures behind two verdicts: q(w) = 4w + 6 for G1; q = 30 (degree 0 < n − 1) for G2.
  EXPECT_MATRIX_NEAR(adaptobs::strictly_positive_real<double>(poly({1, 1}), poly({1, 5, 6})).q, poly({4, 6}), 1e-12, 0);
  const auto g2 = adaptobs::strictly_positive_real<double>(poly({1, 5}), poly({1, 5, 6}));
  EXPECT_MATRIX_NEAR(g2.q, poly({30}), 1e-12, 0);
  EXPECT_TRUE(g2.q_positive_on_nonnegative_axis);
  EXPECT_FALSE(g2.strict_at_infinity);
}

// The residuals of a P with known spectrum {0.5, 2, 7} (rotated by a random
// orthogonal Q) and A = −I: AᵀP + PA = −2P has largest eigenvalue −1, and
// c = (Pb)ᵀ + 10⁻³e₂ misses the equality Pb = cᵀ by exactly 10⁻³.
TEST(PositiveReal, KypResidualsOfAKnownCertificate) {
  RandomMatrices rng(11);
  const Matrix q = adaptobs::testing::random_orthogonal(rng, 3);
  const Matrix p = q * Eigen::Vector3d(7, 0.5, 2).asDiagonal() * q.transpose();
  const Vector b = Eigen::Vector3d(1, -2, 0.5);
  Eigen::RowVectorXd c = (p * b).transpose();
  c(1) += 1e-3;
  const auto k = adaptobs::kyp_residuals(p, Matrix(-Matrix::Identity(3, 3)), b, c);
  EXPECT_NEAR(k.min_eigenvalue_P, 0.5, 1e-13);
  EXPECT_NEAR(k.max_eigenvalue_lyapunov, -1.0, 1e-13);
  EXPECT_NEAR(k.equality_residual, 1e-3, 1e-13);
  // A NaN in P shows in every figure (the largest-entry scan once skipped it: 0).
  Matrix p_nan = p;
  p_nan(1, 1) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_TRUE(std::isnan(adaptobs::kyp_residuals(p_nan, Matrix(-Matrix::Identity(3, 3)), b, c).equality_residual));
}

// Transform of Algorithm 1 with ν = (s + 1)(s + 3) and ker C spanned by
// (e2, e1 − e3): exact rationals.
TEST(CanonicalForms, BastinGeversFormOfTheThirdOrderPlant) {
  using D = siso::Dims<double>;
  Matrix w(3, 2);
  w << 0, 1, 1, 0, 0, -1;
  const auto st =
      adaptobs::bastin_gevers_form<D>(siso::dynamics<double>(), siso::output_matrix<double>(), poly({1, 4, 3}), w);
  Eigen::Matrix3d t_expected;
  t_expected << 1, 0, 1, -4.0 / 25, 1, -4.0 / 25, -3.0 / 25, 0, -28.0 / 25;
  EXPECT_MATRIX_NEAR(st.T(), t_expected, 1e-12, 0);
  EXPECT_MATRIX_NEAR(st.K(), Eigen::Vector3d(0, -7.0 / 5, -4.0 / 5), 1e-12, 0);
  const auto so = st.apply(siso::model<double>().system());
  Eigen::Matrix3d ao_expected;
  ao_expected << 0, 2, 1.5, 0, -33.0 / 25, -56.0 / 25, 0, -6.0 / 25, -67.0 / 25;
  EXPECT_MATRIX_NEAR(so.Ao, ao_expected, 1e-12, 0);
  EXPECT_MATRIX_NEAR(so.Co, Eigen::RowVector3d(1, 0, 0), 1e-12, 0);

  // Default (orthonormal) kernel basis: another T, the same structure and zeros.
  const auto st2 =
      adaptobs::bastin_gevers_form<D>(siso::dynamics<double>(), siso::output_matrix<double>(), poly({1, 4, 3}));
  const auto so2 = st2.apply(siso::model<double>().system());
  EXPECT_MATRIX_NEAR(so2.Co, Eigen::RowVector3d(1, 0, 0), 1e-12, 0);
  EXPECT_MATRIX_NEAR(so2.Ao.col(0), Eigen::Vector3d::Zero(), 1e-12, 0);
  EXPECT_MATRIX_NEAR(adaptobs::characteristic_polynomial(Eigen::Matrix2d(so2.Ao.bottomRightCorner(2, 2))),
                     poly({1, 4, 3}), 1e-10, 0);

  // c in other units has the same kernel: 1e12 c was refused as 'kernel', and
  // with 1e-12 c a W outside the kernel was accepted (an absolute test).
  const Eigen::Matrix3d a3 = siso::dynamics<double>();
  for (const double s : {1e-12, 1e12}) {
    const Eigen::RowVector3d cs = s * siso::output_matrix<double>();
    const auto st3 = adaptobs::bastin_gevers_form<D>(a3, cs, poly({1, 4, 3}));
    const Eigen::Matrix3d t_inv = st3.T_inverse();
    const Eigen::RowVector3d co = cs * t_inv;
    const Eigen::Matrix3d ao = st3.T() * a3 * t_inv - st3.K() * co;
    EXPECT_MATRIX_NEAR(co, Eigen::RowVector3d(1, 0, 0), 1e-12, 0) << s;
    EXPECT_MATRIX_NEAR(adaptobs::characteristic_polynomial(Eigen::Matrix2d(ao.bottomRightCorner(2, 2))),
                       poly({1, 4, 3}), 1e-9, 0)
        << s;
  }
  Matrix not_kernel = Matrix::Zero(3, 2);
  not_kernel(0, 0) = 1;
  not_kernel(1, 1) = 1;
  EXPECT_CONFIGURATION_ERROR_NAMES(
      (void)adaptobs::bastin_gevers_form<D>(a3, Eigen::RowVector3d(1e-12 * siso::output_matrix<double>()),
                                            poly({1, 4, 3}), not_kernel),
      "kernel");

  EXPECT_NE(configuration_error_of([&] {
              (void)adaptobs::bastin_gevers_form<D>(siso::dynamics<double>(), siso::output_matrix<double>(),
                                                    poly({1, -1, 3}));
            }).find("'zeros'"),
            std::string::npos);
  // A valid fourth-order pair for three-state dimensions: refused, naming A.
  Eigen::Matrix4d shift = Eigen::Matrix4d::Zero();
  shift.diagonal(1).setOnes();
  EXPECT_NE(configuration_error_of([&] {
              (void)adaptobs::bastin_gevers_form<D>(shift, Eigen::RowVector4d(1, 0, 0, 0), poly({1, 6, 11, 6}));
            }).find("'A'"),
            std::string::npos);
  EXPECT_NE(configuration_error_of([&] {
              (void)adaptobs::marino_tomei_form<D>(shift, Eigen::RowVector4d(1, 0, 0, 0));
            }).find("'A'"),
            std::string::npos);
}

// Non-finite data gets the reason "not finite" under its own name, not a
// verdict on observability or on the polynomial, and never a NaN gain.
// Past n ≈ 15 the observability matrix of a random pair has a condition number
// beyond 1/(n eps): the form was refused as StaticTransform's argument 'T',
// which the caller never gave.
TEST(CanonicalForms, APairTooIllConditionedForTheFormIsRefusedAsThePair) {
  using D = adaptobs::Dimensions<double, Eigen::Dynamic, 1, 1, 1>;
  std::mt19937_64 rng(5);
  std::normal_distribution<double> normal;
  const Eigen::Index n = 20;
  Eigen::MatrixXd a(n, n), c(1, n);
  for (Eigen::Index j = 0; j < n; ++j) {
    for (Eigen::Index i = 0; i < n; ++i) a(i, j) = normal(rng);
    c(0, j) = normal(rng);
  }
  EXPECT_CONFIGURATION_ERROR_NAMES((void)adaptobs::marino_tomei_form<D>(a, c), "A, c");
}

// A chain x_{i+1}' = -r_{i+1} x_{i+1} + x_i with rates r_i = factor^i, seen at its last state.
Matrix graded_chain(Eigen::Index n, double factor) {
  Matrix a = Matrix::Zero(n, n);
  for (Eigen::Index i = 0; i < n; ++i) a(i, i) = -std::pow(factor, double(i));
  for (Eigen::Index i = 0; i + 1 < n; ++i) a(i + 1, i) = 1;
  return a;
}

// Graded dynamics are observable: the rank test on [c; cA; ...], whose rows
// grow like the powers of A, refused them as "not an observable pair". The
// form is found where it can be computed (Besancon, rates 1 ... 1e12), and
// refused as too ill-conditioned where it cannot.
TEST(CanonicalForms, GradedObservablePairsAreNotRefusedAsUnobservable) {
  using D = adaptobs::Dimensions<double, Eigen::Dynamic, 1, 1, 1>;
  using D2 = adaptobs::Dimensions<double, Eigen::Dynamic, 1, 2, 1>;
  const Matrix a = graded_chain(5, 1e3);
  Matrix c = Matrix::Zero(2, 5);
  c(0, 4) = 1;  // the last state and the first
  c(1, 0) = 1;
  const auto st = adaptobs::besancon_form<D2>(a, c, 0.5);
  const Matrix t_inv = st.T_inverse();
  const Matrix co = c * t_inv, ao = st.T() * a * t_inv - st.K() * co;
  Matrix leading_identity = Matrix::Zero(2, 5);
  leading_identity.leftCols(2).setIdentity();
  EXPECT_MATRIX_NEAR(co, leading_identity, 1e-9, 0);
  EXPECT_LE(ao.leftCols(2).cwiseAbs().maxCoeff(), 1e-9 * a.norm());
  EXPECT_LT(adaptobs::spectral_abscissa(Matrix(ao.bottomRightCorner(3, 3))), -0.5);

  const auto refused_as_ill_conditioned = [](const std::string& message) {
    EXPECT_NE(message.find("'A, c' is too ill-conditioned"), std::string::npos) << message;
    EXPECT_EQ(message.find("observable"), std::string::npos) << message;
  };
  Matrix last = Matrix::Zero(1, 5);
  last(0, 4) = 1;
  refused_as_ill_conditioned(configuration_error_of(
      [&] { (void)adaptobs::marino_tomei_form<D>(graded_chain(3, 1e3), Matrix(last.rightCols(3))); }));
  refused_as_ill_conditioned(configuration_error_of(
      [&] { (void)adaptobs::bastin_gevers_form<D>(graded_chain(5, 1e2), last, poly({1, 4, 6, 4, 1})); }));
  refused_as_ill_conditioned(configuration_error_of([&] {
    (void)adaptobs::ackermann_observer_gain(graded_chain(4, 1e2), Matrix(last.rightCols(4)), poly({1, 10, 35, 50, 24}));
  }));

  // Unobservable pairs stay refused as such, whatever the units of c.
  Matrix cut = graded_chain(4, 10);
  cut(2, 1) = 0;  // the first two states never reach the output
  const Matrix tiny = 1e-12 * last.rightCols(4);
  const auto refused_as_unobservable = [](const std::string& message, const std::string& pair) {
    EXPECT_NE(message.find("'" + pair + "' must be an observable pair"), std::string::npos) << message;
  };
  refused_as_unobservable(configuration_error_of([&] { (void)adaptobs::marino_tomei_form<D>(cut, tiny); }), "A, c");
  refused_as_unobservable(
      configuration_error_of([&] { (void)adaptobs::bastin_gevers_form<D>(cut, tiny, poly({1, 3, 3, 1})); }), "A, c");
  refused_as_unobservable(
      configuration_error_of([&] { (void)adaptobs::ackermann_observer_gain(cut, tiny, poly({1, 10, 35, 50, 24})); }),
      "A, c");
  Matrix c2 = Matrix::Zero(2, 4);
  c2(0, 3) = 1e-12;
  c2(1, 2) = 1e-12;
  refused_as_unobservable(configuration_error_of([&] { (void)adaptobs::besancon_form<D2>(cut, c2, 0.5); }), "A, C");
}

TEST(CanonicalForms, NonFiniteDataOfTheSisoDesignsIsRefusedByName) {
  using D = siso::Dims<double>;
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  const Eigen::Matrix3d a = siso::dynamics<double>();
  const Eigen::RowVector3d c = siso::output_matrix<double>();
  Eigen::Matrix3d a_nan = a;
  a_nan(1, 2) = nan;
  const Eigen::RowVector3d c_inf(1, inf, 0);
  const auto refused_as_not_finite = [](const std::string& message, const std::string& argument) {
    EXPECT_NE(message.find("'" + argument + "'"), std::string::npos) << message;
    EXPECT_NE(message.find("finite"), std::string::npos) << message;
  };
  refused_as_not_finite(
      configuration_error_of([&] { (void)adaptobs::bastin_gevers_form<D>(a_nan, c, poly({1, 4, 3})); }), "A");
  refused_as_not_finite(
      configuration_error_of([&] { (void)adaptobs::bastin_gevers_form<D>(a, c_inf, poly({1, 4, 3})); }), "c");
  refused_as_not_finite(configuration_error_of([&] { (void)adaptobs::bastin_gevers_form<D>(a, c, poly({1, nan, 3})); }),
                        "zeros");
  refused_as_not_finite(configuration_error_of([&] { (void)adaptobs::marino_tomei_form<D>(a_nan, c); }), "A");
  refused_as_not_finite(configuration_error_of([&] { (void)adaptobs::marino_tomei_form<D>(a, c_inf); }), "c");
  const Eigen::Vector3d gamma(1, 3, 2);
  refused_as_not_finite(configuration_error_of([&] { (void)adaptobs::spr_injection_gain(a_nan, c, gamma, 2.0); }), "A");
  refused_as_not_finite(
      configuration_error_of([&] { (void)adaptobs::spr_injection_gain(a, c, Eigen::Vector3d(1, nan, 2), 2.0); }),
      "gamma");
  refused_as_not_finite(
      configuration_error_of([&] { (void)adaptobs::ackermann_observer_gain(a, c_inf, poly({1, 6, 11, 6})); }), "c");
  refused_as_not_finite(
      configuration_error_of([&] { (void)adaptobs::ackermann_observer_gain(a, c, poly({1, 6, nan, 6})); }), "p");
  refused_as_not_finite(
      configuration_error_of([&] { (void)adaptobs::transfer_function(a, Eigen::Vector3d(0, nan, 1), c); }), "b");
}

TEST(CanonicalForms, MarinoTomeiFormOfTheThirdOrderPlant) {
  using D = siso::Dims<double>;
  const auto st = adaptobs::marino_tomei_form<D>(siso::dynamics<double>(), siso::output_matrix<double>());
  Eigen::Matrix3d t_expected;
  t_expected << 1, 0, 1, 3.5, 2, 2, 2.5, 5, 5;
  EXPECT_MATRIX_NEAR(st.T(), t_expected, 1e-12, 0);
  EXPECT_MATRIX_NEAR(st.K(), Eigen::Vector3d(-4, -7, -5), 1e-12, 0);
  const auto so = st.apply(siso::model<double>().system());
  Eigen::Matrix3d shift = Eigen::Matrix3d::Zero();
  shift.diagonal(1).setOnes();
  EXPECT_MATRIX_NEAR(so.Ao, shift, 1e-12, 0);
  EXPECT_MATRIX_NEAR(so.Co, Eigen::RowVector3d(1, 0, 0), 1e-12, 0);
}

TEST(CanonicalForms, BesanconFormOfRandomMimoSystems) {
  RandomMatrices rng(7);
  using D = adaptobs::Dimensions<double, 4, 1, 2, 1>;
  for (int trial = 0; trial < 10; ++trial) {
    const Eigen::Matrix4d a = rng.uniform<Eigen::Matrix4d>();
    const Eigen::Matrix<double, 2, 4> c = rng.uniform<Eigen::Matrix<double, 2, 4>>();
    const auto st = adaptobs::besancon_form<D>(a, c, 0.5);
    const Eigen::Matrix4d ao = st.T() * a * st.T_inverse() - st.K() * c * st.T_inverse();
    Eigen::Matrix<double, 2, 4> leading_identity = Eigen::Matrix<double, 2, 4>::Zero();
    leading_identity.leftCols(2).setIdentity();
    using Output24 = Eigen::Matrix<double, 2, 4>;
    using Block42 = Eigen::Matrix<double, 4, 2>;
    const Output24 co = c * st.T_inverse();
    EXPECT_MATRIX_NEAR(co, leading_identity, 1e-10, 0);
    EXPECT_MATRIX_NEAR(ao.leftCols(2), Block42::Zero(), 1e-10, 0);
    EXPECT_LT(adaptobs::spectral_abscissa(Matrix(ao.bottomRightCorner(2, 2))), -0.5);
  }
  // One output for two-output dimensions: refused, naming C.
  const Eigen::Matrix4d a = rng.uniform<Eigen::Matrix4d>();
  EXPECT_NE(configuration_error_of([&] {
              (void)adaptobs::besancon_form<D>(a, Eigen::RowVector4d(1, 0, 0, 0), 0.5);
            }).find("'C'"),
            std::string::npos);
  // A C without full row rank, or not finite, is refused naming C (with
  // assertions on, a refusal inside the transform's comma initializer aborted).
  Eigen::Matrix<double, 2, 4> dependent_rows;
  dependent_rows << 1, 0, 0, 0, 2, 0, 0, 0;
  EXPECT_CONFIGURATION_ERROR_NAMES(adaptobs::besancon_form<D>(a, dependent_rows, 0.5), "C");
  Eigen::Matrix<double, 2, 4> not_finite = Eigen::Matrix<double, 2, 4>::Identity();
  not_finite(1, 2) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_CONFIGURATION_ERROR_NAMES(adaptobs::besancon_form<D>(a, not_finite, 0.5), "C");
  Eigen::Matrix4d a_not_finite = a;
  a_not_finite(3, 0) = std::numeric_limits<double>::infinity();
  EXPECT_CONFIGURATION_ERROR_NAMES(
      adaptobs::besancon_form<D>(a_not_finite, Eigen::Matrix<double, 2, 4>::Identity(), 0.5), "A");
}

// A decay the pair's scale cannot carry is refused naming decay, with its true
// reason, not as a defect of (A, C): first T = [I 0; -X I] T0 turns
// ill-conditioned (cond T ~ ||X||^2), then the shifted Riccati equation fails.
TEST(CanonicalForms, BesanconFormRefusesAnExcessiveDecayNamingIt) {
  using D = adaptobs::Dimensions<double, 3, 1, 1, 1>;
  Eigen::Matrix3d a;
  a << 0, 1, 0, 0, 0, 1, -1, -2, -3;
  const Eigen::RowVector3d c(1, 0, 0);
  const auto st = adaptobs::besancon_form<D>(a, c, 1e3);
  const Eigen::Matrix3d ao = st.T() * a * st.T_inverse() - st.K() * c * st.T_inverse();
  EXPECT_LT(adaptobs::spectral_abscissa(Matrix(ao.bottomRightCorner(2, 2))), -1e3);
  const auto refusal = [&](double decay) {
    return configuration_error_of([&] { (void)adaptobs::besancon_form<D>(a, c, decay); });
  };
  for (const double decay : {1e4, 1e8}) {
    const std::string message = refusal(decay);
    EXPECT_TRUE(adaptobs::testing::quotes_argument(message, "decay")) << message;
    EXPECT_EQ(message.find("detectable"), std::string::npos) << message;
  }
  EXPECT_NE(refusal(1e4).find("condition number"), std::string::npos);
  EXPECT_NE(refusal(1e8).find("Riccati"), std::string::npos);
}

// A pair whose scale puts the powers of A beyond the floating-point range is
// refused naming A and the overflow. Marino–Tomei and Bastin–Gevers blamed an
// argument 'A' of observability_matrix "not finite", Besançon an undetectable
// pair (decay 0) or its default decay 1.
TEST(CanonicalForms, APairBeyondTheFloatingPointRangeIsRefusedNamingA) {
  using D = adaptobs::Dimensions<double, 4, 1, 1, 1>;
  const auto scaled = [](double s) {
    Eigen::Matrix4d a = Eigen::Matrix4d::Zero();
    a.topRightCorner(3, 3).setIdentity();
    a(3, 0) = -1;
    return Eigen::Matrix4d(s * a);  // characteristic polynomial λ⁴ + s⁴
  };
  const Eigen::RowVector4d c(1, 0, 0, 0);
  const auto expect_scale_refusal = [](const std::string& message, const char* reason) {
    EXPECT_TRUE(adaptobs::testing::quotes_argument(message, "A")) << message;
    EXPECT_NE(message.find(reason), std::string::npos) << message;
    EXPECT_NE(message.find("rescale"), std::string::npos) << message;
  };
  for (const double s : {1e80, 1e200}) {
    expect_scale_refusal(configuration_error_of([&] { (void)adaptobs::marino_tomei_form<D>(scaled(s), c); }),
                         "overflows");
    expect_scale_refusal(
        configuration_error_of([&] { (void)adaptobs::bastin_gevers_form<D>(scaled(s), c, poly({1, 3, 3, 1})); }),
        "overflows");
  }
  // Besançon's Riccati equation is solved up to about 1e150 (the form is
  // found at 1e100, with or without a decay) and refused beyond, with the
  // decay asked for or without.
  for (const double decay : {0.0, 1.0}) {
    EXPECT_NO_THROW((void)adaptobs::besancon_form<D>(scaled(1e100), c, decay));
    expect_scale_refusal(configuration_error_of([&] { (void)adaptobs::besancon_form<D>(scaled(1e160), c, decay); }),
                         "Riccati");
  }
}

TEST(SprDesign, GainsOfAlgorithmsOneAndTwo) {
  using D = siso::Dims<double>;
  const Eigen::Vector3d e1(1, 0, 0);
  // Algorithm 1 in the form (5) of the plant: k = λ e1, G = 1/(s + λ).
  const auto so1 =
      adaptobs::bastin_gevers_form<D>(siso::dynamics<double>(), siso::output_matrix<double>(), poly({1, 4, 3}))
          .apply(siso::model<double>().system());
  const Eigen::Vector3d k1 = adaptobs::spr_injection_gain(so1.Ao, so1.Co, e1, 2.0);
  EXPECT_MATRIX_NEAR(k1, Eigen::Vector3d(2, 0, 0), 1e-12, 0);
  const auto g1 = adaptobs::transfer_function(Eigen::Matrix3d(so1.Ao - k1 * so1.Co), e1, so1.Co);
  EXPECT_MATRIX_NEAR(g1.numerator, poly({1, 4, 3}), 1e-12, 0);
  EXPECT_MATRIX_NEAR(g1.denominator, poly({1, 6, 11, 6}), 1e-12, 0);
  EXPECT_TRUE(adaptobs::strictly_positive_real(Eigen::Matrix3d(so1.Ao - k1 * so1.Co), e1, so1.Co));
  for (const Eigen::Vector3d& bad : {Eigen::Vector3d(-0.5, 0, 0), Eigen::Vector3d(2, -4, 4)})
    EXPECT_FALSE(adaptobs::strictly_positive_real(Eigen::Matrix3d(so1.Ao - bad * so1.Co), e1, so1.Co))
        << bad.transpose();

  // Algorithm 2 with γ = (1, 3, 2).
  const auto so2 = adaptobs::marino_tomei_form<D>(siso::dynamics<double>(), siso::output_matrix<double>())
                       .apply(siso::model<double>().system());
  const Eigen::Vector3d gamma(1, 3, 2);
  EXPECT_MATRIX_NEAR(adaptobs::spr_injection_gain(so2.Ao, so2.Co, gamma, 2.0), Eigen::Vector3d(5, 8, 4), 1e-12, 0);
  EXPECT_MATRIX_NEAR(adaptobs::spr_injection_gain(so2.Ao, so2.Co, gamma, 5.0), Eigen::Vector3d(8, 17, 10), 1e-12, 0);

  // No gain exists: c γ ≤ 0, or a non-Hurwitz N_γ.
  EXPECT_NE(configuration_error_of([&] {
              (void)adaptobs::spr_injection_gain(so2.Ao, so2.Co, Eigen::Vector3d(-1, 3, 2), 2.0);
            }).find("'gamma'"),
            std::string::npos);
  EXPECT_NE(configuration_error_of([&] {
              (void)adaptobs::spr_injection_gain(so2.Ao, so2.Co, Eigen::Vector3d(1, -1, 2), 2.0);
            }).find("'gamma'"),
            std::string::npos);
  EXPECT_NE(
      configuration_error_of([&] { (void)adaptobs::spr_injection_gain(so2.Ao, so2.Co, gamma, 0.0); }).find("'lambda'"),
      std::string::npos);
}

TEST(Riccati, CareAndKalmanBucyGainOnRandomSystems) {
  RandomMatrices rng(3);
  for (int n : {1, 2, 3, 5, 8}) {
    for (int m : {1, 2}) {
      const Matrix a = rng.uniform<Matrix>(n, n) * 1.5;
      const Matrix b = rng.uniform<Matrix>(n, m);
      const Matrix g = rng.uniform<Matrix>(n, n);
      const Matrix q = g.transpose() * g + 0.1 * Matrix::Identity(n, n);
      const Matrix r = Matrix::Identity(m, m) * 0.5;
      const auto x = adaptobs::solve_care(a, b, q, r);
      const Matrix residual = a.transpose() * x.X + x.X * a - x.X * b * r.inverse() * b.transpose() * x.X + q;
      EXPECT_LE(residual.norm(), 1e-9 * std::max(1.0, x.X.norm())) << "n=" << n << " m=" << m;
      EXPECT_LT(adaptobs::spectral_abscissa(Matrix(a - b * r.inverse() * b.transpose() * x.X)), 0.0);
      const auto kb = adaptobs::kalman_bucy_gain(a, Matrix(b.transpose()), q, r);
      EXPECT_LT(adaptobs::spectral_abscissa(Matrix(a - kb.K * b.transpose())), 0.0);
      EXPECT_LE(kb.relative_residual, 1e-9);
    }
  }
  // Scalar: 2ax − x²b²/r + q = 0.
  const double a = 1.0, b = 2.0, q = 3.0, r = 0.5;
  const double x = (a + std::sqrt(a * a + b * b * q / r)) * r / (b * b);
  EXPECT_NEAR(adaptobs::solve_care(Eigen::Matrix<double, 1, 1>(a), Eigen::Matrix<double, 1, 1>(b),
                                   Eigen::Matrix<double, 1, 1>(q), Eigen::Matrix<double, 1, 1>(r))
                  .X(0, 0),
              x, 1e-12);
  // An uncontrollable unstable mode has no stabilizing solution.
  EXPECT_NE(configuration_error_of([] {
              (void)adaptobs::solve_care(Eigen::Matrix2d(Eigen::Vector2d(1, -1).asDiagonal()), Eigen::Vector2d(0, 1),
                                         Eigen::Matrix2d::Identity(), Eigen::Matrix<double, 1, 1>(1));
            }).find("'A, B'"),
            std::string::npos);
}

// Q = R near the largest number: X = r(a + √(a² + 1)) for b = 1 is found in
// scaled form. For a = 1 it is beyond the floating-point range, and the
// solvers refuse, naming Q and R, instead of returning X = ∞ as a solution; for
// a = −0.001 it is just inside, and is returned to full accuracy.
TEST(ContinuousRiccati, ASolutionBeyondTheFloatingPointRangeIsRefusedNamingQAndR) {
  using Scalar1 = Eigen::Matrix<double, 1, 1>;
  const Scalar1 one(1), huge(1e308);
  const auto message = configuration_error_of([&] { (void)adaptobs::solve_care(one, one, huge, huge); });
  EXPECT_NE(message.find("'Q, R'"), std::string::npos) << message;
  EXPECT_NE(message.find("floating-point range"), std::string::npos) << message;
  EXPECT_CONFIGURATION_ERROR_NAMES(adaptobs::kalman_bucy_gain(one, one, huge, huge), "Q, R");
  const double a = -0.001, r = 1.2e308;
  const auto inside = adaptobs::solve_care(Scalar1(a), one, Scalar1(r), Scalar1(r));
  EXPECT_NEAR(inside.X(0, 0) / (r * (a + std::sqrt(a * a + 1))), 1.0, 1e-13);
}

TEST(Riccati, LyapunovSolverResidual) {
  RandomMatrices rng(5);
  for (int n : {1, 2, 4, 7}) {
    Matrix a = rng.uniform<Matrix>(n, n);
    a -= (adaptobs::spectral_abscissa(a) + 0.5) * Matrix::Identity(n, n);
    const Matrix g = rng.uniform<Matrix>(n, n);
    const Matrix q = g * g.transpose();
    const Matrix x = adaptobs::solve_continuous_lyapunov(a, q);
    EXPECT_LE((a.transpose() * x + x * a + q).norm(), 1e-11 * std::max(1.0, x.norm()));
    EXPECT_GE(adaptobs::symmetric_eigenvalues(x)(0), -1e-12);
  }
  // A slow Hurwitz A is as regular as a fast one: with eigenvalues −1e-20 and
  // −3e-20 it was refused as sharing an eigenvalue with −A. X = diag(1/(2·1e-20), 1/(2·3e-20)).
  const Eigen::Matrix2d slow = Eigen::Vector2d(-1e-20, -3e-20).asDiagonal();
  const Eigen::Matrix2d x_slow = adaptobs::solve_continuous_lyapunov(slow, Eigen::Matrix2d::Identity());
  EXPECT_NEAR(x_slow(0, 0) * 2e-20, 1.0, 1e-14);
  EXPECT_NEAR(x_slow(1, 1) * 6e-20, 1.0, 1e-14);
  // The solution is symmetrized: a non-symmetric Q gave an X that solves nothing.
  Eigen::Matrix2d q_skewed;
  q_skewed << 1, 2, 0, 1;
  EXPECT_CONFIGURATION_ERROR_NAMES(
      adaptobs::solve_continuous_lyapunov(Eigen::Matrix2d(-Eigen::Matrix2d::Identity()), q_skewed), "Q");
}

// P of the Riccati differential equation tends to the CARE solution for a constant system.
TEST(Riccati, DifferentialEquationTendsToTheAlgebraicSolution) {
  using D = siso::Dims<double>;
  adaptobs::RiccatiDifferentialEquation<D> rde(Eigen::Matrix3d::Identity(), Eigen::Matrix3d::Identity(),
                                               Eigen::Matrix<double, 1, 1>(0.1));
  const auto model = siso::model<double>();
  for (int k = 0; k < 2000; ++k) rde.advance(model, 0.01 * k, 0.01 * (k + 1));
  const auto kb = adaptobs::kalman_bucy_gain(siso::dynamics<double>(), siso::output_matrix<double>(),
                                             Eigen::Matrix3d::Identity(), Eigen::Matrix<double, 1, 1>(0.1));
  EXPECT_MATRIX_NEAR(rde.covariance(), kb.P, 1e-9, 1e-9);
  EXPECT_MATRIX_NEAR(rde.gain(siso::output_matrix<double>()), kb.K, 1e-8, 1e-8);
}

// A stiff system (eigenvalue −200) sampled every 0.1 s: one RK4 step per sample
// would have h|λ| = 40, far outside RK4's stability interval. The step is
// bounded by 2.5 / (2‖A − KC‖_F), and P follows a run with 1000 steps per sample.
TEST(Riccati, DifferentialEquationSubstepsALongIntervalOfAStiffSystem) {
  using D = adaptobs::Dimensions<double, 2, 1, 1, 0>;
  Eigen::Matrix2d a;
  a << -200, 1, 0, -1;
  const auto model = adaptobs::make_continuous_lti_model<D>(a, Eigen::Vector2d(0, 1), Eigen::RowVector2d(1, 1),
                                                            [](double) { return Eigen::Matrix<double, 2, 0>(); });
  const Eigen::Matrix<double, 1, 1> r(0.5);
  adaptobs::RiccatiDifferentialEquation<D> bounded(Eigen::Matrix2d::Identity(), Eigen::Matrix2d::Identity(), r);
  adaptobs::RiccatiDifferentialEquation<D> fine(Eigen::Matrix2d::Identity(), Eigen::Matrix2d::Identity(), r);
  int bounded_steps = 0;
  for (int k = 0; k < 50; ++k) {
    bounded_steps += bounded.advance(model, 0.1 * k, 0.1 * (k + 1));
    EXPECT_EQ(fine.advance(model, 0.1 * k, 0.1 * (k + 1), 1000), 1000);
  }
  // At least 2‖A − KC‖_F · 0.1 / 2.5 ≥ 16 steps per sample, and not many more.
  EXPECT_GE(bounded_steps, 50 * 16);
  EXPECT_LE(bounded_steps, 50 * 20);
  EXPECT_MATRIX_NEAR(bounded.covariance(), fine.covariance(), 1e-9, 1e-6);
  EXPECT_GT(bounded.covariance().determinant(), 0.0);
}

// A model that turns non-finite inside an interval, where only an RK4 stage
// sees it, is refused by name, and P stays as it was, bit for bit.
TEST(Riccati, DifferentialEquationRefusesANonFiniteModelWithinTheIntervalLeavingPUnchanged) {
  using D = adaptobs::Dimensions<double, 2, 1, 1, 0>;
  const auto matrices_at = [](double t) {
    Eigen::Matrix2d a;
    a << -1, 1, 0, t < 0.3 ? -2 : std::numeric_limits<double>::quiet_NaN();
    return adaptobs::ContinuousSystem<D>{a, Eigen::Vector2d(0, 1), Eigen::RowVector2d(1, 0)};
  };
  const auto model =
      adaptobs::make_continuous_ltv_model<D>(matrices_at, [](double) { return Eigen::Matrix<double, 2, 0>(); });
  adaptobs::RiccatiDifferentialEquation<D> rde(Eigen::Matrix2d::Identity(), Eigen::Matrix2d::Identity(),
                                               Eigen::Matrix<double, 1, 1>(0.5));
  rde.advance(model, 0, 0.1);
  const Eigen::Matrix2d before = rde.covariance();
  // One step over [0.1, 0.5]: its start is finite, its stages at 0.3 and 0.5 are not.
  EXPECT_NE(configuration_error_of([&] { rde.advance(model, 0.1, 0.5); }).find("'model'"), std::string::npos);
  EXPECT_TRUE(rde.covariance() == before);
  // Ten steps: the first two are finite, the third reaches 0.3.
  EXPECT_NE(configuration_error_of([&] { rde.advance(model, 0.1, 0.5, 10); }).find("'model'"), std::string::npos);
  EXPECT_TRUE(rde.covariance() == before);
  EXPECT_EQ(rde.advance(model, 0.1, 0.2, 4), 4);
  EXPECT_TRUE(rde.covariance().allFinite());
}

TEST(LtvStability, FloquetExponents) {
  // Markus–Yamabe: frozen eigenvalues −1/4 ± 0.66i at every t, yet a Floquet exponent of +1/2.
  const auto markus_yamabe = [](double t) {
    const double c = std::cos(t), s = std::sin(t);
    Eigen::Matrix2d a;
    a << -1 + 1.5 * c * c, 1 - 1.5 * s * c, -1 - 1.5 * s * c, -1 + 1.5 * s * s;
    return a;
  };
  EXPECT_NEAR(adaptobs::spectral_abscissa(Matrix(markus_yamabe(0.3))), -0.25, 1e-12);
  EXPECT_NEAR(adaptobs::floquet_exponents(markus_yamabe, std::numbers::pi)(0), 0.5, 1e-6);
  EXPECT_FALSE(adaptobs::is_exponentially_stable_periodic(markus_yamabe, std::numbers::pi));
  // Plant of the MIMO examples: A22(t) has exponents −2, −2; A − KC's largest is −1.98.
  const auto a22 = [](double t) {
    return Eigen::Matrix2d(periodic::form8_dynamics<double>(t).bottomRightCorner(2, 2));
  };
  EXPECT_MATRIX_NEAR(adaptobs::floquet_exponents(a22, periodic::period), Eigen::Vector2d(-2, -2), 1e-6, 0);
  const auto closed = [](double t) {
    const auto s = periodic::system<double>(t);
    return Eigen::Matrix4d(s.A - periodic::zhang_gain<double>() * s.C);
  };
  EXPECT_NEAR(adaptobs::floquet_exponents(closed, periodic::period)(0), -1.98, 0.01);
  EXPECT_TRUE(adaptobs::is_exponentially_stable_periodic(closed, periodic::period, 1.9));
}

// A solution that grows like e^{800 t} leaves the floating-point range within
// one period: no exponent can be told, and stability is not certified (the
// eigen-solver's failure on the infinite monodromy matrix once returned
// unwritten storage, read here as exponents −1, −2, −712 and "stable"). At
// e^{700 t} the monodromy matrix is still finite and the exponent is found.
TEST(LtvStability, AMonodromyMatrixBeyondTheFloatingPointRangeIsNotCertifiedStable) {
  for (const double growth : {700.0, 800.0}) {
    const auto a = [growth](double) {
      Eigen::Matrix3d m;
      m << growth, 1, 0, 0, -1, 1, 0, 0, -2;
      return m;
    };
    const Eigen::VectorXd exponents = adaptobs::floquet_exponents(a, 1.0);
    EXPECT_FALSE(adaptobs::is_exponentially_stable_periodic(a, 1.0)) << growth;
    if (growth < 709) {
      EXPECT_NEAR(exponents(0), growth, 1.0);
      EXPECT_MATRIX_NEAR(exponents.tail(2), Eigen::Vector2d(-1, -2), 1e-6, 0);
    } else {
      EXPECT_TRUE(exponents.array().isNaN().all()) << exponents.transpose();
    }
  }
}

// RK4 damps an oscillatory mode z = iωh by |R(z)| = 1 − (ωh)⁶/144: at 2000 fixed
// steps over ωT ≈ 1005 rad, e' = [[ε, ω(t)], [−ω(t), ε]] e (exponents exactly
// ε = +0.01, A(t) = εI + ω(t)J with commuting terms) read −0.0132 and was
// certified stable. The step count now follows h·max‖A(t)‖ and is confirmed by
// step doubling.
TEST(LtvStability, AnUnstableFastOscillatorKeepsItsPositiveExponent) {
  const double eps = 0.01, omega = 100.0, period = 2 * std::numbers::pi / omega * 160;
  const auto a = [&](double t) {
    const double w = omega * (1 + 0.1 * std::sin(omega * t / 160));
    Eigen::Matrix2d m;
    m << eps, w, -w, eps;
    return m;
  };
  EXPECT_MATRIX_NEAR(adaptobs::floquet_exponents(a, period), Eigen::Vector2d(eps, eps), 1e-5, 0);
  EXPECT_FALSE(adaptobs::is_exponentially_stable_periodic(a, period));
  // The same oscillator with ε = −0.01 is stable.
  const auto stable = [&](double t) { return Eigen::Matrix2d(a(t) - 2 * eps * Eigen::Matrix2d::Identity()); };
  EXPECT_TRUE(adaptobs::is_exponentially_stable_periodic(stable, period));
}

// A stiff stable mode. With the step count asked for taken as fixed, h·1000
// lay outside RK4's stability region, the monodromy matrix overflowed and
// e' = −1000e read NaN, "not stable"; the step count asked for is a minimum (100
// steps over T = 1 give h·1000 = 10), the step control takes more. Over a period
// where e^{−1000T} is representable the exponent is found; where it underflows
// (T = 1: e^{−1000}, below DBL_MIN) it cannot be told and is refused; the
// stability of diag(−1, −1000) needs only its largest exponent, −1.
TEST(LtvStability, AStiffStableModeIsFoundOrRefusedNotReportedUnstable) {
  const auto a = [](double) { return Eigen::MatrixXd(Eigen::MatrixXd::Constant(1, 1, -1000)); };
  EXPECT_NEAR(adaptobs::floquet_exponents(a, 0.5)(0), -1000, 1e-3);
  EXPECT_TRUE(adaptobs::is_exponentially_stable_periodic(a, 0.5, 999.0));
  const std::string refused = configuration_error_of([&] { (void)adaptobs::floquet_exponents(a, 1.0); });
  EXPECT_NE(refused.find("'A'"), std::string::npos) << refused;
  EXPECT_NE(refused.find("underflows"), std::string::npos) << refused;
  EXPECT_CONFIGURATION_ERROR_NAMES(adaptobs::is_exponentially_stable_periodic(a, 1.0), "A");
  const auto two_rates = [](double) { return Eigen::Matrix2d(Eigen::Vector2d(-1, -1000).asDiagonal()); };
  EXPECT_TRUE(adaptobs::is_exponentially_stable_periodic(two_rates, 1.0, 0.0, 100));
  EXPECT_FALSE(adaptobs::is_exponentially_stable_periodic(two_rates, 1.0, 1.5));
  // The −1000 multiplier is rounding noise beside e^{−1}: its exponent is
  // reported as the resolution bound −1 + log(2ε)/T, which it lies below.
  const Eigen::Vector2d both = adaptobs::floquet_exponents(two_rates, 1.0);
  const double bound = -1 + std::log(2 * std::numeric_limits<double>::epsilon());
  EXPECT_NEAR(both(0), -1, 1e-5);
  EXPECT_NEAR(both(1), bound, 1e-5);
  // Nor does a fast mode need to underflow: −50 beside −1 over T = 1 (a
  // multiplier 2e-22 beside 0.37) was refused as underflowing.
  Eigen::Matrix2d coupled;
  coupled << -25.5, 24.5, 24.5, -25.5;  // eigenvalues −1 and −50
  const Eigen::Vector2d fast = adaptobs::floquet_exponents([&](double) { return coupled; }, 1.0);
  EXPECT_NEAR(fast(0), -1, 1e-5);
  EXPECT_NEAR(fast(1), -1 + std::log(2 * std::numeric_limits<double>::epsilon()), 1e-5);
  EXPECT_TRUE(adaptobs::is_exponentially_stable_periodic([&](double) { return coupled; }, 1.0, 0.9));
  // The period is checked whatever the order.
  EXPECT_CONFIGURATION_ERROR_NAMES(adaptobs::floquet_exponents([](double) { return Eigen::MatrixXd(0, 0); }, -1.0),
                                   "period");
}

// A(t) is checked at every evaluation, not only at t0: a later A(t) of another
// size overran the heap of the dynamic-size transition matrix, and a later NaN
// reached the exponents.
TEST(LtvStability, ADynamicsCallableChangingShapeOrNotFiniteIsRefusedByName) {
  const auto resized = [](double t) {
    return t < 0.5 ? Matrix(-Matrix::Identity(2, 2)) : Matrix(-Matrix::Identity(3, 3));
  };
  const std::string message = configuration_error_of([&] { (void)adaptobs::transition_matrix(resized, 0.0, 1.0); });
  EXPECT_NE(message.find("'A'"), std::string::npos) << message;
  EXPECT_NE(message.find("3x3"), std::string::npos) << message;
  EXPECT_CONFIGURATION_ERROR_NAMES(adaptobs::floquet_exponents(resized, 1.0), "A");
  EXPECT_CONFIGURATION_ERROR_NAMES(adaptobs::is_exponentially_stable_periodic(resized, 1.0), "A");
  const auto not_finite = [](double t) {
    return Matrix(Matrix::Constant(1, 1, t < 0.7 ? -1.0 : std::numeric_limits<double>::quiet_NaN()));
  };
  EXPECT_CONFIGURATION_ERROR_NAMES(adaptobs::transition_matrix(not_finite, 0.0, 1.0), "A");
  EXPECT_CONFIGURATION_ERROR_NAMES(adaptobs::floquet_exponents(not_finite, 1.0), "A");
  EXPECT_NEAR(adaptobs::transition_matrix(not_finite, 0.0, 0.5)(0, 0), std::exp(-0.5), 1e-12);
}

// The frequency sweep refuses what it cannot evaluate instead of skipping it:
// at ω_max = ∞ every point of the grid was NaN, and G = (s² + 0.01s + 1)/(s + 1)³,
// which is not strictly positive real, was certified.
TEST(SprDesign, FrequencySweepRefusesAnInfiniteRangeOrNonFiniteSystem) {
  Eigen::Matrix3d a;  // companion form of (s + 1)³
  a << 0, 1, 0, 0, 0, 1, -1, -3, -3;
  const Eigen::Vector3d b(0, 0, 1);
  const Eigen::RowVector3d c(1, 0.01, 1);
  EXPECT_FALSE(adaptobs::spr_frequency_sweep(a, b, c).strictly_positive_real);
  EXPECT_CONFIGURATION_ERROR_NAMES(
      adaptobs::spr_frequency_sweep(a, b, c, 1e-4, std::numeric_limits<double>::infinity()),
      "omega_min, omega_max, points");
  Eigen::Matrix3d a_not_finite = a;
  a_not_finite(2, 0) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_CONFIGURATION_ERROR_NAMES(adaptobs::spr_frequency_sweep(a_not_finite, b, c), "A");
}

}  // namespace
