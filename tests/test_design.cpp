// Design helpers: DARE and Kalman gain, the Riccati recursion for
// time-varying gains, stability checks, and the excitation monitor.

#include <adaptobs/core/detail/cholesky.hpp>
#include <adaptobs/core/spectral_norm.hpp>
#include <adaptobs/core/symmetric_eigenvalues.hpp>
#include <adaptobs/design/companion_matrix.hpp>
#include <adaptobs/design/dare.hpp>
#include <adaptobs/design/riccati_recursion.hpp>
#include <adaptobs/design/stability.hpp>
#include <adaptobs/diagnostics/excitation_monitor.hpp>

#include "support/eigen_testing.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <utility>

namespace {

using adaptobs::ConfigurationError;
using adaptobs::testing::RandomMatrices;

// A random square matrix with prescribed spectral radius (unstable when > 1).
Eigen::MatrixXd random_dynamics(RandomMatrices& rng, int n, double radius) {
  Eigen::MatrixXd a = rng.uniform<Eigen::MatrixXd>(n, n);
  return a * (radius / adaptobs::spectral_radius(a));
}

Eigen::MatrixXd random_spd(RandomMatrices& rng, int n, double floor) {
  const Eigen::MatrixXd g = rng.uniform<Eigen::MatrixXd>(n, n);
  return g * g.transpose() + floor * Eigen::MatrixXd::Identity(n, n);
}

TEST(Dare, RandomStabilizableDetectablePairs) {
  RandomMatrices rng(21);
  int cases = 0;
  for (int n : {1, 2, 3, 5, 8, 12}) {
    for (int m : {1, 2, 3}) {
      for (double radius : {0.5, 0.99, 1.3, 2.0}) {
        const Eigen::MatrixXd a = random_dynamics(rng, n, radius);
        const Eigen::MatrixXd b = rng.uniform<Eigen::MatrixXd>(n, m);  // controllable with probability 1
        // Q = GᵀG of rank ≤ n with G random: (A, Q) detectable with probability 1.
        const Eigen::MatrixXd g = rng.uniform<Eigen::MatrixXd>(std::max(1, n / 2), n);
        const Eigen::MatrixXd q = g.transpose() * g;
        const Eigen::MatrixXd r = random_spd(rng, m, 0.1);
        const auto solution = adaptobs::solve_dare(a, b, q, r);
        EXPECT_LE(solution.relative_residual, 1e-10) << "n=" << n << " m=" << m << " radius=" << radius;
        EXPECT_LE(adaptobs::dare_relative_residual(solution.X, a, b, q, r), 1e-10);
        EXPECT_LE((solution.X - solution.X.transpose()).norm(), 1e-12 * solution.X.norm());
        const Eigen::MatrixXd s = r + b.transpose() * solution.X * b;
        const Eigen::MatrixXd closed = a - b * adaptobs::testing::solve_by_ldlt(s, b.transpose() * solution.X * a);
        EXPECT_LT(adaptobs::spectral_radius(closed), 1.0);
        ++cases;
      }
    }
  }
  EXPECT_EQ(cases, 72);
}

TEST(Dare, ScalarClosedForm) {
  // x = a²x − a²b²x²/(r + b²x) + q  ⇔  b²x² + (r − a²r − qb²)x − qr = 0.
  for (double a : {0.3, 1.0, 1.7}) {
    const double b = 0.8, q = 2.0, r = 0.5;
    const double lin = r - a * a * r - q * b * b;
    const double expected = (-lin + std::sqrt(lin * lin + 4 * b * b * q * r)) / (2 * b * b);
    const auto solution = adaptobs::solve_dare(Eigen::Matrix<double, 1, 1>(a), Eigen::Matrix<double, 1, 1>(b),
                                               Eigen::Matrix<double, 1, 1>(q), Eigen::Matrix<double, 1, 1>(r));
    EXPECT_NEAR(solution.X(0, 0), expected, 1e-12 * expected) << "a = " << a;
  }
}

TEST(Dare, KalmanGainMakesPredictorStable) {
  RandomMatrices rng(22);
  for (int n : {2, 4, 6, 10}) {
    for (int m : {1, 2}) {
      const Eigen::MatrixXd a = random_dynamics(rng, n, 1.4);
      const Eigen::MatrixXd c = rng.uniform<Eigen::MatrixXd>(m, n);
      const Eigen::MatrixXd q = random_spd(rng, n, 0.01);
      const Eigen::MatrixXd r = random_spd(rng, m, 0.1);
      const auto kalman = adaptobs::steady_state_kalman_gain(a, c, q, r);
      EXPECT_LE(kalman.relative_residual, 1e-10);
      EXPECT_TRUE(adaptobs::is_schur_stable(Eigen::MatrixXd(a - kalman.K * c))) << "n=" << n << " m=" << m;
      // P is the fixed point of the one-step covariance recursion with this K.
      const Eigen::MatrixXd closed = a - kalman.K * c;
      const Eigen::MatrixXd p_next = closed * kalman.P * closed.transpose() + kalman.K * r * kalman.K.transpose() + q;
      EXPECT_LE((p_next - kalman.P).norm(), 1e-9 * kalman.P.norm());
    }
  }
}

TEST(Dare, FixedSizeAgreesWithDynamic) {
  RandomMatrices rng(23);
  const Eigen::Matrix4d a = random_dynamics(rng, 4, 1.2);
  const Eigen::Matrix<double, 2, 4> c = rng.uniform<Eigen::Matrix<double, 2, 4>>();
  const auto fixed = adaptobs::steady_state_kalman_gain(a, c, Eigen::Matrix4d::Identity(), Eigen::Matrix2d::Identity());
  const auto dynamic = adaptobs::steady_state_kalman_gain(
      Eigen::MatrixXd(a), Eigen::MatrixXd(c), Eigen::MatrixXd::Identity(4, 4), Eigen::MatrixXd::Identity(2, 2));
  EXPECT_MATRIX_NEAR(fixed.K, dynamic.K, 1e-12, 1e-12);
}

using adaptobs::testing::configuration_error_of;

TEST(Dare, RefusesUnstabilizablePairAndBadWeights) {
  // The unstable mode 2 is not reachable from B.
  const Eigen::Matrix2d a = Eigen::Vector2d(2.0, 0.5).asDiagonal();
  const Eigen::Vector2d b(0, 1);
  const Eigen::Matrix2d q = Eigen::Matrix2d::Identity();
  const Eigen::Matrix<double, 1, 1> r = Eigen::Matrix<double, 1, 1>::Ones();
  EXPECT_NE(configuration_error_of([&] { (void)adaptobs::solve_dare(a, b, q, r); }).find("stabilizable"),
            std::string::npos);
  const Eigen::Matrix<double, 1, 1> negative_r(-1.0);
  EXPECT_NE(configuration_error_of([&] { (void)adaptobs::solve_dare(a, b, q, negative_r); }).find("'R'"),
            std::string::npos);
  Eigen::Matrix2d indefinite_q;
  indefinite_q << 1, 0, 0, -1;
  EXPECT_NE(configuration_error_of([&] { (void)adaptobs::solve_dare(a, b, indefinite_q, r); }).find("'Q'"),
            std::string::npos);
  Eigen::Matrix2d asymmetric_q;
  asymmetric_q << 1, 0.5, 0, 1;
  EXPECT_NE(configuration_error_of([&] { (void)adaptobs::solve_dare(a, b, asymmetric_q, r); }).find("symmetric"),
            std::string::npos);
}

// Q = R near the largest number. X of (A, B) = (0.99, 1) is found in scaled
// form but is beyond the floating-point range: refused, naming Q and R, where
// X = ∞ was returned as a solution. The filter's P of (0.9, 1) is just inside,
// and its gain, which does not change when Q and R are scaled together, equals
// the gain at Q = R = 1 (S = CPCᵀ + R overflowed, and K = 0 was returned).
TEST(Dare, ASolutionBeyondTheFloatingPointRangeIsRefusedAndAGainNearItIsExact) {
  using Scalar1 = Eigen::Matrix<double, 1, 1>;
  const Scalar1 one(1);
  const auto message = configuration_error_of(
      [&] { (void)adaptobs::solve_dare(Scalar1(0.99), one, Scalar1(1.2e308), Scalar1(1.2e308)); });
  EXPECT_NE(message.find("'Q, R'"), std::string::npos) << message;
  EXPECT_NE(message.find("floating-point range"), std::string::npos) << message;
  const auto near_limit = adaptobs::steady_state_kalman_gain(Scalar1(0.9), one, Scalar1(1e308), Scalar1(1e308));
  const auto unit = adaptobs::steady_state_kalman_gain(Scalar1(0.9), one, one, one);
  EXPECT_NEAR(near_limit.P(0, 0) / (1e308 * unit.P(0, 0)), 1.0, 1e-13);
  EXPECT_NEAR(near_limit.K(0, 0), unit.K(0, 0), 1e-14);
}

// Bad limits are refused by name: with too few doubling steps allowed, a
// controllable pair was called unstabilizable, and a margin of 1.5 was blamed on
// conditioning.
TEST(Dare, BadOptionsAreRefusedByName) {
  Eigen::Matrix2d a;
  a << 1.1, 1, 0, 0.9;
  const Eigen::Vector2d b(0, 1);
  const Eigen::Matrix2d q = Eigen::Matrix2d::Identity();
  const Eigen::Matrix<double, 1, 1> r(1);
  EXPECT_CONFIGURATION_ERROR_NAMES(adaptobs::solve_dare(a, b, q, r, {.max_iterations = 0}), "options.max_iterations");
  EXPECT_CONFIGURATION_ERROR_NAMES(adaptobs::solve_dare(a, b, q, r, {.stability_margin = 1.5}),
                                   "options.stability_margin");
  EXPECT_CONFIGURATION_ERROR_NAMES(
      adaptobs::solve_dare(a, b, q, r, {.tolerance = std::numeric_limits<double>::quiet_NaN()}), "options.tolerance");
  EXPECT_CONFIGURATION_ERROR_NAMES(
      adaptobs::steady_state_kalman_gain(Eigen::Matrix2d(a.transpose()), Eigen::RowVector2d(b.transpose()), q, r,
                                         {.residual_tolerance = -1}),
      "options.residual_tolerance");
  // A limit too small to reach a stabilizing start is named as the reason, not the pair.
  EXPECT_CONFIGURATION_ERROR_NAMES(adaptobs::solve_dare(a, b, q, r, {.max_iterations = 1}), "options.max_iterations");
  EXPECT_LE(adaptobs::solve_dare(a, b, q, r).relative_residual, 1e-10);
}

using Dims3 = adaptobs::Dimensions<double, 3, 1, 1, 1>;

TEST(KalmanGainRecursion, ConvergesToSteadyStateGainForLti) {
  RandomMatrices rng(25);
  const Eigen::Matrix3d a = random_dynamics(rng, 3, 1.3);
  const Eigen::RowVector3d c = rng.uniform<Eigen::RowVector3d>();
  const Eigen::Matrix3d q = Eigen::Matrix3d::Identity() * 0.1;
  const Eigen::Matrix<double, 1, 1> r(0.5);
  adaptobs::KalmanGainRecursion<Dims3> recursion(Eigen::Matrix3d::Identity() * 10, q, r);
  const adaptobs::DiscreteSystem<Dims3> system{a, Eigen::Vector3d::Zero(), c};
  for (int k = 0; k < 500; ++k) (void)recursion.next_gain(system);
  const auto steady = adaptobs::steady_state_kalman_gain(a, c, q, r);
  EXPECT_MATRIX_NEAR(recursion.gain(), steady.K, 1e-10, 1e-9);
}

// A step with a non-finite (or, at run-time sizes, misshapen) system is refused
// by name with the covariance unchanged, and the recursion goes on from there;
// a NaN once stayed in P for every later step.
TEST(KalmanGainRecursion, ANonFiniteSystemIsRefusedWithTheCovarianceUnchanged) {
  const Eigen::Matrix3d q = Eigen::Matrix3d::Identity() * 0.1;
  const Eigen::Matrix<double, 1, 1> r(0.5);
  adaptobs::KalmanGainRecursion<Dims3> recursion(Eigen::Matrix3d::Identity() * 10, q, r);
  const adaptobs::DiscreteSystem<Dims3> system{Eigen::Matrix3d::Identity() * 0.9, Eigen::Vector3d::Zero(),
                                               Eigen::RowVector3d(1, 0, 0)};
  (void)recursion.next_gain(system);
  const Eigen::Matrix3d before = recursion.covariance();
  adaptobs::DiscreteSystem<Dims3> bad = system;
  bad.A(1, 2) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_CONFIGURATION_ERROR_NAMES(recursion.next_gain(bad), "system.A");
  bad = system;
  bad.C(0, 1) = std::numeric_limits<double>::infinity();
  EXPECT_CONFIGURATION_ERROR_NAMES(recursion.next_gain(bad), "system.C");
  EXPECT_TRUE(adaptobs::testing::bitwise_equal(recursion.covariance(), before));
  EXPECT_TRUE(recursion.next_gain(system).allFinite());
}

TEST(KalmanGainRecursion, TimeVaryingGainsMakeErrorDynamicsExponentiallyStable) {
  // A_k rotates and stretches with k; C_k alternates its direction. Each frozen
  // A_k is unstable (spectral radius 1.05), the pair is uniformly observable.
  auto system_at = [](int k) {
    const double angle = 0.3 + 0.2 * std::sin(0.05 * k);
    Eigen::Matrix3d a;
    a << std::cos(angle), -std::sin(angle), 0.1,  //
        std::sin(angle), std::cos(angle), 0,      //
        0, 0.2, 0.9;
    a *= 1.05 / adaptobs::spectral_radius(a);
    Eigen::RowVector3d c(1.0, 0.3 * std::cos(0.1 * k), 0.5);
    return adaptobs::DiscreteSystem<Dims3>{a, Eigen::Vector3d::Zero(), c};
  };
  adaptobs::KalmanGainRecursion<Dims3> recursion(Eigen::Matrix3d::Identity(), Eigen::Matrix3d::Identity() * 0.01,
                                                 Eigen::Matrix<double, 1, 1>(0.1));
  Eigen::Matrix3d transition = Eigen::Matrix3d::Identity();
  std::vector<double> norms;
  for (int k = 0; k < 400; ++k) {
    const auto system = system_at(k);
    const Eigen::Vector3d gain = recursion.next_gain(system);
    transition = ((system.A - gain * system.C) * transition).eval();
    norms.push_back(transition.norm());
  }
  // Definition 1 of Guyader & Zhang (2003): ‖Π (A_i − K_iC_i)‖ ≤ r q^k with q < 1.
  EXPECT_LT(norms.back(), 1e-8);
  EXPECT_LT(adaptobs::testing::fit_geometric_rate(norms), 0.97);
  const Eigen::Matrix3d p = recursion.covariance();
  EXPECT_LE((p - p.transpose()).norm(), 1e-14 * p.norm());
  EXPECT_GT(adaptobs::symmetric_eigenvalues(p)(0), 0.0);
}

TEST(Stability, SchurAndHurwitzChecks) {
  Eigen::Matrix2d rotation;
  rotation << 0, 1, -1, 0;  // eigenvalues ±i
  EXPECT_NEAR(adaptobs::spectral_radius(rotation), 1.0, 1e-15);
  EXPECT_FALSE(adaptobs::is_schur_stable(rotation));
  EXPECT_TRUE(adaptobs::is_schur_stable(Eigen::Matrix2d(0.99 * rotation)));
  EXPECT_FALSE(adaptobs::is_schur_stable(Eigen::Matrix2d(0.99 * rotation), 0.02));
  EXPECT_FALSE(adaptobs::is_hurwitz_stable(rotation));
  Eigen::Matrix2d damped;
  damped << -0.1, 1, -1, -0.1;
  EXPECT_NEAR(adaptobs::spectral_abscissa(damped), -0.1, 1e-15);
  EXPECT_TRUE(adaptobs::is_hurwitz_stable(damped));
  EXPECT_FALSE(adaptobs::is_hurwitz_stable(damped, 0.2));

  // A matrix that is not square or not finite is refused under the name of the function called.
  Eigen::Matrix2d not_finite = damped;
  not_finite(0, 1) = std::numeric_limits<double>::quiet_NaN();
  const Eigen::MatrixXd wide = Eigen::MatrixXd::Zero(2, 3);
  for (const auto& [message, who] : std::vector<std::pair<std::string, std::string>>{
           {configuration_error_of([&] { (void)adaptobs::spectral_radius(not_finite); }), "spectral_radius"},
           {configuration_error_of([&] { (void)adaptobs::spectral_abscissa(wide); }), "spectral_abscissa"},
           {configuration_error_of([&] { (void)adaptobs::is_hurwitz_stable(not_finite); }), "is_hurwitz_stable"},
           {configuration_error_of([&] { (void)adaptobs::eigenvalues(wide); }), "eigenvalues"}}) {
    EXPECT_EQ(message.rfind(who + ":", 0), 0u) << message;
    EXPECT_NE(message.find("'M'"), std::string::npos) << message;
  }
}

// ρ(M) ≤ the squaring bound, and the bound reaches ρ(M): checked against the
// eigenvalues on random, defective and graded matrices.
TEST(Stability, SquaringBoundMeetsSpectralRadius) {
  RandomMatrices rng(31);
  for (int n : {1, 2, 3, 5, 8, 20}) {
    for (double radius : {0.3, 0.97, 1.03, 1.4}) {
      const Eigen::MatrixXd a = random_dynamics(rng, n, radius);
      const double bound = adaptobs::spectral_radius_bound(a);
      EXPECT_NEAR(bound, radius, 1e-9 * radius) << "n=" << n;
      EXPECT_EQ(adaptobs::is_schur_stable(a), radius < 1.0) << "n=" << n << " radius=" << radius;
    }
  }
  // A Jordan block with a huge coupling: ‖M^k‖ grows 1e6-fold before it decays.
  Eigen::Matrix3d jordan;
  jordan << 0.999, 1e3, 0, 0, 0.999, 1e3, 0, 0, 0.999;
  EXPECT_TRUE(adaptobs::is_schur_stable(jordan));
  EXPECT_FALSE(adaptobs::is_schur_stable(jordan, 0.002));
  EXPECT_NEAR(adaptobs::spectral_radius_bound(jordan), 0.999, 1e-6);
  EXPECT_FALSE(adaptobs::is_schur_stable(Eigen::Matrix3d(jordan / 0.998)));
  // Nilpotent: exactly 0. Scaled by 1e150 the squares would overflow without rescaling.
  Eigen::Matrix3d nilpotent = Eigen::Matrix3d::Zero();
  nilpotent(0, 1) = nilpotent(1, 2) = 1e150;
  EXPECT_EQ(adaptobs::spectral_radius_bound(nilpotent), 0.0);
  EXPECT_TRUE(adaptobs::is_schur_stable(nilpotent));
  Eigen::Matrix2d huge;
  huge << 0.5e200, 1e200, -1e200, 0.5e200;  // ρ = 1.118e200
  EXPECT_NEAR(adaptobs::spectral_radius_bound(huge) / 1.118033988749895e200, 1.0, 1e-12);
  Eigen::Matrix2d nonfinite = Eigen::Matrix2d::Identity();
  nonfinite(0, 1) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(adaptobs::is_schur_stable(Eigen::Matrix2d(0.5 * nonfinite)));
}

// The in-place Cholesky factor of the covariance updates and the Riccati solvers,
// on both sides of the size where it changes loop order (24 rows): a lower
// factor with a positive diagonal that reproduces A (the unique one), and a
// refusal at the first pivot that is not positive.
TEST(Cholesky, BothLoopOrdersGiveTheFactorAndRefuseAnIndefiniteMatrix) {
  RandomMatrices rng(33);
  for (const int n : {3, 24, 25, 40}) {
    const Eigen::MatrixXd a = random_spd(rng, n, 0.1);
    Eigen::MatrixXd l = a;
    ASSERT_TRUE(adaptobs::detail::cholesky_in_place(l)) << n;
    l = Eigen::MatrixXd(l.triangularView<Eigen::Lower>());
    EXPECT_GT(l.diagonal().minCoeff(), 0.0) << n;
    EXPECT_MATRIX_NEAR(Eigen::MatrixXd(l * l.transpose()), a, 1e-13 * a.norm(), 0);
    Eigen::MatrixXd indefinite = a;
    indefinite(n / 2, n / 2) = -1;
    EXPECT_FALSE(adaptobs::detail::cholesky_in_place(indefinite)) << n;
  }
}

// Jacobi eigenvalues of symmetric matrices: against a prescribed spectrum, and to
// full relative accuracy on a graded matrix where only the relative criterion works.
TEST(SymmetricEigenvalues, PrescribedSpectrumAndGradedMatrix) {
  RandomMatrices rng(32);
  for (int n : {1, 2, 4, 7, 15}) {
    const Eigen::MatrixXd q = adaptobs::testing::random_orthogonal(rng, n);
    Eigen::VectorXd spectrum = rng.uniform<Eigen::VectorXd>(n, 1, -5.0, 5.0);
    const Eigen::MatrixXd m = q * spectrum.asDiagonal() * q.transpose();
    std::sort(spectrum.data(), spectrum.data() + n);
    EXPECT_MATRIX_NEAR(adaptobs::symmetric_eigenvalues(m), spectrum, 1e-13, 0.0) << "n=" << n;
  }
  // Fixed size, only the lower triangle read.
  Eigen::Matrix2d lower;
  lower << 2, 99, 1, 2;  // eigenvalues of [[2, 1], [1, 2]]: 1 and 3
  EXPECT_MATRIX_NEAR(adaptobs::symmetric_eigenvalues(lower), Eigen::Vector2d(1, 3), 1e-15, 0.0);
  // Graded diag(1e-20, 1, 1e20) with couplings that a solver with an absolute error
  // of ε‖M‖ could not resolve: the smallest eigenvalue, 1e-20 − 1e-42, keeps full
  // relative accuracy.
  Eigen::Matrix3d graded;
  graded << 1e-20, 1e-21, 0, 1e-21, 1, 1e-5, 0, 1e-5, 1e20;
  const Eigen::Vector3d lambda = adaptobs::symmetric_eigenvalues(graded);
  EXPECT_NEAR(lambda(0) / 1e-20, 1.0, 1e-14);
  EXPECT_NEAR(lambda(1), 1.0, 1e-15);
  EXPECT_NEAR(lambda(2) / 1e20, 1.0, 1e-15);
}

// A non-finite entry anywhere in the lower triangle gives NaN eigenvalues, never
// the diagonal of a matrix whose coupling is unknown: a NaN coupling fails every
// rotation test, so without the check the answer would be the finite diagonal.
TEST(SymmetricEigenvalues, NonFiniteEntryGivesNaN) {
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  for (const double bad : {nan, inf, -inf}) {
    for (const auto& [i, j] : {std::pair{1, 0}, std::pair{2, 1}, std::pair{0, 0}, std::pair{2, 2}}) {
      Eigen::Matrix3d m = Eigen::Vector3d(1, 2, 3).asDiagonal();
      m(i, j) = bad;
      const Eigen::Vector3d lambda = adaptobs::symmetric_eigenvalues(m);
      EXPECT_TRUE(lambda.array().isNaN().all())
          << "entry (" << i << ", " << j << ") = " << bad << ": " << lambda.transpose();
    }
  }
  // Entries near the ends of the range: the rotation test once multiplied two
  // diagonal entries, whose product overflowed beyond 10^154 (no rotation was
  // made, and the diagonal came back as the eigenvalues).
  for (const double scale : {1e-200, 1e155, 1e200}) {
    Eigen::Matrix2d m;
    m << 1, 2, 2, 1;
    EXPECT_MATRIX_NEAR(adaptobs::symmetric_eigenvalues(Eigen::Matrix2d(scale * m)), Eigen::Vector2d(-scale, 3 * scale),
                       0.0, 1e-15)
        << scale;
  }
  // The strict upper triangle is not read.
  Eigen::Matrix2d upper_nan;
  upper_nan << 1, nan, 0, 2;
  EXPECT_MATRIX_NEAR(adaptobs::symmetric_eigenvalues(upper_nan), Eigen::Vector2d(1, 2), 0.0, 0.0);
  // Through the spectral norm, whatever the order of the largest-magnitude scan.
  Eigen::Matrix2d coupled_nan;
  coupled_nan << 1, 0, nan, 2;
  EXPECT_TRUE(std::isnan(adaptobs::spectral_norm(coupled_nan)));
  // NaN beside ∞ is NaN, at fixed and at dynamic size, wherever each one stands.
  for (int nan_at = 0; nan_at < 8; ++nan_at) {
    for (int inf_at = 0; inf_at < 8; ++inf_at) {
      if (nan_at == inf_at) continue;
      Eigen::Matrix<double, 2, 4> m = Eigen::Matrix<double, 2, 4>::Ones();
      m(nan_at) = nan;
      m(inf_at) = inf;
      EXPECT_TRUE(std::isnan(adaptobs::spectral_norm(m))) << nan_at << " " << inf_at;
      EXPECT_TRUE(std::isnan(adaptobs::spectral_norm(Eigen::MatrixXd(m)))) << nan_at << " " << inf_at;
    }
  }
  EXPECT_EQ(adaptobs::spectral_norm(Eigen::Vector3d(1, -inf, 2)), inf);
}

TEST(Validation, PositiveSemidefiniteToleratesRoundingOnly) {
  RandomMatrices rng(33);
  const Eigen::MatrixXd g = rng.uniform<Eigen::MatrixXd>(2, 5);
  const Eigen::MatrixXd rank_two = g.transpose() * g;  // eigenvalues ~ 0 up to rounding
  EXPECT_NO_THROW(adaptobs::require_positive_semidefinite(rank_two, "test", "Q"));
  Eigen::MatrixXd indefinite = rank_two;
  indefinite(4, 4) -= 1e-6 * rank_two.norm();
  const Eigen::MatrixXd q = adaptobs::testing::random_orthogonal(rng, 5);
  const Eigen::MatrixXd rotated = q * Eigen::Vector<double, 5>(1, 2, 3, 4, -1e-6).asDiagonal() * q.transpose();
  EXPECT_THROW(adaptobs::require_positive_semidefinite(rotated, "test", "Q"), ConfigurationError);
  EXPECT_THROW(adaptobs::require_positive_semidefinite(indefinite, "test", "Q"), ConfigurationError);
}

// The coefficients are read as a vector whatever its type: a 1 × 3 MatrixXd
// stopped on an Eigen assertion, a 2 × 2 matrix was read as four coefficients,
// and block_companion_matrix without q (Q dynamic) built a matrix of negative size.
TEST(CompanionMatrix, ReadsAVectorOfAnyShapeAndRefusesAMatrixOrABadBlockSize) {
  Eigen::MatrixXd row(1, 3);
  row << -1, -2, -3;
  Eigen::Matrix3d expected;
  expected << -1, 1, 0, -2, 0, 1, -3, 0, 0;
  EXPECT_MATRIX_NEAR(adaptobs::companion_matrix(row), expected, 0.0, 0.0);
  EXPECT_MATRIX_NEAR(adaptobs::companion_matrix(Eigen::Vector3d(-1, -2, -3)), expected, 0.0, 0.0);
  const Eigen::MatrixXd blocks = adaptobs::block_companion_matrix(row, 2);
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      EXPECT_MATRIX_NEAR(blocks.block(2 * i, 2 * j, 2, 2), expected(i, j) * Eigen::Matrix2d::Identity(), 0.0, 0.0);
    }
  }
  EXPECT_CONFIGURATION_ERROR_NAMES(adaptobs::companion_matrix(Eigen::MatrixXd::Ones(2, 2)), "a");
  EXPECT_CONFIGURATION_ERROR_NAMES(adaptobs::block_companion_matrix(Eigen::MatrixXd::Ones(2, 2), 2), "a");
  EXPECT_CONFIGURATION_ERROR_NAMES(adaptobs::block_companion_matrix(row), "q");
  EXPECT_CONFIGURATION_ERROR_NAMES(adaptobs::block_companion_matrix<2>(row, 3), "q");
}

