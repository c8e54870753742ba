// Continuous-discrete adaptive observer of Guiro, Iggidr, Ngom, Touré (paper
// 002): the regressor integrals H_k (closed forms, adaptive bisection, exact
// polynomial form), the gain design (the paper's example, its printed gains,
// random MIMO cases, cases without solution), proposition 2.2 as a
// diagnostic, and the observer itself (convergence, error recursion (4),
// float/double, fixed/dynamic, bad input).

#include <adaptobs/core/discretization.hpp>
#include <adaptobs/core/observer.hpp>
#include <adaptobs/core/regressor_integral.hpp>
#include <adaptobs/core/sampled_model.hpp>
#include <adaptobs/design/guiro_convergence.hpp>
#include <adaptobs/design/guiro_gains.hpp>
#include <adaptobs/observers/guiro.hpp>
#include <adaptobs/simulation/discrete_plant.hpp>

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

using adaptobs::ConditionVerdict;
using adaptobs::Index;
using adaptobs::UpdateStatus;
using adaptobs::testing::RandomMatrices;
using Eigen::MatrixXd;
using Eigen::VectorXd;
namespace g = adaptobs::examples::guiro;

template <class F>
std::string configuration_error_of(F&& f) {
  try {
    f();
  } catch (const adaptobs::ConfigurationError& e) {
    return e.what();
  }
  return "<no exception>";
}

// The paper's system: E = e^{AT}, C, H_0 (closed form).
struct Paper {
  Eigen::Matrix2d E = g::model<double>().system().A;
  Eigen::RowVector2d C = g::output_matrix<double>();
  Eigen::Vector2d H0 = g::closed_form_H<double>(0);
};

auto paper_gains(const Eigen::Vector3d& poles = g::requested_poles()) {
  const Paper paper;
  return adaptobs::design_guiro_gains(paper.E, paper.C, paper.H0, poles);
}

Eigen::Matrix3d error_matrix(const Eigen::Vector2d& K, double gamma, const Eigen::Vector2d& Hbar) {
  const Paper paper;
  return adaptobs::guiro_error_matrix(paper.E, paper.C, Hbar, K, Eigen::Matrix<double, 1, 1>(gamma));
}

Eigen::Vector3cd sorted_eigenvalues(const Eigen::Matrix3d& u) {
  Eigen::Vector3cd e = Eigen::EigenSolver<MatrixXd>(MatrixXd(u), false).eigenvalues();
  std::sort(e.data(), e.data() + 3, [](auto a, auto b) { return a.real() != b.real() ? a.real() < b.real() : a.imag() < b.imag(); });
  return e;
}

// ---- H_k ------------------------------------------------------------------------

TEST(GuiroRegressor, H0MatchesThePrintedClosedForm) {
  adaptobs::RegressorIntegral<double, 2, 1> integral(g::continuous_dynamics<double>(), 1.0);
  const auto h0 = integral.integrate(g::Regressor{}, 0.0);
  const Eigen::Vector2d printed(1 - std::log(1.5), 0.5 - std::log(2.25));
  EXPECT_MATRIX_NEAR(h0.H, printed, 1e-12, 0);
  EXPECT_MATRIX_NEAR(h0.H, Eigen::Vector2d(0.5945348918918356, -0.31093021621632877), 1e-12, 0);
  EXPECT_MATRIX_NEAR(h0.Psi, Eigen::Vector2d(0.5945348918918356, 0.28360467567550685), 1e-12, 0);
  EXPECT_TRUE(h0.converged);
}

