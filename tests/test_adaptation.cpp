// Adaptation laws on their own (Dey & Bhasin 2022, eq. (17)–(23); exponential
// forgetting; normalized gradient): the recursions against their closed forms,
// the exactness and the cost of the reset test, partial measurements (the step
// on the present sub-regression), compute-then-commit, and configuration checks.

#include <adaptobs/adaptation/adaptation_law.hpp>
#include <adaptobs/adaptation/covariance_resetting.hpp>
#include <adaptobs/adaptation/exponential_forgetting.hpp>
#include <adaptobs/adaptation/normalized_gradient.hpp>
#include <adaptobs/adaptation/recursive_least_squares.hpp>
#include <adaptobs/core/symmetric_eigenvalues.hpp>

#include <Eigen/Cholesky>
#include <Eigen/LU>

#include "support/eigen_testing.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

namespace {

using adaptobs::Index;
using adaptobs::testing::RandomMatrices;

template <typename S>
using Rls = adaptobs::RecursiveLeastSquares<S, 4, 2>;
template <typename S>
using Resetting = adaptobs::CovarianceResettingRls<S, 4, 2>;
using Forgetting = adaptobs::ExponentialForgettingRls<double, 4, 2>;
using Gradient = adaptobs::NormalizedGradient<double, 4, 2>;
using DynamicResetting = adaptobs::CovarianceResettingRls<double, Eigen::Dynamic, Eigen::Dynamic>;

static_assert(adaptobs::DiscreteAdaptationLaw<Rls<double>>);
static_assert(adaptobs::DiscreteAdaptationLaw<Resetting<double>>);
static_assert(adaptobs::DiscreteAdaptationLaw<Forgetting>);
static_assert(adaptobs::DiscreteAdaptationLaw<Gradient>);
static_assert(adaptobs::DiscreteAdaptationLaw<DynamicResetting>);

using Matrix4 = Eigen::Matrix4d;
using Regressor = Eigen::Matrix<double, 4, 2>;
using Vector4 = Eigen::Vector4d;
using Vector2 = Eigen::Vector2d;

// Eigenvalues of a symmetric matrix in ascending order (Jacobi; dynamic: one instantiation).
Eigen::VectorXd eigenvalues(const Eigen::MatrixXd& m) { return adaptobs::symmetric_eigenvalues(m); }

// A symmetric positive definite matrix with eigenvalues in [lo, hi].
template <class M>
M random_spd(RandomMatrices& rng, Index n, double lo, double hi) {
  const Eigen::MatrixXd q = adaptobs::testing::random_orthogonal(rng, n);
  Eigen::VectorXd d(n);
  for (Index i = 0; i < n; ++i) d(i) = rng.scalar(lo, hi);
  const Eigen::MatrixXd m = q * d.asDiagonal() * q.transpose();
  return (0.5 * (m + m.transpose())).cast<typename M::Scalar>();
}

// A stream of samples z = φᵀp (noise free), φ uniform in [−1, 1].
struct Stream {
  std::vector<Regressor> phi;
  std::vector<Vector2> z;
};
Stream random_stream(std::uint64_t seed, Index steps, const Vector4& p, double scale = 1.0) {
  RandomMatrices rng(seed);
  Stream s;
  for (Index t = 0; t < steps; ++t) {
    s.phi.push_back(scale * rng.uniform<Regressor>());
    s.z.push_back(s.phi.back().transpose() * p);
  }
  return s;
}

ADAPTOBS_TYPED_SUITE_IN_BOTH_PRECISIONS(RlsTyped);

// (21) is the inverse form (19) Γ_t⁻¹ = Γ_{t−1}⁻¹ + φR⁻¹φᵀ, (22) equals (20), and Γ is symmetric to the last bit.
TYPED_TEST(RlsTyped, RecursionMatchesInverseForm19AndUpdate20) {
  using S = TypeParam;
  using M4 = Eigen::Matrix<S, 4, 4>;
  using M2 = Eigen::Matrix<S, 2, 2>;
  RandomMatrices rng(19);
  const M4 gamma0 = random_spd<M4>(rng, 4, 0.5, 5.0);
  const M2 weight = random_spd<M2>(rng, 2, 0.5, 2.0);
  Rls<S> law(Eigen::Matrix<S, 4, 1>::Zero(), {gamma0, weight});
  const double tol = std::is_same_v<S, float> ? 2e-4 : 1e-12;
  for (int t = 0; t < 30; ++t) {
    const Eigen::Matrix<double, 4, 2> phi = rng.uniform<Eigen::Matrix<double, 4, 2>>();
    const Eigen::Vector2d z = rng.uniform<Eigen::Vector2d>();
    const Matrix4 before = law.covariance().template cast<double>();
    const Vector4 p_before = law.parameters().template cast<double>();
    ASSERT_TRUE(law.propose(phi.cast<S>(), z.cast<S>()));
    law.commit();
    const Eigen::Matrix2d r = weight.template cast<double>();
    const Matrix4 information = before.inverse() + phi * r.inverse() * phi.transpose();
    const Matrix4 expected = information.inverse();
    const Matrix4 gamma = law.covariance().template cast<double>();
    EXPECT_MATRIX_NEAR(gamma, expected, tol * expected.norm(), 0.0) << "step " << t;
    EXPECT_TRUE(adaptobs::testing::bitwise_equal(law.covariance(), law.covariance().transpose().eval()));
    // (20): p̂_t = p̂_{t−1} + Γ_t φ R⁻¹ (z − φᵀ p̂_{t−1}), valid when no reset intervenes.
    const Vector4 p20 = p_before + gamma * phi * r.inverse() * (z - phi.transpose() * p_before);
    EXPECT_MATRIX_NEAR(law.parameters().template cast<double>(), p20, tol * (1 + p20.norm()), 0.0);
  }
}

// The extracted text of (21) ends in Γ_t⁻¹: that matrix is neither symmetric nor the inverse form (19).
TEST(Rls, PrintedEquation21IsNotTheCovarianceRecursion) {
  RandomMatrices rng(21);
  const Matrix4 gamma = random_spd<Matrix4>(rng, 4, 0.5, 5.0);
  const Regressor phi = rng.uniform<Regressor>();
  const Eigen::Matrix2d w = (Eigen::Matrix2d::Identity() + phi.transpose() * gamma * phi).inverse();
  const Matrix4 printed = gamma - gamma * phi * w * phi.transpose() * gamma.inverse();
  const Matrix4 read = gamma - gamma * phi * w * phi.transpose() * gamma;
  const Matrix4 inverse_form = (gamma.inverse() + phi * phi.transpose()).inverse();
  EXPECT_LT((read - inverse_form).norm(), 1e-12 * inverse_form.norm());
  EXPECT_GT((printed - inverse_form).norm(), 1e-2 * inverse_form.norm());
  EXPECT_GT((printed - printed.transpose()).norm(), 1e-3 * printed.norm());
}

// Without resetting the recursion is the batch least-squares solution (18).
TEST(Rls, EqualsBatchLeastSquares18) {
  RandomMatrices rng(18);
  const Vector4 p = rng.uniform<Vector4>();
  const Vector4 p0 = rng.uniform<Vector4>();
  const Matrix4 gamma0 = random_spd<Matrix4>(rng, 4, 1.0, 100.0);
  const Eigen::Matrix2d weight = random_spd<Eigen::Matrix2d>(rng, 2, 0.5, 2.0);
  Rls<double> law(p0, {gamma0, weight});
  Matrix4 information = gamma0.inverse();
  Vector4 rhs = information * p0;
  const Stream data = random_stream(180, 300, p);
  for (std::size_t t = 0; t < data.phi.size(); ++t) {
    Vector2 z = data.z[t] + 0.1 * rng.uniform<Vector2>();  // noisy: (18) is then not p
    ASSERT_TRUE(law.propose(data.phi[t], z));
    law.commit();
    information += data.phi[t] * weight.inverse() * data.phi[t].transpose();
    rhs += data.phi[t] * weight.inverse() * z;
  }
  const Vector4 batch = information.ldlt().solve(rhs);
  EXPECT_MATRIX_NEAR(law.parameters(), batch, 1e-9 * batch.norm(), 0.0);
  EXPECT_MATRIX_NEAR(law.covariance(), Matrix4(information.inverse()), 1e-9 * law.covariance().norm(), 0.0);
  EXPECT_GT((law.parameters() - p).norm(), 1e-3) << "noise should keep (18) away from p";
}

// With forgetting, the recursion minimizes Σ λ^{t−i}‖z_i − φ_iᵀp‖²_{R⁻¹} + λ^t‖p − p̂₀‖²_{Γ₀⁻¹}.
TEST(ExponentialForgetting, EqualsWeightedBatchLeastSquares) {
  RandomMatrices rng(33);
  const double lambda = 0.9;
  const Vector4 p = rng.uniform<Vector4>();
  const Vector4 p0 = rng.uniform<Vector4>();
  const Matrix4 gamma0 = random_spd<Matrix4>(rng, 4, 1.0, 10.0);
  const Eigen::Matrix2d weight = random_spd<Eigen::Matrix2d>(rng, 2, 0.5, 2.0);
  Forgetting law(p0, {gamma0, weight, lambda});
  const Stream data = random_stream(330, 60, p);
  std::vector<Vector2> noisy;
  for (const Vector2& z : data.z) noisy.push_back(z + 0.1 * rng.uniform<Vector2>());
  for (std::size_t t = 0; t < noisy.size(); ++t) {
    ASSERT_TRUE(law.propose(data.phi[t], noisy[t]));
    law.commit();
  }
  const double steps = double(noisy.size());
  Matrix4 information = std::pow(lambda, steps) * gamma0.inverse();
  Vector4 rhs = information * p0;
  for (std::size_t i = 0; i < noisy.size(); ++i) {
    const double w = std::pow(lambda, steps - double(i + 1));
    information += w * data.phi[i] * weight.inverse() * data.phi[i].transpose();
    rhs += w * data.phi[i] * weight.inverse() * noisy[i];
  }
  const Vector4 batch = information.ldlt().solve(rhs);
  EXPECT_MATRIX_NEAR(law.parameters(), batch, 1e-9 * batch.norm(), 0.0);
  EXPECT_MATRIX_NEAR(law.covariance(), Matrix4(information.inverse()), 1e-9 * law.covariance().norm(), 0.0);
}

TEST(ExponentialForgetting, LambdaOneIsPlainRls) {
  RandomMatrices rng(1);
  const Matrix4 gamma0 = random_spd<Matrix4>(rng, 4, 1.0, 10.0);
  Forgetting forgetting(Vector4::Zero(), {gamma0, Eigen::Matrix2d::Identity(), 1.0});
  Rls<double> rls(Vector4::Zero(), {gamma0, Eigen::Matrix2d::Identity()});
  const Stream data = random_stream(11, 200, rng.uniform<Vector4>());
  for (std::size_t t = 0; t < data.phi.size(); ++t) {
    ASSERT_TRUE(forgetting.propose(data.phi[t], data.z[t]));
    ASSERT_TRUE(rls.propose(data.phi[t], data.z[t]));
    forgetting.commit();
    rls.commit();
  }
  EXPECT_MATRIX_NEAR(forgetting.parameters(), rls.parameters(), 1e-12, 1e-10);
  EXPECT_MATRIX_NEAR(forgetting.covariance(), rls.covariance(), 1e-12 * rls.covariance().norm(), 1e-9);
}

// Covariance windup: in the directions φ never reaches, Γ grows by exactly 1/λ per step.
TEST(ExponentialForgetting, CovarianceGrowsAsInverseLambdaWhereUnexcited) {
  const double lambda = std::sqrt(0.5);
  adaptobs::ExponentialForgettingRls<double, 4, 1> law(Vector4::Zero(),
                                                       {Matrix4::Identity(), Eigen::Matrix<double, 1, 1>(1.0), lambda});
  RandomMatrices rng(5);
  for (int t = 0; t < 200; ++t) {
    Vector4 phi = Vector4::Zero();
    phi.head<2>() = rng.uniform<Eigen::Vector2d>();  // only the first two directions are excited
    const double before = law.covariance()(3, 3);
    ASSERT_TRUE(law.propose(phi, Eigen::Matrix<double, 1, 1>(0.0)));
    law.commit();
    EXPECT_NEAR(law.covariance()(3, 3) / before, 1.0 / lambda, 1e-12);
  }
  EXPECT_GT(law.covariance()(3, 3), 1e29);  // √2^200 = 2^100
  EXPECT_LT((law.covariance().topLeftCorner<2, 2>().norm()), 10.0);
}

// The reset test decides λ_min(Γ) > bound exactly; a tie counts as a reset ("≤" in (23)).
TEST(CovarianceResetting, ResetTestIsExactAtTheThreshold) {
  const double kmin = 1e-4;
  RandomMatrices rng(23);
  const Eigen::MatrixXd q = adaptobs::testing::random_orthogonal(rng, 6);
  const auto rotated = [&](double smallest) {
    Eigen::VectorXd d(6);
    d << smallest, 0.3, 1.0, 7.0, 50.0, 1000.0;
    return Eigen::MatrixXd(q * d.asDiagonal() * q.transpose());
  };
  const Eigen::VectorXd diagonal = (Eigen::VectorXd(3) << kmin, 1.0, 2.0).finished();
  EXPECT_FALSE(adaptobs::smallest_eigenvalue_exceeds(Eigen::MatrixXd(diagonal.asDiagonal()), kmin));
  const Eigen::VectorXd above = (Eigen::VectorXd(3) << kmin * (1 + 1e-6), 1.0, 2.0).finished();
  EXPECT_TRUE(adaptobs::smallest_eigenvalue_exceeds(Eigen::MatrixXd(above.asDiagonal()), kmin));
  // Rotated: decided correctly down to a relative gap of 1e-7 of kmin at cond = 1e7.
  EXPECT_TRUE(adaptobs::smallest_eigenvalue_exceeds(rotated(kmin * (1 + 1e-7)), kmin));
  EXPECT_FALSE(adaptobs::smallest_eigenvalue_exceeds(rotated(kmin * (1 - 1e-7)), kmin));
  EXPECT_FALSE(adaptobs::smallest_eigenvalue_exceeds(rotated(-1.0), kmin));
  Eigen::MatrixXd nan = rotated(1.0);
  nan(3, 2) = nan(2, 3) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(adaptobs::smallest_eigenvalue_exceeds(nan, kmin)) << "a Cholesky pivot of NaN must not pass";
  // Against eigenvalues on random matrices.
  for (int i = 0; i < 200; ++i) {
    const Eigen::MatrixXd m = random_spd<Eigen::MatrixXd>(rng, 8, 1e-5, 1e3);
    const double lmin = eigenvalues(m)(0);
    EXPECT_TRUE(adaptobs::smallest_eigenvalue_exceeds(m, lmin * (1 - 1e-6)));
    EXPECT_FALSE(adaptobs::smallest_eigenvalue_exceeds(m, lmin * (1 + 1e-6)));
  }
}

// Runs a resetting law on a stream and checks, at every step, the decision of
// (23) against an independent computation of Γ̄ and its eigenvalues.
TEST(CovarianceResetting, ResetsExactlyWhenTheSmallestEigenvalueReachesKmin) {
  RandomMatrices rng(230);
  const Vector4 p = rng.uniform<Vector4>();
  const double k0 = 100.0, kmin = 1e-2;
  Resetting<double> law(Vector4::Zero(), {.k0 = k0, .kmin = kmin, .R = Eigen::Matrix2d::Identity()});
  const Stream data = random_stream(231, 5000, p, 3.0);
  Index resets = 0, ambiguous = 0;
  for (std::size_t t = 0; t < data.phi.size(); ++t) {
    const Regressor& phi = data.phi[t];
    const Matrix4 gamma = law.covariance();
    const Eigen::Matrix2d w = (Eigen::Matrix2d::Identity() + phi.transpose() * gamma * phi).inverse();
    const Matrix4 bar = gamma - gamma * phi * w * phi.transpose() * gamma;
    const double lmin = eigenvalues(bar)(0);
    ASSERT_TRUE(law.propose(phi, data.z[t]));
    law.commit();
    const double band = 1e-12 * k0;  // well above the rounding of Γ̄ (about 4ε k0)
    if (lmin <= kmin - band) {
      EXPECT_TRUE(law.reset_at_last_step()) << "step " << t << ": λ_min(Γ̄) = " << lmin;
    } else if (lmin > kmin + band) {
      EXPECT_FALSE(law.reset_at_last_step()) << "step " << t << ": λ_min(Γ̄) = " << lmin;
    } else {
      ++ambiguous;
    }
    resets += law.reset_at_last_step();
    if (law.reset_at_last_step()) {
      EXPECT_TRUE(law.covariance() == k0 * Matrix4::Identity());
    }
    // Γ_t stays inside (kmin, k0], and the screening bound is a true lower bound.
    const Eigen::VectorXd lambda = eigenvalues(law.covariance());
    EXPECT_GT(lambda(0), kmin);
    EXPECT_LE(lambda(3), k0 * (1 + 1e-12));
    EXPECT_LE(law.eigenvalue_lower_bound(), lambda(0) * (1 + 1e-12));
  }
  EXPECT_EQ(resets, law.reset_count());
  EXPECT_GT(resets, 200);
  EXPECT_LE(ambiguous, 1);
}

// Screening by the bound ℓ_t changes no decision and no bit, and saves most factorizations.
TEST(CovarianceResetting, ScreeningChangesNothingButTheCost) {
  RandomMatrices rng(7);
  const Vector4 p = rng.uniform<Vector4>();
  Resetting<double> screened(Vector4::Zero(), {.k0 = 1e3, .kmin = 1e-2, .R = Eigen::Matrix2d::Identity()});
  Resetting<double> unscreened(Vector4::Zero(),
                               {.k0 = 1e3, .kmin = 1e-2, .R = Eigen::Matrix2d::Identity(), .screen_reset_test = false});
  const Stream data = random_stream(70, 20000, p);
  for (std::size_t t = 0; t < data.phi.size(); ++t) {
    ASSERT_TRUE(screened.propose(data.phi[t], data.z[t]));
    ASSERT_TRUE(unscreened.propose(data.phi[t], data.z[t]));
    screened.commit();
    unscreened.commit();
    ASSERT_EQ(screened.reset_at_last_step(), unscreened.reset_at_last_step()) << "step " << t;
  }
  EXPECT_TRUE(adaptobs::testing::bitwise_equal(screened.parameters(), unscreened.parameters()));
  EXPECT_TRUE(adaptobs::testing::bitwise_equal(screened.covariance(), unscreened.covariance()));
  EXPECT_GT(screened.reset_count(), 50);
  EXPECT_EQ(unscreened.reset_tests_run(), Index(data.phi.size()));
  // Dense random regressors are the bound's worst case (it uses ‖φ‖_F² in every
  // direction); on the paper's example it settles three steps in four.
  EXPECT_LT(screened.reset_tests_run(), Index(data.phi.size()) * 9 / 10);
  RecordProperty("reset_tests_run", std::to_string(screened.reset_tests_run()));
}

// Normalized gradient: ‖p̃‖ never grows (noise free), and converges with a rich regressor.
TEST(NormalizedGradient, ErrorNeverGrowsAndConvergesWithExcitation) {
  RandomMatrices rng(9);
  const Vector4 p = rng.uniform<Vector4>();
  Gradient law(Vector4::Zero(), {.mu = 1.0, .offset = 0.1});
  const Stream data = random_stream(90, 3000, p);
  double previous = (p - law.parameters()).norm();
  for (std::size_t t = 0; t < data.phi.size(); ++t) {
    ASSERT_TRUE(law.propose(data.phi[t], data.z[t]));
    law.commit();
    const double error = (p - law.parameters()).norm();
    ASSERT_LE(error, previous * (1 + 1e-12) + 1e-15) << "step " << t;
    previous = error;
  }
  EXPECT_LT(previous, 1e-8);
}

// A regressor beyond about 10^154, whose ‖φ‖² overflows, still takes the step
// p + μφ(z − φᵀp)/(c + ‖φ‖²) (the step factor once underflowed to 0, and the
// proposal stood still while reported accepted). With z = φᵀp* and c ≪ ‖φ‖²,
// the step reaches p* along φ.
TEST(NormalizedGradient, ARegressorWhoseNormOverflowsStillTakesTheStep) {
  using ScalarLaw = adaptobs::NormalizedGradient<double, 1, 1>;
  using One = Eigen::Matrix<double, 1, 1>;
  for (const double scale : {1e100, 1e160, 1e300}) {
    ScalarLaw law(One::Zero(), {.mu = 1, .offset = 1});
    ASSERT_TRUE(law.propose(One(scale), One(2 * scale)));
    EXPECT_NEAR(law.proposal()(0), 2.0, 1e-15) << scale;
  }
  Gradient law(Vector4::Zero(), {.mu = 0.5, .offset = 1});
  Regressor phi = Regressor::Zero();
  phi(0, 0) = 3e200;
  phi(2, 1) = -4e200;
  const Vector4 target(1, -2, 3, 0.5);
  ASSERT_TRUE(law.propose(phi, Vector2(phi.transpose() * target)));
  // φ(φᵀp*)/‖φ‖² = (9/25·1, 0, 16/25·3, 0) for these two orthogonal columns.
  EXPECT_MATRIX_NEAR(law.proposal(), Vector4(0.5 * 9.0 / 25, 0, 0.5 * 16.0 / 25 * 3, 0), 1e-15, 1e-14);
}

// propose() leaves everything as it was until commit(); a NaN measurement is refused.
template <class Law>
void check_compute_then_commit(Law& law, const Regressor& phi, const Vector2& z) {
  const Vector4 before = law.parameters();
  ASSERT_TRUE(law.propose(phi, z));
  EXPECT_TRUE(adaptobs::testing::bitwise_equal(law.parameters(), before));
  const Vector4 proposal = law.proposal();
  EXPECT_FALSE(adaptobs::testing::bitwise_equal(proposal, before));
  law.commit();
  EXPECT_TRUE(adaptobs::testing::bitwise_equal(law.parameters(), proposal));
  const Vector4 after = law.parameters();
  EXPECT_FALSE(law.propose(phi, Vector2(std::numeric_limits<double>::quiet_NaN(), 0.0)));
  EXPECT_TRUE(adaptobs::testing::bitwise_equal(law.parameters(), after));
  law.restart(Vector4::Zero());
  EXPECT_TRUE(law.parameters().isZero());
}

TEST(AdaptationLaws, ProposeChangesNothingUntilCommit) {
  RandomMatrices rng(2);
  const Regressor phi = rng.uniform<Regressor>();
  const Vector2 z(0.3, -0.7);
  Rls<double> rls(Vector4::Zero(), {Matrix4::Identity(), Eigen::Matrix2d::Identity()});
  check_compute_then_commit(rls, phi, z);
  EXPECT_TRUE(rls.covariance() == Matrix4::Identity());
  Resetting<double> resetting(Vector4::Zero(), {.k0 = 10, .kmin = 1e-3, .R = Eigen::Matrix2d::Identity()});
  check_compute_then_commit(resetting, phi, z);
  EXPECT_TRUE(resetting.covariance() == 10 * Matrix4::Identity());
  EXPECT_EQ(resetting.reset_count(), 0);
  Forgetting forgetting(Vector4::Zero(), {Matrix4::Identity(), Eigen::Matrix2d::Identity(), 0.9});
  check_compute_then_commit(forgetting, phi, z);
  Gradient gradient(Vector4::Zero(), {});
  check_compute_then_commit(gradient, phi, z);
}

// A masked step is the law's step on the present sub-regression: the columns of
// φ, the entries of z and the block R_PP of R for the present set P. R couples
// the entries, so zeroing the absent ones alone would not give it. The masks run
// through all eight subsets of three entries; absent entries of z hold NaN.
TEST(AdaptationLaws, MaskedStepIsTheStepOnThePresentSubRegression) {
  using Dynamic = Eigen::MatrixXd;
  using DynamicRls = adaptobs::RecursiveLeastSquares<double, Eigen::Dynamic, Eigen::Dynamic>;
  using DynamicForgetting = adaptobs::ExponentialForgettingRls<double, Eigen::Dynamic, Eigen::Dynamic>;
  using DynamicGradient = adaptobs::NormalizedGradient<double, Eigen::Dynamic, Eigen::Dynamic>;
  RandomMatrices rng(14);
  const Index np = 5, nz = 3;
  const double lambda = 0.9;
  const Dynamic r = random_spd<Dynamic>(rng, nz, 0.2, 2.0);
  const Dynamic gamma0 = random_spd<Dynamic>(rng, np, 1.0, 10.0);
  const Eigen::VectorXd p0 = rng.uniform<Eigen::VectorXd>(np, 1);
  DynamicRls rls(p0, {gamma0, r});
  DynamicResetting resetting(p0, {.k0 = 5, .kmin = 1e-9, .R = r});
  DynamicForgetting forgetting(p0, {gamma0, r, lambda});
  DynamicGradient gradient(p0, {}, nz);
  for (Index t = 0; t < 48; ++t) {
    adaptobs::RegressionTypes<double, Eigen::Dynamic, Eigen::Dynamic>::Presence present(nz);
    std::vector<Index> kept;
    for (Index j = 0; j < nz; ++j) {
      present(j) = ((t >> j) & 1) != 0;
      if (present(j)) kept.push_back(j);
    }
    const Dynamic phi = rng.uniform<Dynamic>(np, nz);
    Eigen::VectorXd z = rng.uniform<Eigen::VectorXd>(nz, 1);
    for (Index j = 0; j < nz; ++j)
      if (!present(j)) z(j) = std::numeric_limits<double>::quiet_NaN();
    const Dynamic phi_p = phi(Eigen::all, kept);
    const Eigen::VectorXd z_p = z(kept);
    const Dynamic r_pp = r(kept, kept);
    const auto m = static_cast<Index>(kept.size());

    // All present must be the unmasked step: copies taken before the masked proposals.
    DynamicRls rls_plain = rls;
    DynamicForgetting forgetting_plain = forgetting;
    // The references: each law restarted from the current state on the sub-regression.
    if (m > 0) {
      DynamicRls rls_ref(rls.parameters(), {rls.covariance(), r_pp});
      DynamicRls resetting_ref(resetting.parameters(), {resetting.covariance(), r_pp});
      DynamicForgetting forgetting_ref(forgetting.parameters(), {forgetting.covariance(), r_pp, lambda});
      DynamicGradient gradient_ref(gradient.parameters(), {}, m);
      ASSERT_TRUE(rls_ref.propose(phi_p, z_p) && resetting_ref.propose(phi_p, z_p) &&
                  forgetting_ref.propose(phi_p, z_p) && gradient_ref.propose(phi_p, z_p));
      ASSERT_TRUE(rls.propose(phi, z, present) && resetting.propose(phi, z, present) &&
                  forgetting.propose(phi, z, present) && gradient.propose(phi, z, present));
      EXPECT_MATRIX_NEAR(rls.proposal(), rls_ref.proposal(), 1e-12, 1e-12) << "t = " << t;
      EXPECT_MATRIX_NEAR(rls.proposed_covariance(), rls_ref.proposed_covariance(), 1e-12, 1e-12) << "t = " << t;
      EXPECT_MATRIX_NEAR(resetting.proposal(), resetting_ref.proposal(), 1e-12, 1e-12) << "t = " << t;
      EXPECT_MATRIX_NEAR(resetting.proposed_covariance(), resetting_ref.proposed_covariance(), 1e-12, 1e-12);
      EXPECT_MATRIX_NEAR(forgetting.proposal(), forgetting_ref.proposal(), 1e-12, 1e-12) << "t = " << t;
      EXPECT_MATRIX_NEAR(forgetting.proposed_covariance(), forgetting_ref.proposed_covariance(), 1e-12, 1e-12);
      EXPECT_MATRIX_NEAR(gradient.proposal(), gradient_ref.proposal(), 1e-12, 1e-12) << "t = " << t;
    } else {  // no data: p unchanged; Γ unchanged, or divided by λ under forgetting
      ASSERT_TRUE(rls.propose(phi, z, present) && resetting.propose(phi, z, present) &&
                  forgetting.propose(phi, z, present) && gradient.propose(phi, z, present));
      EXPECT_TRUE(adaptobs::testing::bitwise_equal(rls.proposal(), rls.parameters()));
      EXPECT_TRUE(adaptobs::testing::bitwise_equal(rls.proposed_covariance(), rls.covariance()));
      EXPECT_TRUE(adaptobs::testing::bitwise_equal(resetting.proposal(), resetting.parameters()));
      EXPECT_TRUE(adaptobs::testing::bitwise_equal(forgetting.proposal(), forgetting.parameters()));
      EXPECT_MATRIX_NEAR(forgetting.proposed_covariance(), Dynamic(forgetting.covariance() / lambda), 1e-12, 1e-14);
      EXPECT_TRUE(adaptobs::testing::bitwise_equal(gradient.proposal(), gradient.parameters()));
    }
    if (m == nz) {  // all present: the unmasked step, bit for bit
      ASSERT_TRUE(rls_plain.propose(phi, z) && forgetting_plain.propose(phi, z));
      EXPECT_TRUE(adaptobs::testing::bitwise_equal(rls_plain.proposed_covariance(), rls.proposed_covariance()));
      EXPECT_TRUE(adaptobs::testing::bitwise_equal(forgetting_plain.proposal(), forgetting.proposal()));
    }
    rls.commit();
    resetting.commit();
    forgetting.commit();
    gradient.commit();
  }
  EXPECT_EQ(resetting.reset_count(), 0);  // the resetting law compared as plain RLS
  EXPECT_GT((rls.parameters() - p0).norm(), 0.1);
  // A run-time-sized mask of the wrong length is refused, naming it.
  const std::string message = adaptobs::testing::configuration_error_of([&] {
    (void)rls.propose(Dynamic::Zero(np, nz), Eigen::VectorXd::Zero(nz),
                      adaptobs::RegressionTypes<double, Eigen::Dynamic, Eigen::Dynamic>::Presence::Constant(2, true));
  });
  EXPECT_NE(message.find("'present'"), std::string::npos) << message;
}

TEST(AdaptationLaws, DynamicSizesGiveTheSameNumbersAsFixedSizes) {
  RandomMatrices rng(3);
  const Vector4 p = rng.uniform<Vector4>();
  Resetting<double> fixed(Vector4::Zero(), {.k0 = 1e3, .kmin = 1e-4, .R = Eigen::Matrix2d::Identity()});
  DynamicResetting dynamic(Eigen::VectorXd::Zero(4), {.k0 = 1e3, .kmin = 1e-4, .R = Eigen::MatrixXd::Identity(2, 2)});
  EXPECT_EQ(dynamic.parameter_count(), 4);
  EXPECT_EQ(dynamic.measurement_count(), 2);
  const Stream data = random_stream(30, 3000, p);
  for (std::size_t t = 0; t < data.phi.size(); ++t) {
    ASSERT_TRUE(fixed.propose(data.phi[t], data.z[t]));
    ASSERT_TRUE(dynamic.propose(Eigen::MatrixXd(data.phi[t]), Eigen::VectorXd(data.z[t])));
    fixed.commit();
    dynamic.commit();
  }
  EXPECT_EQ(fixed.reset_count(), dynamic.reset_count());
  EXPECT_MATRIX_NEAR(dynamic.parameters(), fixed.parameters(), 1e-12, 1e-12);
  EXPECT_MATRIX_NEAR(dynamic.covariance(), fixed.covariance(), 1e-10, 1e-12);
}

using adaptobs::testing::configuration_error_of;

TEST(AdaptationLaws, BadConfigurationNamesTheArgument) {
  const Vector4 p0 = Vector4::Zero();
  const Eigen::Matrix2d identity = Eigen::Matrix2d::Identity();
  Matrix4 non_symmetric = Matrix4::Identity();
  non_symmetric(0, 1) = 0.5;
  const Matrix4 indefinite = Eigen::Vector4d(1, 1, -1, 1).asDiagonal();
  Eigen::Matrix2d non_symmetric_r = identity;
  non_symmetric_r(1, 0) = 0.3;
  const Eigen::Matrix2d indefinite_r = Eigen::Vector2d(1, -2).asDiagonal();
  const Eigen::Matrix2d semidefinite_r = Eigen::Vector2d(1, 0).asDiagonal();

  EXPECT_CONFIGURATION_ERROR_NAMES(Rls<double>(p0, {non_symmetric, identity}), "gamma0");
  EXPECT_CONFIGURATION_ERROR_NAMES(Rls<double>(p0, {indefinite, identity}), "gamma0");
  EXPECT_CONFIGURATION_ERROR_NAMES(Rls<double>(p0, {Matrix4::Identity(), non_symmetric_r}), "R");
  EXPECT_CONFIGURATION_ERROR_NAMES(Rls<double>(p0, {Matrix4::Identity(), indefinite_r}), "R");
  EXPECT_CONFIGURATION_ERROR_NAMES(Rls<double>(Vector4(1, std::nan(""), 0, 0), {Matrix4::Identity(), identity}), "p0");
  EXPECT_CONFIGURATION_ERROR_NAMES(Forgetting(p0, {indefinite, identity, 0.9}), "gamma0");
  EXPECT_CONFIGURATION_ERROR_NAMES(Forgetting(p0, {non_symmetric, identity, 0.9}), "gamma0");
  EXPECT_CONFIGURATION_ERROR_NAMES(Forgetting(p0, {Matrix4::Identity(), semidefinite_r, 0.9}), "R");
  EXPECT_CONFIGURATION_ERROR_NAMES(Forgetting(p0, {Matrix4::Identity(), identity, 0.0}), "lambda");
  EXPECT_CONFIGURATION_ERROR_NAMES(Forgetting(p0, {Matrix4::Identity(), identity, 1.5}), "lambda");
  EXPECT_CONFIGURATION_ERROR_NAMES(Resetting<double>(p0, {.k0 = -1, .kmin = 1e-4, .R = identity}), "k0");
  EXPECT_CONFIGURATION_ERROR_NAMES(Resetting<double>(p0, {.k0 = 1, .kmin = 0, .R = identity}), "kmin");
  EXPECT_CONFIGURATION_ERROR_NAMES(Resetting<double>(p0, {.k0 = 1, .kmin = 2, .R = identity}), "kmin");
  EXPECT_CONFIGURATION_ERROR_NAMES(Resetting<double>(p0, {.k0 = 1, .kmin = 1e-3, .R = indefinite_r}), "R");
  EXPECT_CONFIGURATION_ERROR_NAMES(Resetting<double>(p0, {.k0 = 1, .kmin = 1e-3, .R = non_symmetric_r}), "R");
  EXPECT_CONFIGURATION_ERROR_NAMES(
      DynamicResetting(Eigen::VectorXd::Zero(4), {.k0 = 1, .kmin = 1e-3, .R = Eigen::MatrixXd::Identity(2, 2)}, 3),
      "R");
  EXPECT_CONFIGURATION_ERROR_NAMES(Gradient(p0, {.mu = 2.0, .offset = 1.0}), "mu");
  EXPECT_CONFIGURATION_ERROR_NAMES(Gradient(p0, {.mu = 1.0, .offset = 0.0}), "offset");
}

// With Eigen::Dynamic sizes a sample of the wrong size would be read past its end
// under NDEBUG: `propose` refuses it, naming phi or z, and the law is unchanged.
template <class Law>
void check_wrong_sample_sizes_refused(Law law) {
  const Eigen::MatrixXd phi = (Eigen::MatrixXd(4, 2) << 0.5, -0.2, 0.1, 0.7, -0.3, 0.4, 0.9, 0.05).finished();
  const Eigen::VectorXd z = Eigen::Vector2d(1.0, -0.5);
  ASSERT_TRUE(law.propose(phi, z));
  law.commit();
  ASSERT_TRUE(law.propose(phi, z));  // a proposal is pending; it must survive the refusals too
  const Eigen::VectorXd parameters = law.parameters(), proposal = law.proposal();
  EXPECT_CONFIGURATION_ERROR_NAMES(law.propose(Eigen::MatrixXd::Ones(3, 2), z), "phi");
  EXPECT_CONFIGURATION_ERROR_NAMES(law.propose(Eigen::MatrixXd::Ones(4, 3), z), "phi");
  EXPECT_CONFIGURATION_ERROR_NAMES(law.propose(phi, Eigen::VectorXd::Ones(1)), "z");
  EXPECT_CONFIGURATION_ERROR_NAMES(law.propose(phi, Eigen::VectorXd::Ones(3)), "z");
  EXPECT_TRUE(law.parameters() == parameters);
  EXPECT_TRUE(law.proposal() == proposal);
}

TEST(AdaptationLaws, WrongRunTimeSampleSizesAreRefusedAndChangeNothing) {
  using Vector = Eigen::VectorXd;
  using Matrix = Eigen::MatrixXd;
  constexpr int X = Eigen::Dynamic;
  const Matrix gamma0 = Matrix::Identity(4, 4), r = Matrix::Identity(2, 2);
  check_wrong_sample_sizes_refused(adaptobs::RecursiveLeastSquares<double, X, X>(Vector::Zero(4), {gamma0, r}));
  check_wrong_sample_sizes_refused(adaptobs::ExponentialForgettingRls<double, X, X>(Vector::Zero(4), {gamma0, r, 0.9}));
  check_wrong_sample_sizes_refused(DynamicResetting(Vector::Zero(4), {.k0 = 10, .kmin = 1e-3, .R = r}));
  check_wrong_sample_sizes_refused(adaptobs::NormalizedGradient<double, X, X>(Vector::Zero(4), {}, 2));
}

}  // namespace