TEST(ExcitationMonitor, WindowedMinimumEigenvalue) {
  adaptobs::ExcitationMonitor<double, 2> monitor(4);
  const Eigen::RowVector2d e1(1, 0), e2(0, 1);
  monitor.add(e1);
  EXPECT_FALSE(monitor.full());
  monitor.add(e2, 3.0);
  monitor.add(e1);
  monitor.add(e2, 3.0);
  ASSERT_TRUE(monitor.full());
  // (2·e1ᵀe1 + 2·3·e2ᵀe2)/4 = diag(0.5, 1.5)
  EXPECT_NEAR(monitor.level(), 0.5, 1e-15);
  // Only e1 over the last window: the e2 direction is not excited.
  for (int i = 0; i < 4; ++i) monitor.add(e1);
  EXPECT_NEAR(monitor.level(), 0.0, 1e-15);
  EXPECT_MATRIX_NEAR(monitor.average(), Eigen::Matrix2d(Eigen::Vector2d(1, 0).asDiagonal()), 1e-15, 0.0);
  monitor.reset();
  EXPECT_EQ(monitor.count(), 0);
}

// Φ given as an expression without storage is added as its value: a constant Φ
// of dynamic size did not compile (Eigen's product cannot take w·Ones()).
TEST(ExcitationMonitor, ExpressionsWithoutStorageAreAddedAsTheirValues) {
  adaptobs::ExcitationMonitor<double, Eigen::Dynamic> monitor(2, 3);
  monitor.add(Eigen::MatrixXd::Ones(1, 3), 2.0);
  monitor.add(Eigen::MatrixXd::Identity(3, 3) + Eigen::MatrixXd::Zero(3, 3));
  // (2·11ᵀ + I)/2: eigenvalues 3.5, 0.5, 0.5
  const Eigen::Matrix3d expected = (2 * Eigen::Matrix3d::Ones() + Eigen::Matrix3d::Identity()) / 2;
  EXPECT_MATRIX_NEAR(monitor.average(), expected, 1e-15, 0.0);
  EXPECT_NEAR(monitor.level(), 0.5, 1e-15);
}