// The closed form behind the paper's W(k): H_k = (T − r, T − T²/2 − c r), c = kT + 2, r = ln(1 + T/c).
TEST(GuiroRegressor, HkMatchesTheClosedFormForSeveralKAndPeriods) {
  for (double T : {0.5, 1.0, 2.0}) {
    adaptobs::RegressorIntegral<double, 2, 1> integral(g::continuous_dynamics<double>(), T);
    for (Index k : {0, 1, 2, 5, 10, 50, 1000}) {
      const auto h = integral.integrate(g::Regressor{}, double(k) * T);
      EXPECT_MATRIX_NEAR(h.H, g::closed_form_H<double>(k, T), 1e-12, 0) << "T=" << T << " k=" << k;
      EXPECT_MATRIX_NEAR(h.Psi, g::closed_form_Psi<double>(k, T), 1e-12, 0) << "T=" << T << " k=" << k;
      EXPECT_TRUE(h.converged);
      EXPECT_LE(h.error_estimate, 2e-12 * std::max(1.0, h.H.cwiseAbs().maxCoeff()));
    }
  }
  // The printed values the W(k) of §4 is built from.
  EXPECT_MATRIX_NEAR(g::closed_form_H<double>(1), Eigen::Vector2d(0.7123179275482191, -0.3630462173553427), 1e-15, 0);
  EXPECT_MATRIX_NEAR(g::closed_form_H<double>(10), Eigen::Vector2d(0.9199572923264636, -0.46051249208243705), 1e-15, 0);
}

// A kink inside the period: one 15-point panel cannot meet the tolerance,
// bisection does. With A nilpotent, H = (∫f, −∫τf) for φ = (f, 0).
TEST(GuiroRegressor, BisectionResolvesAKink) {
  const auto kink = [](double t) { return Eigen::Vector2d(std::abs(t - 4.3), 0.0); };
  const Eigen::Vector2d exact(0.29, -(0.0045 + (1.0 / 3 - 0.15) - (0.009 - 0.0135)));
  adaptobs::RegressorIntegral<double, 2, 1> adaptive(g::continuous_dynamics<double>(), 1.0);
  const auto h = adaptive.integrate(kink, 4.0);
  EXPECT_TRUE(h.converged);
  EXPECT_MATRIX_NEAR(h.H, exact, 1e-11, 0);
  EXPECT_LE((h.H - exact).cwiseAbs().maxCoeff(), std::max(h.error_estimate, 1e-15));
  adaptobs::RegressorIntegral<double, 2, 1> single_panel(g::continuous_dynamics<double>(), 1.0, {.max_depth = 0});
  const auto coarse = single_panel.integrate(kink, 4.0);
  EXPECT_FALSE(coarse.converged);
  EXPECT_GT((coarse.H - exact).cwiseAbs().maxCoeff(), 1e-6);
}

// Exact polynomial form against the quadrature and against zero-order hold.
TEST(GuiroRegressor, PolynomialFormAgreesWithQuadratureAndZeroOrderHold) {
  Eigen::Matrix3d a;
  a << -0.5, 2.0, 0.0, -1.0, -0.3, 0.4, 0.2, 0.0, 0.1;
  const double T = 0.7;
  RandomMatrices rng(501);
  using Regressor = Eigen::Matrix<double, 3, 2>;
  const std::vector<Regressor> p{rng.uniform<Regressor>(), rng.uniform<Regressor>(), rng.uniform<Regressor>()};
  const double t0 = 3.5;
  const auto phi = [&](double t) -> Regressor {
    const double tau = t - t0;
    return p[0] + p[1] * tau + p[2] * tau * tau;
  };
  const adaptobs::PolynomialRegressorIntegral<double, 3, 2> exact(a, T, 2);
  adaptobs::RegressorIntegral<double, 3, 2> quadrature(a, T, {.relative_tolerance = 1e-14});
  const auto e = exact.integrate(p);
  const auto q = quadrature.integrate(phi, t0);
  EXPECT_MATRIX_NEAR(e.H, q.H, 1e-13, 1e-13);
  EXPECT_MATRIX_NEAR(e.Psi, q.Psi, 1e-13, 1e-13);
  EXPECT_MATRIX_NEAR(exact.transition(), quadrature.transition(), 1e-14, 1e-14);
  // Zero-order hold: Ψ = ∫₀ᵀ e^{As} ds P₀, as discretize_zoh computes it.
  const auto zoh = exact.integrate(std::span(p.data(), 1));
  EXPECT_MATRIX_NEAR(zoh.Psi, adaptobs::discretize_zoh(a, p[0], T).Bd, 1e-14, 1e-14);
  EXPECT_MATRIX_NEAR(zoh.H, quadrature.transition().partialPivLu().solve(zoh.Psi), 1e-13, 1e-13);
  EXPECT_NE(configuration_error_of([&] { (void)exact.integrate(std::vector<Regressor>(4, Regressor::Zero())); })
                .find("'coefficients'"),
            std::string::npos);
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
    const Eigen::VectorXcd spectrum = Eigen::EigenSolver<MatrixXd>(u, false).eigenvalues();
    EXPECT_LE(adaptobs::cayley_hamilton_residual(MatrixXd(a_bar - l * c_bar), spectrum), 1e-11);
    const double det = e.determinant() * (MatrixXd::Identity(m, m) - c * k).determinant() *
                       (MatrixXd::Identity(p, p) + gamma * c * hbar).determinant();
    EXPECT_NEAR(u.determinant(), det, 1e-10 * std::max(1.0, std::abs(det)));
  }
}

