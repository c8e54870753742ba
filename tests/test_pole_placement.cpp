// Eigenvalue assignment and the linear-algebra tools behind it: the Sylvester
// solver, the observability staircase, output-injection and state-feedback
// placement (random cases, complex and repeated poles, poles on open-loop
// eigenvalues, unobservable pairs), and exponential power bounds.

#include <adaptobs/core/sylvester.hpp>
#include <adaptobs/design/observability.hpp>
#include <adaptobs/design/pole_placement.hpp>
#include <adaptobs/design/power_bound.hpp>
#include <adaptobs/design/stability.hpp>

#include "support/eigen_testing.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <string>
#include <utility>
#include <vector>

namespace {

using adaptobs::ConfigurationError;
using adaptobs::testing::RandomMatrices;
using Eigen::MatrixXd;
using Eigen::VectorXd;
using ComplexVector = Eigen::VectorXcd;

using adaptobs::testing::configuration_error_of;
using adaptobs::testing::random_orthogonal;

// Conjugate-closed random poles in the disk of radius 0.9, pairwise at least `gap` apart.
ComplexVector random_poles(RandomMatrices& rng, int n, double gap = 0.1) {
  for (;;) {
    std::vector<std::complex<double>> p;
    while (int(p.size()) < n) {
      if (n - int(p.size()) >= 2 && rng.scalar(0, 1) < 0.4) {
        const std::complex<double> z = std::polar(0.9 * std::sqrt(rng.scalar(0, 1)), rng.scalar(0.2, 2.9));
        p.push_back(z);
        p.push_back(std::conj(z));
      } else {
        p.emplace_back(rng.scalar(-0.9, 0.9), 0.0);
      }
    }
    bool separated = true;
    for (std::size_t i = 0; i < p.size(); ++i)
      for (std::size_t j = i + 1; j < p.size(); ++j) separated = separated && std::abs(p[i] - p[j]) > gap;
    if (separated) return Eigen::Map<ComplexVector>(p.data(), n);
  }
}

// ---- Sylvester ----------------------------------------------------------------

TEST(Sylvester, RandomEquationsHaveSmallResiduals) {
  RandomMatrices rng(401);
  for (int n : {1, 2, 5, 9}) {
    for (int m : {1, 3, 7}) {
      const MatrixXd a = rng.uniform<MatrixXd>(n, n), b = rng.uniform<MatrixXd>(m, m) + 3 * MatrixXd::Identity(m, m);
      const MatrixXd c = rng.uniform<MatrixXd>(n, m);
      const MatrixXd x = adaptobs::solve_sylvester(a, b, c);
      EXPECT_LE((a * x + x * b - c).norm(), 1e-12 * (1 + x.norm())) << "n=" << n << " m=" << m;
    }
  }
}

TEST(Sylvester, SharedEigenvalueOfAAndMinusBIsRejected) {
  Eigen::Matrix2d a;
  a << 1, 2, 0, 3;
  const Eigen::Matrix2d b = -a.transpose();  // eigenvalues −1, −3: A and −B share both
  EXPECT_NE(configuration_error_of([&] {
              (void)adaptobs::solve_sylvester(a, b, Eigen::Matrix2d::Identity());
            }).find("'A, B'"),
            std::string::npos);
}

// Entries beyond 10^154: ‖A‖_F once overflowed, the separation read 0, and a
// well-posed equation was refused as singular. Small entries: the separation
// was once measured against max(1, ‖A‖_F), and read 0 below 10^-15. The
// equation is the same at every scale s: X = [[1/2, 1/3], [1/3, 1/4]].
TEST(Sylvester, EntriesAtEitherEndOfTheRangeAreSolved) {
  for (const double s : {1e-200, 1e-20, 1e160, 1e200}) {
    const Eigen::Matrix2d a = s * Eigen::Vector2d(1, 2).asDiagonal();
    const Eigen::Matrix2d c = s * Eigen::Matrix2d::Ones();
    const Eigen::Matrix2d x = adaptobs::solve_sylvester(a, a, c);
    Eigen::Matrix2d expected;
    expected << 0.5, 1.0 / 3, 1.0 / 3, 0.25;
    EXPECT_MATRIX_NEAR(x, expected, 0.0, 1e-14) << s;
  }
}

// ---- Observability ---------------------------------------------------------------

TEST(Observability, RandomPairsAreObservable) {
  RandomMatrices rng(402);
  for (int n : {1, 3, 6}) {
    const auto report = adaptobs::observability(rng.uniform<MatrixXd>(n, n), rng.uniform<MatrixXd>(1, n));
    EXPECT_TRUE(report.observable());
    EXPECT_EQ(report.observable_dimension, n);
  }
}

// Observability does not depend on the units of the output or of time. With
// C × 1e-12 every singular value of C once fell below the yardstick
// max(1, ||A||_F, ||C||_F) and the pair read unobservable (dimension 0), with
// A × 1e-9 too, and so did a chain seen through C × 1e-12. A row of C that is
// subnormal, or whose norm overflows, counts like any other, in double and
// float alike (the float tolerance is sqrt(eps), not 1e6 eps = 0.12).
TEST(Observability, BadlyScaledObservablePairsAreObservable) {
  MatrixXd a(3, 3), c(1, 3);
  a << 0.5, 1, 0, -0.3, 0.2, 1, 0.1, 0, -0.4;
  c << 1, 0, 0;
  for (const auto& [aa, cc] : {std::pair{a, MatrixXd(1e-12 * c)}, std::pair{a, MatrixXd(1e12 * c)},
                               std::pair{MatrixXd(1e-9 * a), c}, std::pair{MatrixXd(1e-9 * a), MatrixXd(1e-12 * c)}}) {
    const auto report = adaptobs::observability(aa, cc);
    EXPECT_TRUE(report.observable());
    EXPECT_EQ(report.observable_dimension, 3);
  }
  MatrixXd chain = MatrixXd::Zero(5, 5), last = MatrixXd::Zero(1, 5);
  for (Eigen::Index i = 0; i < 5; ++i) chain(i, i) = -std::pow(10.0, double(i));
  for (Eigen::Index i = 0; i + 1 < 5; ++i) chain(i + 1, i) = 1;  // x_{i+1}' = -r x_{i+1} + x_i
  last(0, 4) = 1;
  EXPECT_EQ(adaptobs::observability(chain, last).observable_dimension, 5);
  EXPECT_EQ(adaptobs::observability(chain, MatrixXd(1e-12 * last)).observable_dimension, 5);
  // Cut the chain after the second state: the first two modes stay hidden at
  // every scale of C, and are reported to rounding.
  chain(2, 1) = 0;
  for (const double s : {1.0, 1e-12, 1e12}) {
    const auto report = adaptobs::observability(chain, MatrixXd(s * last));
    EXPECT_EQ(report.observable_dimension, 3) << s;
    ASSERT_EQ(report.unobservable_modes.size(), 2) << s;
    std::vector<double> modes{report.unobservable_modes(0).real(), report.unobservable_modes(1).real()};
    std::sort(modes.begin(), modes.end());
    EXPECT_NEAR(modes[0], -10.0, 1e-12) << s;
    EXPECT_NEAR(modes[1], -1.0, 1e-12) << s;
  }
  // An unobservable pair in other units stays unobservable.
  Eigen::Matrix2d lower;
  lower << 0, 0, 1, 0;
  for (const double s : {1e-12, 1e12})
    EXPECT_EQ(adaptobs::observability(lower, Eigen::RowVector2d(s, 0)).observable_dimension, 1) << s;
  // Rows at the ends of the range: each output is judged in its own units.
  Eigen::Matrix2d graded;
  graded << -1, 0, 1, -2;
  for (const double s : {1e-310, 1.5e308})
    EXPECT_EQ(adaptobs::observability(graded, Eigen::RowVector2d(0, s)).observable_dimension, 2) << s;
  EXPECT_EQ(
      adaptobs::observability(Eigen::Matrix2d::Zero().eval(), Eigen::Matrix2d(Eigen::Vector2d(1, 1e-310).asDiagonal()))
          .observable_dimension,
      2);
  Eigen::Matrix2f weak;
  weak << -1, 0.05f, 0, -2;
  EXPECT_EQ(adaptobs::observability(weak, Eigen::RowVector2f(1, 0)).observable_dimension, 2);
  EXPECT_EQ(adaptobs::observability(Eigen::Matrix2f(Eigen::Vector2f(-1, -2).asDiagonal()), Eigen::RowVector2f(1, 0))
                .observable_dimension,
            1);
}

// A state that reaches the output only through a coupling far below the data,
// with no coupling back, is not observable in any useful sense: moving its mode
// takes a gain of the coupling's inverse size. The staircase does not rescale
// the states (that would make a coupling of 1e-300 count), and placement names
// the true reason.
TEST(Observability, ACouplingFarBelowTheDataIsNoObservability) {
  for (const double eps : {1e-17, 1e-100, 1e-300}) {
    Eigen::Matrix2d a;
    a << -1, eps, 0, -2;  // x2 reaches y = x1 only through eps
    const Eigen::RowVector2d c(1, 0);
    const auto report = adaptobs::observability(a, c);
    EXPECT_EQ(report.observable_dimension, 1) << eps;
    ASSERT_EQ(report.unobservable_modes.size(), 1) << eps;
    EXPECT_EQ(report.unobservable_modes(0).real(), -2.0) << eps;
    EXPECT_CONFIGURATION_ERROR_NAMES(
        (void)adaptobs::place_output_injection(a, c, Eigen::Vector2d(-3, -4).cast<std::complex<double>>().eval()),
        "A, C");
  }
}

// A pair built with a hidden mode, disguised by a random orthogonal change of basis.
TEST(Observability, StaircaseFindsHiddenModesThatEigenvalueTestsMiss) {
  RandomMatrices rng(403);
  // Observable part (2 states) and an unobservable 3-state Jordan block at 0.7
  // (defective: its computed eigenvalues are only accurate to ε^(1/3)).
  MatrixXd a = MatrixXd::Zero(5, 5);
  a.topLeftCorner(2, 2) << 0.3, 1.0, -0.4, 0.1;
  a.bottomRightCorner(3, 3) << 0.7, 1, 0, 0, 0.7, 1, 0, 0, 0.7;
  a.bottomLeftCorner(3, 2) = rng.uniform<MatrixXd>(3, 2);  // the hidden part is driven, but never seen
  MatrixXd c = MatrixXd::Zero(2, 5);
  c.leftCols(2) = rng.uniform<MatrixXd>(2, 2);
  const MatrixXd q = random_orthogonal(rng, 5);
  const auto report = adaptobs::observability(MatrixXd(q.transpose() * a * q), MatrixXd(c * q));
  EXPECT_FALSE(report.observable());
  EXPECT_EQ(report.observable_dimension, 2);
  ASSERT_EQ(report.unobservable_modes.size(), 3);
  for (Eigen::Index i = 0; i < 3; ++i) EXPECT_NEAR(std::abs(report.unobservable_modes(i) - 0.7), 0.0, 1e-4);
  // The exact PBH test at the known mode sees it too; at another point it does not.
  EXPECT_LT(adaptobs::pbh_margin(MatrixXd(q.transpose() * a * q), MatrixXd(c * q), 0.7), 1e-14);
  const double margin = adaptobs::pbh_margin(MatrixXd(q.transpose() * a * q), MatrixXd(c * q), 0.2);
  EXPECT_GT(margin, 1e-3);
  // Outputs in other units (C scaled row by row) leave the margin as it is:
  // exactly for powers of two, within the power of two the scaling rounds to otherwise.
  const Eigen::Vector2d units(std::ldexp(1.0, -40), std::ldexp(1.0, 30));
  EXPECT_EQ(adaptobs::pbh_margin(MatrixXd(q.transpose() * a * q), MatrixXd(units.asDiagonal() * c * q), 0.2), margin);
  const double tiny_units = adaptobs::pbh_margin(MatrixXd(q.transpose() * a * q), MatrixXd(1e-9 * c * q), 0.2);
  EXPECT_GT(tiny_units, margin / 4);
  EXPECT_LT(tiny_units, margin * 4);
  EXPECT_LT(adaptobs::pbh_margin(MatrixXd(q.transpose() * a * q), MatrixXd(1e-9 * c * q), 0.7), 1e-14);
  // Non-finite data is refused by name: the SVD of a NaN matrix fails, and its
  // unwritten singular values were read as the margin.
  const double nan = std::numeric_limits<double>::quiet_NaN();
  MatrixXd a_nan = a, c_inf = c;
  a_nan(4, 1) = nan;
  c_inf(1, 0) = std::numeric_limits<double>::infinity();
  EXPECT_CONFIGURATION_ERROR_NAMES(adaptobs::pbh_margin(a_nan, c, 0.7), "A");
  EXPECT_CONFIGURATION_ERROR_NAMES(adaptobs::pbh_margin(a, c_inf, 0.7), "C");
  EXPECT_CONFIGURATION_ERROR_NAMES(adaptobs::pbh_margin(a, c, nan), "mu");
}

// ---- Output injection ----------------------------------------------------------------

TEST(PolePlacement, CharacteristicPolynomialAndSpreadPoles) {
  const VectorXd q = adaptobs::polynomial_from_roots(Eigen::Vector3d(0.5, 0.6, 0.2));
  EXPECT_MATRIX_NEAR(q, Eigen::Vector4d(1, -1.3, 0.52, -0.06), 1e-15, 0);
  const ComplexVector pair =
      (Eigen::Vector2cd() << std::complex<double>(0.5, 0.2), std::complex<double>(0.5, -0.2)).finished();
  EXPECT_MATRIX_NEAR(adaptobs::polynomial_from_roots(pair), Eigen::Vector3d(1, -1.0, 0.29), 1e-15, 0);
  EXPECT_MATRIX_NEAR(adaptobs::spread_poles<double>(4, 0.8), Eigen::Vector4d(0.8, 0.6, 0.4, 0.2), 1e-15, 0);
}

// Every random observable pair gets its spectrum, certified, for m = 1..3 outputs.
TEST(PolePlacement, RandomObservablePairsGetTheRequestedSpectrum) {
  RandomMatrices rng(404);
  int cases = 0, well_conditioned = 0;
  for (int n = 1; n <= 8; ++n) {
    for (int m = 1; m <= 3; ++m) {
      for (int rep = 0; rep < 3; ++rep) {
        const MatrixXd a = rng.uniform<MatrixXd>(n, n) * 1.5;
        const MatrixXd c = rng.uniform<MatrixXd>(m, n);
        const ComplexVector poles = random_poles(rng, n);
        const auto placed = adaptobs::place_output_injection(a, c, poles);
        const MatrixXd closed = a - placed.L * c;
        EXPECT_LE(adaptobs::cayley_hamilton_residual(closed, poles), 1e-11) << "n=" << n << " m=" << m;
        EXPECT_LE(placed.cayley_hamilton_residual, 1e-11);
        // The eigenvalues themselves are as accurate as their conditioning allows.
        if (placed.transformation_condition < 1e5) {
          ++well_conditioned;
          EXPECT_LE(adaptobs::eigenvalue_mismatch(closed, poles), 1e-9) << "n=" << n << " m=" << m;
        }
        ++cases;
      }
    }
  }
  EXPECT_EQ(cases, 72);
  EXPECT_GE(well_conditioned, 60) << "too few well-conditioned cases: the eigenvalue check has no power";
}

// More outputs give freedom; the best-conditioned draw is kept, so more draws never hurt.
TEST(PolePlacement, MoreDrawsGiveBetterConditionedGains) {
  RandomMatrices rng(405);
  const MatrixXd a = rng.uniform<MatrixXd>(6, 6) * 1.5, c = rng.uniform<MatrixXd>(3, 6);
  const ComplexVector poles = random_poles(rng, 6);
  adaptobs::PolePlacementOptions one{.tries = 1}, many{.tries = 40};
  const auto p1 = adaptobs::place_output_injection(a, c, poles, one);
  const auto p40 = adaptobs::place_output_injection(a, c, poles, many);
  EXPECT_LE(p40.transformation_condition, p1.transformation_condition);
  EXPECT_LE(p40.eigenvalue_mismatch, 1e-10);
}

TEST(PolePlacement, RepeatedPolesAndDeadbeat) {
  RandomMatrices rng(406);
  const MatrixXd a = rng.uniform<MatrixXd>(4, 4), c = rng.uniform<MatrixXd>(1, 4);
  // Deadbeat with one output: a single Jordan block at 0, so (A − LC)⁴ = 0.
  const auto deadbeat = adaptobs::place_output_injection(a, c, Eigen::Vector4d::Zero());
  const MatrixXd closed = a - deadbeat.L * c;
  EXPECT_LE((closed * closed * closed * closed).norm(), 1e-10 * std::pow(closed.norm(), 4));
  // A repeated complex pair.
  const std::complex<double> z(0.3, 0.4);
  const ComplexVector twice = (Eigen::Vector4cd() << z, std::conj(z), z, std::conj(z)).finished();
  const auto placed = adaptobs::place_output_injection(a, c, twice);
  EXPECT_LE(adaptobs::cayley_hamilton_residual(MatrixXd(a - placed.L * c), twice), 1e-11);
  // A matrix with a NaN has no known spectrum: an infinite residual, never 0.
  MatrixXd not_finite = a - placed.L * c;
  not_finite(2, 3) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(adaptobs::cayley_hamilton_residual(not_finite, twice), std::numeric_limits<double>::infinity());
}

// A requested pole equal to an eigenvalue of A makes the Sylvester equation
// singular; the placer first moves A by a random injection.
TEST(PolePlacement, PoleOnAnOpenLoopEigenvalue) {
  Eigen::Matrix3d a;
  a << 0.5, 1, 0, 0, 0.2, 1, 0.1, 0, -0.3;
  const Eigen::RowVector3d c(1, 0, 0);
  const adaptobs::ComplexVector<double> ev = adaptobs::eigenvalues(a);
  const Eigen::Vector3d poles(ev(0).real(), 0.1, -0.1);  // the real eigenvalue of A
  ASSERT_NEAR(ev(0).imag(), 0.0, 1e-15);
  const auto placed = adaptobs::place_output_injection(a, c, poles);
  EXPECT_LE(adaptobs::eigenvalue_mismatch(Eigen::Matrix3d(a - placed.L * c), poles.cast<std::complex<double>>()),
            1e-12);
}

// Ten poles 0.01 apart for a pair with ‖A‖_F ≈ 100 (n = 10, m = 2): the
// Sylvester transformation has cond(X) ≈ 10¹³, and the rounding of L moves
// these eigenvalues by up to 0.1, out of the unit circle for the discrete set.
// The Cayley–Hamilton residual cannot see it: its normalizer
// Σ|q_i|‖A − LC‖_F^{N−i} is about 10²⁰. A returned gain keeps the requested
// stability region and places each simple pole within √ε‖A − LC‖_F; the other
// requests are refused as too clustered for the pair.
TEST(PolePlacement, PolesTooClusteredForThePairAreRefused) {
  RandomMatrices rng(400);
  const double tolerance = std::sqrt(std::numeric_limits<double>::epsilon());
  int refused_as_clustered = 0;
  for (int draw = 0; draw < 4; ++draw) {
    const MatrixXd a = rng.uniform<MatrixXd>(10, 10) * 17, c = rng.uniform<MatrixXd>(2, 10);
    for (const bool discrete : {true, false}) {
      VectorXd poles(10);
      for (int i = 0; i < 10; ++i) poles(i) = discrete ? 0.90 + 0.01 * i : -1.0 - 0.01 * i;
      const std::string message = configuration_error_of([&] {
        const auto placed = adaptobs::place_output_injection(a, c, poles);
        const MatrixXd closed = a - placed.L * c;
        if (discrete)
          EXPECT_LT(adaptobs::spectral_radius(closed), 1.0)
              << "draw " << draw << ": every pole is inside the unit circle";
        else
          EXPECT_LT(adaptobs::spectral_abscissa(closed), 0.0)
              << "draw " << draw << ": every pole is in the left half-plane";
        EXPECT_LE(placed.eigenvalue_mismatch, tolerance * closed.norm())
            << "draw " << draw << (discrete ? " (discrete)" : " (continuous)");
      });
      if (message == "<no exception>") continue;
      EXPECT_NE(message.find("'poles'"), std::string::npos) << message;
      if (message.find("too clustered") != std::string::npos) ++refused_as_clustered;
    }
  }
  EXPECT_GE(refused_as_clustered, 4);
}

// A tenfold pole is only placed to about τ^(1/10)‖A − LC‖_F (here 0.165‖A − LC‖_F,
// wider than the distance 0.05 from 0.95 to the unit circle): for this pair the
// eigenvalues of A − LC spread to a spectral radius near 1.1. A repeated pole
// inside the unit circle is refused when its placed eigenvalues leave it; the
// same pole at −1, whose spread stays in the left half-plane, is placed.
TEST(PolePlacement, RepeatedPoleLeavingItsStabilityRegionIsRefused) {
  RandomMatrices rng(400);
  const MatrixXd a = rng.uniform<MatrixXd>(10, 10) * 17, c = rng.uniform<MatrixXd>(2, 10);
  const std::string message = configuration_error_of([&] {
    const auto placed = adaptobs::place_output_injection(a, c, VectorXd::Constant(10, 0.95));
    EXPECT_LT(adaptobs::spectral_radius(MatrixXd(a - placed.L * c)), 1.0) << "every pole is inside the unit circle";
  });
  EXPECT_NE(message.find("'poles'"), std::string::npos) << message;
  EXPECT_NE(message.find("spectral radius"), std::string::npos) << message;
  const auto hurwitz = adaptobs::place_output_injection(a, c, VectorXd::Constant(10, -1.0));
  const MatrixXd closed = a - hurwitz.L * c;
  EXPECT_LT(adaptobs::spectral_abscissa(closed), 0.0);
  EXPECT_LE(hurwitz.eigenvalue_mismatch,
            std::pow(std::sqrt(std::numeric_limits<double>::epsilon()), 0.1) * closed.norm());
}

TEST(PolePlacement, FixedAndDynamicSizesAgree) {
  RandomMatrices rng(407);
  const Eigen::Matrix<double, 4, 4> a = rng.uniform<Eigen::Matrix<double, 4, 4>>();
  const Eigen::Matrix<double, 2, 4> c = rng.uniform<Eigen::Matrix<double, 2, 4>>();
  const Eigen::Vector4d poles(0.1, -0.2, 0.3, 0.5);
  const auto fixed = adaptobs::place_output_injection(a, c, poles);
  const auto dynamic = adaptobs::place_output_injection(MatrixXd(a), MatrixXd(c), VectorXd(poles));
  static_assert(decltype(fixed.L)::RowsAtCompileTime == 4 && decltype(fixed.L)::ColsAtCompileTime == 2);
  EXPECT_MATRIX_NEAR(fixed.L, dynamic.L, 1e-13, 1e-13);
}

TEST(PolePlacement, StateFeedbackByDuality) {
  RandomMatrices rng(408);
  const MatrixXd a = rng.uniform<MatrixXd>(5, 5) * 1.5, b = rng.uniform<MatrixXd>(5, 2);
  const ComplexVector poles = random_poles(rng, 5);
  const auto k = adaptobs::place_state_feedback(a, b, poles);
  EXPECT_EQ(k.K.rows(), 2);
  EXPECT_LE(adaptobs::eigenvalue_mismatch(MatrixXd(a - b * k.K), poles), 1e-9);
  // An uncontrollable pair: the third state is not reached by the input.
  MatrixXd a3 = MatrixXd::Zero(3, 3), b3 = MatrixXd::Zero(3, 1);
  a3 << 0.5, 1, 0, 0, 0.4, 0, 0, 0, 0.9;
  b3 << 0, 1, 0;
  const std::string message =
      configuration_error_of([&] { (void)adaptobs::place_state_feedback(a3, b3, Eigen::Vector3d(0.1, 0.2, 0.3)); });
  EXPECT_NE(message.find("'A, B' is not controllable"), std::string::npos) << message;
  EXPECT_NE(message.find("0.9"), std::string::npos) << message;
  // A non-finite B is named B, not the C of the dual problem solved for it.
  b3(2, 0) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_CONFIGURATION_ERROR_NAMES(adaptobs::place_state_feedback(a3, b3, Eigen::Vector3d(0.1, 0.2, 0.3)), "B");
}

// The gains of a pair with its output in units 1e12 times too large are
// 1e12 times larger, and place the same poles (the pair was refused as
// unobservable). The same for the dual state feedback with B × 1e-12.
TEST(PolePlacement, OutputInOtherUnitsIsPlaced) {
  MatrixXd a(3, 3), c(1, 3);
  a << 0.5, 1, 0, -0.3, 0.2, 1, 0.1, 0, -0.4;
  c << 1, 0, 0;
  const Eigen::Vector3d poles(-1, -2, -3);
  const auto reference = adaptobs::place_output_injection(a, c, poles);
  const auto scaled = adaptobs::place_output_injection(a, MatrixXd(1e-12 * c), poles);
  EXPECT_MATRIX_NEAR(MatrixXd(1e-12 * scaled.L), MatrixXd(reference.L), 0, 1e-12);
  EXPECT_LE(adaptobs::eigenvalue_mismatch(MatrixXd(a - scaled.L * (1e-12 * c)),
                                          ComplexVector(poles.cast<std::complex<double>>())),
            1e-9);
  EXPECT_LE(scaled.eigenvalue_mismatch, 1e-9);
  const auto feedback = adaptobs::place_state_feedback(a, MatrixXd(1e-12 * c.transpose()), poles);
  EXPECT_LE(adaptobs::eigenvalue_mismatch(MatrixXd(a - 1e-12 * c.transpose() * feedback.K),
                                          ComplexVector(poles.cast<std::complex<double>>())),
            1e-9);
  // Unobservable in any units: still refused, with the hidden mode.
  Eigen::Matrix2d lower;
  lower << 0, 0, 1, 0.3;  // x1' = 0, x2' = x1 + 0.3 x2: C = (1e-12 0) never sees x2
  const std::string message = configuration_error_of(
      [&] { (void)adaptobs::place_output_injection(lower, Eigen::RowVector2d(1e-12, 0), Eigen::Vector2d(0.1, 0.2)); });
  EXPECT_NE(message.find("'A, C' is not observable"), std::string::npos) << message;
  EXPECT_NE(message.find("0.3"), std::string::npos) << message;

  // Two outputs in units 2^40 apart get the design of common units, L's column
  // scaled back exactly; 1e9 apart, one as well conditioned, not a design that
  // leans on the larger output alone.
  RandomMatrices rng(11);
  const MatrixXd a2 = 0.5 * rng.uniform<MatrixXd>(6, 6), c2 = rng.uniform<MatrixXd>(2, 6);
  const Eigen::VectorXd poles2 = Eigen::VectorXd::LinSpaced(6, 0.1, 0.6);
  const auto common = adaptobs::place_output_injection(a2, c2, poles2);
  const Eigen::Vector2d units(1.0, std::ldexp(1.0, -40));
  const auto apart = adaptobs::place_output_injection(a2, MatrixXd(units.asDiagonal() * c2), poles2);
  EXPECT_TRUE(MatrixXd(apart.L * units.asDiagonal()) == common.L);
  const auto nano = adaptobs::place_output_injection(a2, MatrixXd(Eigen::Vector2d(1, 1e-9).asDiagonal() * c2), poles2);
  EXPECT_LT(nano.transformation_condition, 2 * common.transformation_condition);
  EXPECT_LE(nano.eigenvalue_mismatch, 1e-9);
}

TEST(PolePlacement, BadArgumentsAreNamed) {
  Eigen::Matrix2d a;
  a << 0, 0, 1, 0;
  // C = (1 0) does not see the second state of this lower-shift A.
  const std::string unobservable = configuration_error_of(
      [&] { (void)adaptobs::place_output_injection(a, Eigen::RowVector2d(1, 0), Eigen::Vector2d(0.1, 0.2)); });
  EXPECT_NE(unobservable.find("'A, C' is not observable"), std::string::npos) << unobservable;
  const Eigen::RowVector2d c(0, 1);
  const ComplexVector lonely = (Eigen::Vector2cd() << std::complex<double>(0.1, 0.2), 0.3).finished();
  EXPECT_NE(configuration_error_of([&] { (void)adaptobs::place_output_injection(a, c, lonely); }).find("conjugation"),
            std::string::npos);
  EXPECT_NE(configuration_error_of([&] {
              (void)adaptobs::place_output_injection(a, c, Eigen::Vector3d(0, 0, 0));
            }).find("'poles'"),
            std::string::npos);
  EXPECT_NE(configuration_error_of([&] {
              (void)adaptobs::place_output_injection(a, c, Eigen::Vector2d(0.1, std::nan("")));
            }).find("'poles'"),
            std::string::npos);
  for (const double tau : {-1e-3, 1.0, std::nan("")}) {
    const std::string message = configuration_error_of([&] {
      (void)adaptobs::place_output_injection(a, c, Eigen::Vector2d(0.1, 0.2), {.eigenvalue_tolerance = tau});
    });
    EXPECT_NE(message.find("'options.eigenvalue_tolerance'"), std::string::npos) << message;
  }
}

// ---- Power bounds ------------------------------------------------------------------

// sup_k ‖U^k‖/λ^k = sup_k ‖(U/λ)^k‖ by brute force over many powers.
double brute_force_constant(const MatrixXd& u, double lambda, int powers) {
  MatrixXd p = MatrixXd::Identity(u.rows(), u.cols());
  double m = 1;
  for (int k = 1; k <= powers; ++k) {
    p = (p * u / lambda).eval();
    m = std::max(m, adaptobs::detail::largest_singular_value(p));
  }
  return m;
}

TEST(PowerBound, MatchesBruteForceSupremum) {
  // A symmetric matrix has ‖U^k‖ = ρ^k: M = 1 for every λ ≥ ρ.
  Eigen::Matrix2d sym;
  sym << 0.5, 0.2, 0.2, 0.3;
  EXPECT_DOUBLE_EQ(adaptobs::power_bound_constant(sym, 0.7), 1.0);
  // A Jordan-like block has transient growth.
  Eigen::Matrix2d jordan;
  jordan << 0.6, 2.0, 0.0, 0.5;
  for (double lambda : {0.65, 0.8, 0.95}) {
    const double m = adaptobs::power_bound_constant(jordan, lambda);
    EXPECT_NEAR(m, brute_force_constant(jordan, lambda, 3000), 1e-12 * m) << "lambda=" << lambda;
  }
  EXPECT_TRUE(std::isinf(adaptobs::power_bound_constant(jordan, 0.55)));  // λ < ρ: no bound
  // The best margin beats every point of a fine scan.
  const auto best = adaptobs::best_power_bound(jordan);
  ASSERT_TRUE(best.has_value());
  for (double lambda = 0.601; lambda < 1.0; lambda += 0.001)
    EXPECT_GE(best->perturbation_margin() * (1 + 1e-6), (1 - lambda) / adaptobs::power_bound_constant(jordan, lambda))
        << "lambda=" << lambda;
  EXPECT_FALSE(adaptobs::best_power_bound(Eigen::Matrix2d(jordan * 2)).has_value());  // not Schur
}

}  // namespace