TEST(ExcitationMonitor, RunningSumDoesNotDrift) {
  RandomMatrices rng(26);
  adaptobs::ExcitationMonitor<double, 3> monitor(7);
  std::vector<Eigen::Matrix<double, 2, 3>> last;
  for (int k = 0; k < 100003; ++k) {
    const Eigen::Matrix<double, 2, 3> phi = rng.uniform<Eigen::Matrix<double, 2, 3>>(2, 3, -1e3, 1e3);
    monitor.add(phi);
    last.push_back(phi);
    if (last.size() > 7) last.erase(last.begin());
  }
  Eigen::Matrix3d expected = Eigen::Matrix3d::Zero();
  for (const auto& phi : last) expected += phi.transpose() * phi;
  EXPECT_MATRIX_NEAR(monitor.average(), Eigen::Matrix3d(expected / 7), 1e-9 * expected.norm(), 0.0);
}

TEST(ExcitationMonitor, AnOverflowingContributionMakesTheLevelUnavailableUntilItLeavesTheWindow) {
  adaptobs::ExcitationMonitor<double, 2> monitor(3);
  const Eigen::RowVector2d e1(1, 0), e2(0, 2);
  monitor.add(e1);
  monitor.add(Eigen::RowVector2d(1e160, 1e160));  // ΦᵀΦ = 1e320: beyond double
  monitor.add(e2);
  ASSERT_TRUE(monitor.full());
  EXPECT_FALSE(monitor.available());
  EXPECT_TRUE(std::isnan(monitor.level()));
  monitor.add(e1);  // window: e1, huge, e2
  EXPECT_FALSE(monitor.available());
  monitor.add(e2);  // window: e1, e2, e2, so (e1ᵀe1 + 2 e2ᵀe2)/3 = diag(1, 8)/3
  ASSERT_TRUE(monitor.available());
  EXPECT_MATRIX_NEAR(monitor.average(), Eigen::Matrix2d(Eigen::Vector2d(1.0 / 3, 8.0 / 3).asDiagonal()), 1e-15, 0.0);
  EXPECT_DOUBLE_EQ(monitor.level(), 1.0 / 3);
}