// Random observable cases, n = 2..6, m = 1..3, p = 1..min(m, n): the
// Cayley–Hamilton residual is always at round-off, and the eigenvalues are
// placed to 1e-9 wherever their conditioning allows it.
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
            EXPECT_LE(adaptobs::eigenvalue_mismatch(u, poles), 1e-9) << "n=" << n << " m=" << m << " p=" << p;
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
  const std::string message = configuration_error_of([] { (void)paper_gains(Eigen::Vector3d(0.5, 0.6, -0.5352816990913765)); });
  EXPECT_NE(message.find("argument 'poles' cannot be assigned"), std::string::npos) << message;
  EXPECT_NE(message.find("singular"), std::string::npos) << message;
  // Near it the gain exists but grows like the inverse distance.
  const auto near = paper_gains(Eigen::Vector3d(0.5, 0.6, -0.5352816990913765 + 1e-2));
  EXPECT_NEAR(near.Gamma(0, 0), 262.6, 0.5);
  EXPECT_LE(near.cayley_hamilton_residual, 1e-10);
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
  const auto report = adaptobs::check_guiro_convergence(paper.E, paper.C, gains.K, gains.Gamma, paper.H0,
                                                        closed_form_sequence(200));
  const auto& w = report.w_norms;
  EXPECT_NEAR(w[0], 0.0, 1e-15);
  EXPECT_NEAR(w[1], 0.06309072588204587, 1e-12);
  EXPECT_NEAR(w[2], 0.09845066760354387, 1e-12);
  EXPECT_NEAR(w[5], 0.148481410920994, 1e-12);
  EXPECT_NEAR(w[10], 0.17886340017982783, 1e-12);
  EXPECT_NEAR(w[100], 0.21937840520170795, 1e-12);
  // The printed entries of W(1).
  const Eigen::Vector2d w1 = (Eigen::Matrix2d::Identity() - gains.K * paper.C) * paper.E *
                             (g::closed_form_H<double>(1) - paper.H0);
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
  const auto report = adaptobs::check_guiro_convergence(paper.E, paper.C, gains.K, gains.Gamma,
                                                        g::limit_H<double>(), closed_form_sequence(200));
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
  const auto report = adaptobs::check_guiro_convergence(paper.E, paper.C, g::printed_K(),
                                                        Eigen::Matrix<double, 1, 1>(g::printed_Gamma), paper.H0,
                                                        closed_form_sequence(20));
  EXPECT_FALSE(report.bound.has_value());
  EXPECT_FALSE(report.certified());
  EXPECT_NE(report.summary().find("not Schur"), std::string::npos);
}

