// Gain design and convergence diagnostic of the continuous-discrete adaptive
// observer of Guiro, Iggidr, Ngom, Touré (Guiro et al. 2008): the paper's example and
// its printed gains, closed forms, random MIMO cases, cases without solution,
// and proposition 2.2 (the observer itself is tested in test_guiro.cpp).

#include <adaptobs/core/matrix_exponential.hpp>
#include <adaptobs/design/dense_eigenvalues.hpp>
#include <adaptobs/design/guiro_convergence.hpp>
#include <adaptobs/design/guiro_gains.hpp>
#include <adaptobs/design/stability.hpp>

#include "guiro_paper_fixture.hpp"
#include "models/guiro.hpp"
#include "support/eigen_testing.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <string>
#include <vector>

namespace {

namespace g = adaptobs::examples::guiro;
using adaptobs::ConditionVerdict;
using adaptobs::Index;
using adaptobs::testing::bitwise_equal;
using adaptobs::testing::configuration_error_of;
using adaptobs::testing::RandomMatrices;
using adaptobs::testing::guiro::Paper;
using adaptobs::testing::guiro::paper_gains;
using Eigen::MatrixXd;

Eigen::Matrix3d error_matrix(const Eigen::Vector2d& K, double gamma, const Eigen::Vector2d& Hbar) {
  const Paper paper;
  return adaptobs::guiro_error_matrix(paper.E, paper.C, Hbar, K, Eigen::Matrix<double, 1, 1>(gamma));
}

Eigen::Vector3cd sorted_eigenvalues(const Eigen::Matrix3d& u) {
  Eigen::Vector3cd e = adaptobs::detail::dense_eigenvalues<double>(MatrixXd(u));
  std::sort(e.data(), e.data() + 3,
            [](auto a, auto b) { return a.real() != b.real() ? a.real() < b.real() : a.imag() < b.imag(); });
  return e;
}

// ---- Gain design ------------------------------------------------------------------

TEST(GuiroDesign, PaperGainsAreTheExactOnes) {
  const auto gains = paper_gains();
  EXPECT_MATRIX_NEAR(gains.K, Eigen::Vector2d(0.8436768964665971, 0.8563231035334029), 0, 1e-12);
  EXPECT_NEAR(gains.Gamma(0, 0), 1.873077283794877, 1e-12 * 1.873077283794877);
  EXPECT_MATRIX_NEAR(gains.L, Eigen::Vector3d(0.8436768964665971, 1.7, 0.2691179309777314), 1e-12, 0);
  // charpoly(U) = (z − 1/2)(z − 3/5)(z − 1/5) = z³ − 1.3z² + 0.52z − 0.06.
  const Eigen::Matrix3d u = gains.U;
  const double trace = u.trace(), det = u.determinant();
  const double minors = (trace * trace - (u * u).trace()) / 2;
  EXPECT_NEAR(trace, 1.3, 1e-12);
  EXPECT_NEAR(minors, 0.52, 1e-12);
  EXPECT_NEAR(det, 0.06, 1e-12);
  EXPECT_LE((sorted_eigenvalues(u) - Eigen::Vector3cd(0.2, 0.5, 0.6)).cwiseAbs().maxCoeff(), 1e-10);
  EXPECT_LE(gains.eigenvalue_mismatch, 1e-9);
  EXPECT_NEAR(gains.spectral_radius, 0.6, 1e-10);
}

// For n = 2, m = p = 1 the design has a closed form (l₃ = Q(1)/(aT),
// l₂ = Σ(1 − λᵢ), l₁ = (Q'(1) − (Ta + b)l₃)/T, K = (l₁, l₂ − Tl₁),
// Γ = Q(1)/(aTΠλᵢ − bQ(1))): the numerical design reproduces it.
TEST(GuiroDesign, ReproducesTheClosedFormForOtherSpectraAndPeriods) {
  struct Case {
    double T;
    std::vector<std::complex<double>> poles;
  };
  const std::complex<double> z(0.5, 0.2);
  for (const Case& c : {Case{1.0, {0.9, 0.8, 0.7}}, Case{1.0, {z, std::conj(z), 0.3}}, Case{0.5, {0.5, 0.6, 0.2}},
                        Case{2.0, {-0.4, 0.1, 0.3}}}) {
    const double T = c.T;
    const Eigen::Vector2d h0 = g::closed_form_H<double>(0, T);
    const double a = h0(0), b = h0(1);
    std::complex<double> q1 = 1, dq1 = 0, product = 1, sum = 0;
    for (std::size_t i = 0; i < 3; ++i) {
      std::complex<double> others = 1;
      for (std::size_t j = 0; j < 3; ++j)
        if (j != i) others *= 1.0 - c.poles[j];
      q1 *= 1.0 - c.poles[i];
      dq1 += others;
      product *= c.poles[i];
      sum += 1.0 - c.poles[i];
    }
    const double l3 = q1.real() / (a * T), l2 = sum.real(), l1 = (dq1.real() - (T * a + b) * l3) / T;
    const Eigen::Vector2d k(l1, l2 - T * l1);
    const double gamma = q1.real() / (a * T * product.real() - b * q1.real());
    const Eigen::Vector3cd poles = Eigen::Map<const Eigen::Vector3cd>(c.poles.data());
    const auto gains =
        adaptobs::design_guiro_gains(g::model<double>(T).system().A, g::output_matrix<double>(), h0, poles);
    EXPECT_MATRIX_NEAR(gains.K, k, 1e-11, 1e-11) << "T=" << T;
    EXPECT_NEAR(gains.Gamma(0, 0), gamma, 1e-11 * std::abs(gamma)) << "T=" << T;
    EXPECT_LE(gains.eigenvalue_mismatch, 1e-9);
  }
}

// The printed Γ = 18.730773 makes U unstable; Γ = 1.8730773 places the spectrum
// to the printed digits.
TEST(GuiroDesign, PrintedGammaHasItsDecimalPointShifted) {
  const Paper paper;
  const Eigen::Matrix3d printed = error_matrix(g::printed_K(), g::printed_Gamma, paper.H0);
  EXPECT_NEAR(adaptobs::spectral_radius(MatrixXd(printed)), 1.3560717586238364, 1e-9);
  const Eigen::Matrix3d shifted = error_matrix(g::printed_K(), g::corrected_printed_Gamma, paper.H0);
  EXPECT_LE((sorted_eigenvalues(shifted) - Eigen::Vector3cd(0.2, 0.5, 0.6)).cwiseAbs().maxCoeff(), 2e-7);
  EXPECT_GT((sorted_eigenvalues(shifted) - Eigen::Vector3cd(0.2, 0.5, 0.6)).cwiseAbs().maxCoeff(), 1e-9)
      << "printed digits are rounded";
}

// 0 in the spectrum: the paper's route fails there (1 + bΓ = 0), this one does not.
TEST(GuiroDesign, DeadbeatIsAssignable) {
  const auto gains = paper_gains(Eigen::Vector3d::Zero());
  EXPECT_MATRIX_NEAR(gains.K, Eigen::Vector2d(2.522980602916232, 0.477019397083768), 0, 1e-11);
  EXPECT_NEAR(gains.Gamma(0, 0), 3.216155741210603, 1e-11 * 3.216155741210603);
  EXPECT_NEAR(1 + Paper{}.H0(1) * gains.Gamma(0, 0), 0.0, 1e-12);
  EXPECT_LT((gains.U * gains.U * gains.U).norm(), 1e-12);
}

// U(K, Γ) and Ā − LC̄ with L = [EK; Γ(I − CK)] share their characteristic
// polynomial for any gains, and det U = det E · det(I − CK) · det(I + ΓCH̄).
TEST(GuiroDesign, ErrorMatrixHasTheSpectrumOfTheAugmentedPredictor) {
  RandomMatrices rng(502);
  for (int trial = 0; trial < 10; ++trial) {
    const int n = 4, m = 2, p = 2;
    const MatrixXd e = adaptobs::matrix_exponential(MatrixXd(rng.uniform<MatrixXd>(n, n)));
    const MatrixXd c = rng.uniform<MatrixXd>(m, n), hbar = rng.uniform<MatrixXd>(n, p);
    const MatrixXd k = rng.uniform<MatrixXd>(n, m), gamma = rng.uniform<MatrixXd>(p, m);
    const MatrixXd u = adaptobs::guiro_error_matrix(e, c, hbar, k, gamma);
    MatrixXd a_bar = MatrixXd::Zero(n + p, n + p), c_bar = MatrixXd::Zero(m, n + p), l(n + p, m);
    a_bar.topLeftCorner(n, n) = e;
    a_bar.topRightCorner(n, p) = e * hbar;
    a_bar.bottomRightCorner(p, p).setIdentity();
    c_bar.leftCols(n) = c;
    l << e * k, gamma * (MatrixXd::Identity(m, m) - c * k);
    const Eigen::VectorXcd spectrum = adaptobs::detail::dense_eigenvalues<double>(u);
    EXPECT_LE(adaptobs::cayley_hamilton_residual(MatrixXd(a_bar - l * c_bar), spectrum), 1e-11);
    const double det = e.determinant() * (MatrixXd::Identity(m, m) - c * k).determinant() *
                       (MatrixXd::Identity(p, p) + gamma * c * hbar).determinant();
    EXPECT_NEAR(u.determinant(), det, 1e-10 * std::max(1.0, std::abs(det)));
  }
}

// Random observable cases, n = 2..6, m = 1..3, p = 1..min(m, n): the
// Cayley–Hamilton residual is always at round-off, and wherever the eigenvector
// basis is well conditioned (κ(V) < 1e5) the eigenvalues are placed to within
// the Bauer–Fike bound κ(V)·‖δU‖ for a backward error ‖δU‖ of 100 (n + p) ε ‖U‖
// (forming U, then computing its eigenvalues). That bound stays below 7e-7 in
// these cases, and the largest mismatch is 2 % of it.
TEST(GuiroDesign, RandomObservableCasesGetTheRequestedSpectrum) {
  RandomMatrices rng(503);
  int cases = 0, checked = 0, multi = 0;
  for (int n = 2; n <= 6; ++n) {
    for (int m = 1; m <= 3; ++m) {
      for (int p = 1; p <= std::min(m, n); ++p) {
        for (int rep = 0; rep < 3; ++rep) {
          const double T = rng.scalar(0.2, 1.0);
          const MatrixXd e = adaptobs::matrix_exponential(MatrixXd(rng.uniform<MatrixXd>(n, n) * 1.7 * T));
          const MatrixXd c = rng.uniform<MatrixXd>(m, n), hbar = rng.uniform<MatrixXd>(n, p);
          Eigen::VectorXcd poles(n + p);
          for (;;) {  // well separated, conjugate closed, radius ≤ 0.85
            Index i = 0;
            while (i < n + p) {
              if (i + 1 < n + p && rng.scalar(0, 1) < 0.4) {
                const auto z = std::polar(0.85 * std::sqrt(rng.scalar(0, 1)), rng.scalar(0.2, 2.9));
                poles(i++) = z;
                poles(i++) = std::conj(z);
              } else {
                poles(i++) = rng.scalar(-0.85, 0.85);
              }
            }
            double gap = 1;
            for (Index a = 0; a < n + p; ++a)
              for (Index b = a + 1; b < n + p; ++b) gap = std::min(gap, std::abs(poles(a) - poles(b)));
            if (gap > 0.08) break;
          }
          const auto gains = adaptobs::design_guiro_gains(e, c, hbar, poles);
          const MatrixXd u = adaptobs::guiro_error_matrix(e, c, hbar, gains.K, gains.Gamma);
          EXPECT_LE(adaptobs::cayley_hamilton_residual(u, poles), 1e-10) << "n=" << n << " m=" << m << " p=" << p;
          EXPECT_LT(adaptobs::spectral_radius(u), 1.0);
          if (gains.eigenvector_condition < 1e5) {
            ++checked;
            const double backward_error =
                100.0 * static_cast<double>(n + p) * std::numeric_limits<double>::epsilon() * u.norm();
            EXPECT_LE(adaptobs::eigenvalue_mismatch(u, poles), gains.eigenvector_condition * backward_error)
                << "n=" << n << " m=" << m << " p=" << p;
            if (m > 1 && p > 1) ++multi;
          }
          ++cases;
        }
      }
    }
  }
  EXPECT_EQ(cases, 3 * (5 + 4 * 6));  // p ≤ min(m, n): n = 2 caps p at 2
  EXPECT_GE(checked, cases * 8 / 10) << "too few well-conditioned cases: the eigenvalue check has no power";
  EXPECT_GE(multi, 15) << "too few cases with m, p > 1";
}

// The spectrum {1/2, 3/5, λ₃} with aΠλ = bQ(1) needs Γ = ∞ (I − CK singular).
TEST(GuiroDesign, InfeasibleSpectrumIsReportedNotReturned) {
  const std::string message =
      configuration_error_of([] { (void)paper_gains(Eigen::Vector3d(0.5, 0.6, -0.5352816990913765)); });
  EXPECT_NE(message.find("argument 'poles' cannot be assigned"), std::string::npos) << message;
  EXPECT_NE(message.find("singular"), std::string::npos) << message;
  // Near it the gain exists but grows like the inverse distance.
  const auto near = paper_gains(Eigen::Vector3d(0.5, 0.6, -0.5352816990913765 + 1e-2));
  EXPECT_NEAR(near.Gamma(0, 0), 262.6, 0.5);
  EXPECT_LE(near.cayley_hamilton_residual, 1e-10);
}

// The design does not depend on the units of the output: with C × 1e-12 the
// gains K and Gamma are 1e12 times the paper's and U is the same. (E, C) was
// refused as unobservable, and then C as of rank 0.
TEST(GuiroDesign, OutputInOtherUnitsGivesScaledGains) {
  const Paper paper;
  const auto reference = paper_gains();
  for (const double s : {1e-12, 1e12}) {
    const Eigen::RowVector2d c = s * paper.C;
    const auto gains = adaptobs::design_guiro_gains(paper.E, c, paper.H0, g::requested_poles());
    EXPECT_MATRIX_NEAR(Eigen::Vector2d(s * gains.K), reference.K, 0, 1e-12) << s;
    EXPECT_NEAR(s * gains.Gamma(0, 0), reference.Gamma(0, 0), 1e-12 * reference.Gamma(0, 0)) << s;
    EXPECT_MATRIX_NEAR(gains.U, reference.U, 1e-12, 0) << s;
    EXPECT_LE(gains.eigenvalue_mismatch, 1e-9) << s;
    EXPECT_LE((sorted_eigenvalues(gains.U) - Eigen::Vector3cd(0.2, 0.5, 0.6)).cwiseAbs().maxCoeff(), 1e-10) << s;
    // C = (1 0) does not observe this E in any units.
    EXPECT_NE(configuration_error_of([&] {
                (void)adaptobs::design_guiro_gains(paper.E, Eigen::RowVector2d(s, 0), paper.H0, g::requested_poles());
              }).find("'E, C' is not observable"),
              std::string::npos)
        << s;
  }
}

// Each output in its own units: C = diag(2^-40, 1) gets the gains of C = I
// with their first column times 2^40, bit for bit, and the same U (it was
// refused as "C has rank 1"). Gains beyond the floating-point range, for a C
// of 2e-308 or a subnormal one, are refused naming C (they were returned as
// infinite, or refused as another function's argument).
TEST(GuiroDesign, EachOutputInItsOwnUnits) {
  Eigen::Matrix2d e;
  e << 0.9, 0.1, 0, 0.8;
  const Eigen::Matrix2d hbar = Eigen::Matrix2d::Identity();
  Eigen::Vector4cd poles;
  poles << 0.2, 0.3, 0.4, 0.5;
  const auto reference = adaptobs::design_guiro_gains(e, Eigen::Matrix2d::Identity(), hbar, poles);
  const double small = std::ldexp(1.0, -40);
  const auto gains =
      adaptobs::design_guiro_gains(e, Eigen::Matrix2d(Eigen::Vector2d(small, 1).asDiagonal()), hbar, poles);
  const Eigen::Matrix2d back = Eigen::Vector2d(1 / small, 1).asDiagonal();
  EXPECT_TRUE(bitwise_equal(gains.K, Eigen::Matrix2d(reference.K * back)));
  EXPECT_TRUE(bitwise_equal(gains.Gamma, Eigen::Matrix2d(reference.Gamma * back)));
  EXPECT_MATRIX_NEAR(gains.U, reference.U, 1e-14, 0);
  EXPECT_LE(gains.eigenvalue_mismatch, 1e-9);

  const Paper paper;
  for (const double tiny : {2e-308, 1e-310})
    EXPECT_CONFIGURATION_ERROR_NAMES(
        (void)adaptobs::design_guiro_gains(paper.E, Eigen::RowVector2d(tiny, tiny), paper.H0, g::requested_poles()),
        "C");
}

TEST(GuiroDesign, CasesWithoutSolutionAreNamed) {
  const Paper paper;
  // a = 0: θ never reaches the output (rank condition at the eigenvalue 1).
  EXPECT_NE(configuration_error_of([&] {
              (void)adaptobs::design_guiro_gains(paper.E, paper.C, Eigen::Vector2d(0.0, -0.3), g::requested_poles());
            }).find("'Hbar' leaves theta unidentifiable"),
            std::string::npos);
  // Two parameters, one output: an eigenvalue stays at 1.
  const Eigen::Matrix<double, 2, 2> two = Eigen::Matrix2d::Identity();
  EXPECT_NE(configuration_error_of([&] {
              (void)adaptobs::design_guiro_gains(paper.E, paper.C, two, Eigen::Vector4d(0.1, 0.2, 0.3, 0.4));
            }).find("C has rank 1"),
            std::string::npos);
  // C = (1 0), as in the paper's introduction, does not observe this A.
  EXPECT_NE(configuration_error_of([&] {
              (void)adaptobs::design_guiro_gains(paper.E, Eigen::RowVector2d(1, 0), paper.H0, g::requested_poles());
            }).find("'E, C' is not observable"),
            std::string::npos);
  EXPECT_NE(configuration_error_of([] { (void)paper_gains(Eigen::Vector3d(0.5, 0.6, 1.2)); }).find("unit circle"),
            std::string::npos);
  EXPECT_NE(configuration_error_of([&] {
              (void)adaptobs::design_guiro_gains(paper.E, paper.C, paper.H0, Eigen::Vector2d(0.5, 0.6));
            }).find("n + p = 3"),
            std::string::npos);
  // A NaN tolerance is refused by name (every comparison with it failed, and the
  // refusal blamed Hbar or the poles).
  adaptobs::GuiroDesignOptions nan_rank, negative_singularity;
  nan_rank.rank_tolerance = std::numeric_limits<double>::quiet_NaN();
  negative_singularity.singularity_tolerance = -1;
  EXPECT_CONFIGURATION_ERROR_NAMES(
      adaptobs::design_guiro_gains(paper.E, paper.C, paper.H0, g::requested_poles(), nan_rank),
      "options.rank_tolerance");
  EXPECT_CONFIGURATION_ERROR_NAMES(
      adaptobs::design_guiro_gains(paper.E, paper.C, paper.H0, g::requested_poles(), negative_singularity),
      "options.singularity_tolerance");
  // A singular E (no sampled e^{AT} is one) was refused as 'I - C K is singular'.
  Eigen::Matrix2d nilpotent;
  nilpotent << 0, 1, 0, 0;
  EXPECT_CONFIGURATION_ERROR_NAMES(
      adaptobs::design_guiro_gains(nilpotent, Eigen::RowVector2d(1, 0), Eigen::Vector2d(0.1, 0.2),
                                   Eigen::Vector3d(0.2, 0.3, 0.4)),
      "E");
  // A NaN in U was refused as spectral_radius's 'M'.
  EXPECT_CONFIGURATION_ERROR_NAMES(
      adaptobs::best_power_bound(Eigen::Matrix2d(Eigen::Vector2d(0.5, std::nan("")).asDiagonal())), "U");
}

// ---- Proposition 2.2 -----------------------------------------------------------------

std::vector<Eigen::Vector2d> closed_form_sequence(Index count) {
  std::vector<Eigen::Vector2d> h;
  for (Index k = 0; k < count; ++k) h.push_back(g::closed_form_H<double>(k));
  return h;
}

// Around H₀, as in the paper, ‖W(k)‖ grows to 0.225 while (i) tolerates at
// most 0.049: neither condition holds, although the observer converges.
TEST(GuiroConvergence, PaperSplitAroundH0CertifiesNothing) {
  const Paper paper;
  const auto gains = paper_gains();
  const auto report =
      adaptobs::check_guiro_convergence(paper.E, paper.C, gains.K, gains.Gamma, paper.H0, closed_form_sequence(200));
  const auto& w = report.w_norms;
  EXPECT_NEAR(w[0], 0.0, 1e-15);
  EXPECT_NEAR(w[1], 0.06309072588204587, 1e-12);
  EXPECT_NEAR(w[2], 0.09845066760354387, 1e-12);
  EXPECT_NEAR(w[5], 0.148481410920994, 1e-12);
  EXPECT_NEAR(w[10], 0.17886340017982783, 1e-12);
  EXPECT_NEAR(w[100], 0.21937840520170795, 1e-12);
  // The paper prints 0.2156, which is ‖W(59)‖; the norms grow towards their
  // supremum ‖W(∞)‖ = 0.2251, with H∞ = (T, −T²/2) = (1, −1/2).
  EXPECT_NEAR(w[59], 0.2156, 5e-5);
  const double w_limit =
      ((Eigen::Matrix2d::Identity() - gains.K * paper.C) * paper.E * (Eigen::Vector2d(1, -0.5) - paper.H0)).norm();
  EXPECT_NEAR(w_limit, 0.2251, 5e-5);
  EXPECT_LT(*std::max_element(w.begin(), w.end()), w_limit);
  // The printed entries of W(1).
  const Eigen::Vector2d w1 =
      (Eigen::Matrix2d::Identity() - gains.K * paper.C) * paper.E * (g::closed_form_H<double>(1) - paper.H0);
  EXPECT_MATRIX_NEAR(w1, Eigen::Vector2d(0.06238127577460423, 0.009434835719620553), 1e-12, 0);
  EXPECT_NEAR(adaptobs::power_bound_constant(gains.U, 0.8), 4.2369, 1e-4);
  ASSERT_TRUE(report.bound.has_value());
  EXPECT_NEAR(report.bound->perturbation_margin(), 0.0486, 5e-4);
  EXPECT_EQ(report.condition_i, ConditionVerdict::fails);
  EXPECT_EQ(report.condition_ii, ConditionVerdict::fails);
  EXPECT_FALSE(report.certified());
  EXPECT_NE(report.summary().find("(i) fails"), std::string::npos) << report.summary();
}

// Around the limit H∞ = (1, −1/2), W(k) → 0 like 1/(2k) and (i) holds from k₀ = 11.
TEST(GuiroConvergence, SplitAroundTheLimitCertifiesConditionI) {
  const Paper paper;
  const auto gains = paper_gains();
  const auto report = adaptobs::check_guiro_convergence(paper.E, paper.C, gains.K, gains.Gamma, g::limit_H<double>(),
                                                        closed_form_sequence(200));
  EXPECT_NEAR(report.spectral_radius, 0.7464796255405619, 1e-10);
  EXPECT_EQ(report.condition_i, ConditionVerdict::holds);
  ASSERT_TRUE(report.k0.has_value());
  EXPECT_EQ(*report.k0, 11);
  EXPECT_LT(report.rate, 1.0);
  EXPECT_EQ(report.condition_ii, ConditionVerdict::undetermined) << "1/k decay is the border of summability";
  EXPECT_NEAR(report.decay_exponent, 1.0, 0.1);
  EXPECT_TRUE(report.certified());
}

TEST(GuiroConvergence, SummableOrVanishingDeviationsCertifyConditionII) {
  const Paper paper;
  const auto gains = paper_gains();
  std::vector<Eigen::Vector2d> geometric, constant;
  for (Index k = 0; k < 60; ++k) {
    geometric.push_back(paper.H0 + std::pow(0.7, double(k)) * Eigen::Vector2d(0.3, -0.2));
    constant.push_back(paper.H0);
  }
  const auto r1 = adaptobs::check_guiro_convergence(paper.E, paper.C, gains.K, gains.Gamma, paper.H0, geometric);
  EXPECT_EQ(r1.condition_ii, ConditionVerdict::holds);
  EXPECT_EQ(r1.condition_i, ConditionVerdict::holds);
  const auto r2 = adaptobs::check_guiro_convergence(paper.E, paper.C, gains.K, gains.Gamma, paper.H0, constant);
  EXPECT_EQ(r2.condition_ii, ConditionVerdict::holds);
  EXPECT_EQ(*r2.k0, 0);
}

TEST(GuiroConvergence, UnstableErrorMatrixIsReported) {
  const Paper paper;
  const auto report =
      adaptobs::check_guiro_convergence(paper.E, paper.C, g::printed_K(), Eigen::Matrix<double, 1, 1>(g::printed_Gamma),
                                        paper.H0, closed_form_sequence(20));
  EXPECT_FALSE(report.bound.has_value());
  EXPECT_FALSE(report.certified());
  EXPECT_NE(report.summary().find("not Schur"), std::string::npos);
}

}  // namespace