TEST(ExcitationMonitor, AHugeContributionLeavingTheWindowTakesNoSmallOneWithIt) {
  // While ΦᵀΦ = 1e200·I is in the window, the unit contributions are below the
  // sum's rounding; once it leaves, the level must again be theirs, not 0.
  adaptobs::ExcitationMonitor<double, 2> monitor(5);
  const Eigen::Matrix2d identity = Eigen::Matrix2d::Identity();
  monitor.add(identity);
  monitor.add(1e100 * identity);
  for (int i = 0; i < 5; ++i) monitor.add(identity);  // the huge one has left: window of five I
  EXPECT_MATRIX_NEAR(monitor.average(), identity, 1e-15, 0.0);
  EXPECT_DOUBLE_EQ(monitor.level(), 1.0);

  // Two terms of 1e308·I overflow the sum; the level is back as soon as both have left.
  adaptobs::ExcitationMonitor<double, 2> overflowing(10);
  for (int i = 0; i < 2; ++i) overflowing.add(1e154 * identity);
  EXPECT_FALSE(overflowing.available());
  for (int i = 0; i < 10; ++i) overflowing.add(identity);
  ASSERT_TRUE(overflowing.available());
  EXPECT_DOUBLE_EQ(overflowing.level(), 1.0);

  // Excitation dying out geometrically: at every step the oldest term is 10¹⁰
  // times the newest; the level must follow the window, relative error ≤ 1e-12.
  adaptobs::ExcitationMonitor<double, 2> decaying(6);
  std::vector<Eigen::Matrix2d> last;
  for (int k = 0; k < 40; ++k) {
    const Eigen::Matrix2d phi = std::pow(0.1, k) * Eigen::Vector2d(1, 1 + 0.01 * k).asDiagonal().toDenseMatrix();
    decaying.add(phi);
    last.push_back(phi.transpose() * phi);
    if (last.size() > 6) last.erase(last.begin());
    Eigen::Matrix2d expected = Eigen::Matrix2d::Zero();
    for (const auto& g : last) expected += g;
    expected /= double(last.size());
    EXPECT_NEAR(decaying.level(), expected.diagonal().minCoeff(), 1e-12 * expected.diagonal().minCoeff())
        << "k = " << k;
  }
}