// ---- Observer ----------------------------------------------------------------------------

template <typename S>
using PaperObserver = adaptobs::GuiroObserver<adaptobs::DiscreteLtiModel<g::Dims<S>>>;

template <typename S>
PaperObserver<S> make_observer(adaptobs::GuiroOptions options = {}, double gamma = 0) {
  const auto gains = paper_gains();
  const Eigen::Matrix<S, 1, 1> g1(S(gamma == 0 ? gains.Gamma(0, 0) : gamma));
  return PaperObserver<S>(g::model<S>(), gains.K.cast<S>(), g1, g::initial_state_estimate<S>(),
                          g::initial_parameter_estimate<S>(), options);
}

static_assert(adaptobs::Observer<PaperObserver<double>>);
static_assert(adaptobs::Observer<PaperObserver<float>>);

// The example of §4, noise free: the observer uses the quadrature's Ψ_k, the
// plant the closed form.
TEST(Guiro, PaperExampleConvergesWithinSixtySamples) {
  auto observer = make_observer<double>();
  auto plant = g::make_plant<double>();
  adaptobs::RegressorIntegral<double, 2, 1> integral(g::continuous_dynamics<double>(), g::period);
  for (Index k = 0; k < 60; ++k) {
    auto sample = plant.sample();
    sample.Psi = integral.integrate(g::Regressor{}, double(k) * g::period).Psi;
    ASSERT_EQ(observer.update(sample), UpdateStatus::accepted);
    plant.advance();
  }
  EXPECT_LT(std::abs(observer.parameters()(0) - g::theta), 1e-6);
  EXPECT_LT((observer.state() - plant.state()).norm(), 1e-6);
}

// With the paper's uncorrected z₀ the run is eq. (2) from k = 0, and the
// errors at k = 60 are the reference values of that recursion.
TEST(Guiro, PaperInitializationReplaysEquation2) {
  auto observer = make_observer<double>({.correct_initial_estimate = false});
  auto plant = g::make_plant<double>();
  Eigen::Vector2d x60 = Eigen::Vector2d::Zero();
  for (Index k = 0; k <= 60; ++k) {
    if (k == 60) {
      EXPECT_NEAR(std::abs(observer.parameters()(0) - g::theta) / 3.977e-8, 1.0, 1e-3);
      x60 = plant.state();
    }
    ASSERT_EQ(observer.update(plant.sample()), UpdateStatus::accepted);
    plant.advance();
  }
  EXPECT_NEAR((observer.corrected_state() - x60).norm() / 4.625e-8, 1.0, 1e-3);
}

TEST(Guiro, PrintedGainsDiverge) {
  auto observer = make_observer<double>({.correct_initial_estimate = false}, g::printed_Gamma);
  Eigen::Matrix<double, 1, 1> gamma(g::printed_Gamma);
  observer.set_gains(g::printed_K(), gamma);
  auto plant = g::make_plant<double>();
  for (Index k = 0; k < 60; ++k) {
    ASSERT_EQ(observer.update(plant.sample()), UpdateStatus::accepted);
    plant.advance();
  }
  EXPECT_GT(std::abs(observer.parameters()(0) - g::theta), 1e6);
}

// Eq. (4): v_{k+1} = U_k v_k with U_k = U(H_k), v_k = (z_k − x_k, θ̂_k − θ).
// Before the update of sample k the observer holds θ̂_k; after it, z_k.
TEST(Guiro, ErrorsFollowEquation4) {
  const Paper paper;
  const auto gains = paper_gains();
  auto observer = make_observer<double>({.correct_initial_estimate = false});
  auto plant = g::make_plant<double>();
  Eigen::Vector3d previous = Eigen::Vector3d::Zero(), first = Eigen::Vector3d::Zero(), v;
  for (Index k = 0; k <= 30; ++k) {
    const double theta_k = observer.parameters()(0);
    const Eigen::Vector2d x_k = plant.state();
    ASSERT_EQ(observer.update(plant.sample()), UpdateStatus::accepted);
    v << observer.corrected_state() - x_k, theta_k - g::theta;
    if (k == 0) {
      first = v;
    } else {
      const Eigen::Vector3d predicted =
          adaptobs::guiro_error_matrix(paper.E, paper.C, g::closed_form_H<double>(k - 1), gains.K, gains.Gamma) *
          previous;
      EXPECT_MATRIX_NEAR(v, predicted, 1e-12 * (1 + first.norm()), 0) << "k=" << k;
    }
    previous = v;
    plant.advance();
  }
  EXPECT_LT(v.norm(), 1e-3 * first.norm());
}

template <typename S>
class GuiroTyped : public ::testing::Test {};
using Scalars = ::testing::Types<float, double>;
TYPED_TEST_SUITE(GuiroTyped, Scalars);

TYPED_TEST(GuiroTyped, PaperExampleConverges) {
  using S = TypeParam;
  auto observer = make_observer<S>();
  auto plant = g::make_plant<S>();
  for (Index k = 0; k < 60; ++k) {
    ASSERT_EQ(observer.update(plant.sample()), UpdateStatus::accepted);
    plant.advance();
  }
  // x₂ grows like 5t²/2 ≈ 9000: relative to it, float keeps about 1e-6.
  const double tol = std::is_same_v<S, float> ? 1e-3 : 1e-6;
  EXPECT_LT(std::abs(double(observer.parameters()(0)) - g::theta), tol);
  EXPECT_LT(double((observer.state() - plant.state()).norm()) / double(plant.state().norm()), tol * 1e-2);
}

TYPED_TEST(GuiroTyped, NonFiniteSamplesAreRejectedAndChangeNothing) {
  using S = TypeParam;
  auto observer = make_observer<S>();
  auto plant = g::make_plant<S>();
  for (Index k = 0; k < 10; ++k) {
    ASSERT_EQ(observer.update(plant.sample()), UpdateStatus::accepted);
    plant.advance();
  }
  const auto z = observer.state();
  const auto zc = observer.corrected_state();
  const auto theta = observer.parameters();
  const Index step = observer.step();
  const auto unchanged = [&] {
    using adaptobs::testing::bitwise_equal;
    return bitwise_equal(observer.state(), z) && bitwise_equal(observer.corrected_state(), zc) &&
           bitwise_equal(observer.parameters(), theta) && observer.step() == step;
  };
  for (S bad : {std::numeric_limits<S>::quiet_NaN(), std::numeric_limits<S>::infinity()}) {
    auto s = plant.sample();
    s.y(0) = bad;
    EXPECT_EQ(observer.update(s), UpdateStatus::nonfinite_input);
    s = plant.sample();
    s.Psi(1, 0) = -bad;
    EXPECT_EQ(observer.update(s), UpdateStatus::nonfinite_input);
    EXPECT_TRUE(unchanged());
  }
  auto huge = plant.sample();
  huge.Psi.setConstant(std::numeric_limits<S>::max());
  huge.y.setConstant(-std::numeric_limits<S>::max());
  EXPECT_EQ(observer.update(huge), UpdateStatus::nonfinite_result);
  EXPECT_TRUE(unchanged());
  EXPECT_EQ(observer.update(plant.sample()), UpdateStatus::accepted);
}