// w·ΦᵀΦ for a tiny w and a huge Φ: ΦᵀΦ = 1e320 overflows, (wΦ)ᵀΦ does not.
// With run-time sizes Eigen's product kernel took w out of (wΦ)ᵀΦ and applied it
// after the overflowing sum: the dynamic monitor reported the level unavailable
// where the fixed-size one reported it.
TEST(ExcitationMonitor, FixedAndRunTimeSizesAgreeWhereThePlainProductWouldOverflow) {
  const Eigen::Matrix2d phi = 1e160 * Eigen::Vector2d(1, 2).asDiagonal().toDenseMatrix();
  for (const double weight : {1e-300, 1e-320}) {
    SCOPED_TRACE(weight);
    adaptobs::ExcitationMonitor<double, 2> fixed(1);
    adaptobs::ExcitationMonitor<double, Eigen::Dynamic> dynamic(1, 2);
    fixed.add(phi, weight);
    dynamic.add(Eigen::MatrixXd(phi), weight);
    ASSERT_TRUE(fixed.available());
    ASSERT_TRUE(dynamic.available());
    // The level is w·1e320; 1e-320 is subnormal, with a relative spacing of 1e-5.
    const double level = weight * 1e160 * 1e160;
    const double tolerance = (weight < 1e-310 ? 1e-4 : 1e-15) * level;
    EXPECT_NEAR(fixed.level(), level, tolerance);
    EXPECT_NEAR(dynamic.level(), level, tolerance);
    EXPECT_NEAR(dynamic.average()(1, 1), 4 * level, 4 * tolerance);
  }
}