// Three states, two outputs, two parameters, a known input: φ(t) = Φ₀ + e^{−t}Φ₁
// settles, so the design uses H̄ = H∞ (exact from the polynomial form) and
// proposition 2.2 holds through condition (ii).
TEST(Guiro, MimoWithKnownInputConverges) {
  using Dims = adaptobs::Dimensions<double, 3, 1, 2, 2>;
  Eigen::Matrix3d a;
  a << 0, 1, 0,  //
      0, 0, 1,   //
      -0.2, -0.5, -0.4;
  const Eigen::Vector3d b(0, 0, 1);
  Eigen::Matrix<double, 2, 3> c;
  c << 1, 0, 0,  //
      0, 0, 1;
  Eigen::Matrix<double, 3, 2> phi0, phi1;
  phi0 << 0, 0, 1, 0, 0, 1;
  phi1 << 1, 0, 0, 0, 0, -1;
  const double T = 0.5;
  const auto phi = [&](double t) -> Eigen::Matrix<double, 3, 2> { return phi0 + std::exp(-t) * phi1; };
  const auto model = adaptobs::sampled_lti_model<Dims>(a, b, c, T);
  adaptobs::RegressorIntegral<double, 3, 2> integral(a, T, {.relative_tolerance = 1e-14});
  const adaptobs::PolynomialRegressorIntegral<double, 3, 2> constant(a, T, 0);
  const Eigen::Matrix<double, 3, 2> h_limit = constant.integrate(std::span(&phi0, 1)).H;
  const std::complex<double> z(0.3, 0.2);
  const Eigen::Matrix<std::complex<double>, 5, 1> poles(0.2, 0.4, 0.5, z, std::conj(z));
  const auto gains = adaptobs::design_guiro_gains(model.system().A, c, h_limit, poles);
  EXPECT_LE(gains.eigenvalue_mismatch, 1e-9);

  const Eigen::Vector2d theta(1.5, -0.7);
  auto input = [](Index k) { return Eigen::Matrix<double, 1, 1>(std::sin(0.3 * double(k))); };
  auto regressor = [&](Index k, const Eigen::Matrix<double, 1, 1>&) {
    return integral.integrate(phi, double(k) * T).Psi;
  };
  adaptobs::DiscreteLinearPlant plant(model, Eigen::Vector3d(1, -1, 0.5), theta, input, regressor,
                                      adaptobs::PlantNoise<double>{}, T);
  adaptobs::GuiroObserver observer(model, gains.K, gains.Gamma, Eigen::Vector3d::Zero().eval(),
                                   Eigen::Vector2d::Zero().eval());
  std::vector<Eigen::Matrix<double, 3, 2>> hs;
  for (Index k = 0; k < 80; ++k) {
    hs.push_back(integral.integrate(phi, double(k) * T).H);
    ASSERT_EQ(observer.update(plant.sample()), UpdateStatus::accepted);
    plant.advance();
  }
  EXPECT_MATRIX_NEAR(observer.parameters(), theta, 1e-9, 0);
  EXPECT_MATRIX_NEAR(observer.state(), plant.state(), 1e-9, 0);
  const auto report = adaptobs::check_guiro_convergence(model.system().A, c, gains.K, gains.Gamma, h_limit, hs);
  EXPECT_EQ(report.condition_ii, ConditionVerdict::holds);
  EXPECT_TRUE(report.certified());
}

TEST(Guiro, DynamicSizesGiveTheSameNumbersAsFixedSizes) {
  using DynDims = adaptobs::DynamicDimensions<double>;
  const auto fixed_model = g::model<double>();
  const adaptobs::DiscreteLtiModel<DynDims> dynamic_model(fixed_model.system().A, MatrixXd::Zero(2, 0),
                                                          fixed_model.system().C, 1);
  const auto gains = paper_gains();
  auto fixed = make_observer<double>();
  adaptobs::GuiroObserver dynamic(dynamic_model, MatrixXd(gains.K), MatrixXd::Constant(1, 1, gains.Gamma(0, 0)), VectorXd::Zero(2),
                                  VectorXd::Zero(1));
  auto plant = g::make_plant<double>();
  for (Index k = 0; k < 40; ++k) {
    const auto& s = plant.sample();
    ASSERT_EQ(fixed.update(s), UpdateStatus::accepted);
    ASSERT_EQ(dynamic.update({VectorXd::Zero(0), VectorXd::Constant(1, s.y(0)), MatrixXd(s.Psi)}),
              UpdateStatus::accepted);
    plant.advance();
  }
  EXPECT_MATRIX_NEAR(dynamic.state(), fixed.state(), 1e-12, 1e-12);
  EXPECT_MATRIX_NEAR(dynamic.corrected_state(), fixed.corrected_state(), 1e-12, 1e-12);
  EXPECT_MATRIX_NEAR(dynamic.parameters(), fixed.parameters(), 1e-12, 1e-12);
}

TEST(Guiro, ResetRestartsExactly) {
  auto observer = make_observer<double>();
  auto fresh = make_observer<double>();
  auto plant = g::make_plant<double>();
  for (Index k = 0; k < 20; ++k) {
    (void)observer.update(plant.sample());
    plant.advance();
  }
  observer.reset(g::initial_state_estimate<double>(), g::initial_parameter_estimate<double>());
  auto replay = g::make_plant<double>();
  for (Index k = 0; k < 20; ++k) {
    (void)observer.update(replay.sample());
    (void)fresh.update(replay.sample());
    replay.advance();
  }
  EXPECT_TRUE(adaptobs::testing::bitwise_equal(observer.state(), fresh.state()));
  EXPECT_TRUE(adaptobs::testing::bitwise_equal(observer.parameters(), fresh.parameters()));
}

TEST(Guiro, BadConfigurationNamesTheArgument) {
  const auto model = g::model<double>();
  const Eigen::Vector2d k = g::printed_K();
  const Eigen::Matrix<double, 1, 1> gamma(1.0), nan_gamma(std::nan(""));
  const Eigen::Vector2d z0 = Eigen::Vector2d::Zero();
  const Eigen::Matrix<double, 1, 1> th0(0.0);
  EXPECT_NE(configuration_error_of([&] { PaperObserver<double> o(model, k, nan_gamma, z0, th0); }).find("'Gamma'"),
            std::string::npos);
  EXPECT_NE(configuration_error_of([&] {
              PaperObserver<double> o(model, Eigen::Vector2d(std::nan(""), 0), gamma, z0, th0);
            }).find("'K'"),
            std::string::npos);
  using DynDims = adaptobs::DynamicDimensions<double>;
  const adaptobs::DiscreteLtiModel<DynDims> dynamic_model(model.system().A, MatrixXd::Zero(2, 0), model.system().C, 1);
  EXPECT_NE(configuration_error_of([&] {
              adaptobs::GuiroObserver o(dynamic_model, MatrixXd(k), MatrixXd::Ones(2, 1), VectorXd(z0), VectorXd::Zero(1));
            }).find("'Gamma'"),
            std::string::npos);
  EXPECT_NE(configuration_error_of([&] {
              adaptobs::GuiroObserver o(dynamic_model, MatrixXd(k), MatrixXd::Ones(1, 1), VectorXd::Zero(3), VectorXd::Zero(1));
            }).find("'z0'"),
            std::string::npos);
  adaptobs::GuiroObserver dynamic(dynamic_model, MatrixXd(k), MatrixXd::Ones(1, 1), VectorXd(z0), VectorXd::Zero(1));
  EXPECT_NE(configuration_error_of([&] {
              (void)dynamic.update({VectorXd::Zero(0), VectorXd::Zero(1), MatrixXd::Zero(2, 2)});
            }).find("'sample.Psi'"),
            std::string::npos);
  EXPECT_EQ(dynamic.step(), 0);
  EXPECT_NE(configuration_error_of([] {
              adaptobs::RegressorIntegral<double, 2, 1> r(g::continuous_dynamics<double>(), -1.0);
            }).find("'period'"),
            std::string::npos);
  EXPECT_NE(configuration_error_of([] {
              adaptobs::RegressorIntegral<double, 2, 1> r(g::continuous_dynamics<double>(), 1.0, {.max_depth = 50});
            }).find("'options.max_depth'"),
            std::string::npos);
}

}  // namespace