TEST(ExcitationMonitor, RefusesWrongColumnsNonFiniteEntriesAndBadWeightsAddingNothing) {
  adaptobs::ExcitationMonitor<double, Eigen::Dynamic> monitor(3, 2);
  monitor.add(Eigen::RowVector2d(1, 0));
  monitor.add(Eigen::RowVector2d(0, 2), 0.5);
  const Eigen::MatrixXd average = monitor.average();
  const auto refused = [&](const Eigen::MatrixXd& phi, double weight, const char* argument) {
    const std::string message = configuration_error_of([&] { monitor.add(phi, weight); });
    EXPECT_NE(message.find(std::string("'") + argument + "'"), std::string::npos) << message;
  };
  refused(Eigen::MatrixXd::Ones(1, 3), 1, "phi");  // Φ must have p = 2 columns
  refused(Eigen::MatrixXd::Ones(2, 1), 1, "phi");
  refused(Eigen::RowVector2d(1, std::numeric_limits<double>::infinity()), 1, "phi");
  refused(Eigen::RowVector2d(1, 1), -1, "weight");
  refused(Eigen::RowVector2d(1, 1), std::nan(""), "weight");
  EXPECT_EQ(monitor.count(), 2);
  EXPECT_TRUE(monitor.average() == average);
  // (e1ᵀe1 + 0.5·4·e2ᵀe2)/2 = diag(0.5, 1)
  EXPECT_DOUBLE_EQ(monitor.level(), 0.5);
  // A run-time count that contradicts the compile-time one.
  const std::string message = configuration_error_of([] { adaptobs::ExcitationMonitor<double, 2> fixed(5, 3); });
  EXPECT_NE(message.find("'np'"), std::string::npos) << message;
}

}  // namespace
