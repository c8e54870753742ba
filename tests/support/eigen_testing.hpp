#pragma once
// Test helpers shared by every test: matrix comparisons with per-scalar
// tolerances, seeded random draws, and a geometric-rate fit.

#include <adaptobs/core/validation.hpp>

#include <gtest/gtest.h>
#include <Eigen/Core>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <random>
#include <string>
#include <string_view>
#include <vector>

namespace adaptobs::testing {

/// float and double, the precisions every observer is tested in.
using BothPrecisions = ::testing::Types<float, double>;

/// Tolerances that scale with the scalar's precision.
template <typename S>
struct Tolerance {
  static constexpr S eps = std::numeric_limits<S>::epsilon();
  /// Round-off level of a short computation.
  static constexpr S tight = std::is_same_v<S, float> ? S(1e-4) : S(1e-10);
  /// What a converged observer should reach in a noise-free run.
  static constexpr S converged = std::is_same_v<S, float> ? S(1e-3) : S(1e-9);
};

/// |a − b| ≤ abs_tol + rel_tol·|b| entrywise, in double; prints both matrices on
/// failure. One function for every comparison, compiled once (eigen_testing.cpp):
/// the template below only converts its arguments.
::testing::AssertionResult dense_matrices_near(const char* a_expr, const char* b_expr, const Eigen::MatrixXd& a,
                                               const Eigen::MatrixXd& b, double abs_tol, double rel_tol);

template <class DA, class DB>
::testing::AssertionResult matrices_near(const char* a_expr, const char* b_expr, const char* /*abs_expr*/,
                                         const char* /*rel_expr*/, const Eigen::MatrixBase<DA>& a,
                                         const Eigen::MatrixBase<DB>& b, double abs_tol, double rel_tol) {
  return dense_matrices_near(a_expr, b_expr, a.template cast<double>(), b.template cast<double>(), abs_tol, rel_tol);
}

#define EXPECT_MATRIX_NEAR(a, b, abs_tol, rel_tol) \
  EXPECT_PRED_FORMAT4(::adaptobs::testing::matrices_near, a, b, abs_tol, rel_tol)
#define ASSERT_MATRIX_NEAR(a, b, abs_tol, rel_tol) \
  ASSERT_PRED_FORMAT4(::adaptobs::testing::matrices_near, a, b, abs_tol, rel_tol)

/// Exact equality of every bit (used to check that rejected updates change nothing).
template <class DA, class DB>
bool bitwise_equal(const Eigen::MatrixBase<DA>& a, const Eigen::MatrixBase<DB>& b) {
  if (a.rows() != b.rows() || a.cols() != b.cols()) return false;
  for (Eigen::Index j = 0; j < a.cols(); ++j)
    for (Eigen::Index i = 0; i < a.rows(); ++i)
      if (std::memcmp(&a.derived().coeffRef(i, j), &b.derived().coeffRef(i, j), sizeof(a(i, j))) != 0) return false;
  return true;
}

/// Seeded source of random matrices.
class RandomMatrices {
 public:
  explicit RandomMatrices(std::uint64_t seed) : rng_(seed) {}
  template <class M>
  M uniform(Eigen::Index rows, Eigen::Index cols, double lo = -1, double hi = 1) {
    std::uniform_real_distribution<double> d(lo, hi);
    M m(rows, cols);
    for (Eigen::Index j = 0; j < cols; ++j)
      for (Eigen::Index i = 0; i < rows; ++i) m(i, j) = static_cast<typename M::Scalar>(d(rng_));
    return m;
  }
  template <class M>
  M uniform() {
    return uniform<M>(M::RowsAtCompileTime, M::ColsAtCompileTime);
  }
  double scalar(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng_); }
  std::mt19937_64& engine() { return rng_; }

 private:
  std::mt19937_64 rng_;
};

/// A random orthogonal n × n matrix: the Q factor of a uniform random matrix
/// (compiled once, eigen_testing.cpp, so that no test instantiates a QR for it).
Eigen::MatrixXd random_orthogonal(RandomMatrices& rng, Eigen::Index n);

/// \f$M^{-1}B\f$ for a symmetric M, by Eigen's LDLT (semidefinite M) or LLT
/// (positive definite M): the reference solves of the tests, compiled once.
Eigen::MatrixXd solve_by_ldlt(const Eigen::MatrixXd& m, const Eigen::MatrixXd& b);
Eigen::MatrixXd solve_by_llt(const Eigen::MatrixXd& m, const Eigen::MatrixXd& b);
/// \f$e^M = Qe^\Lambda Q^T\f$ of a symmetric M from Eigen's symmetric
/// eigendecomposition: a reference independent of any matrix exponential.
Eigen::MatrixXd symmetric_exponential(const Eigen::MatrixXd& m);
/// Numerical rank by Eigen's full-pivoting LU with its default threshold.
Eigen::Index lu_rank(const Eigen::MatrixXd& m);

/// Least-squares fit of log(e_k) = c + k log(ρ) over the given samples;
/// returns the geometric rate ρ (ρ < 1: the sequence decays geometrically).
inline double fit_geometric_rate(const std::vector<double>& errors) {
  double n = 0, sk = 0, sl = 0, skk = 0, skl = 0;
  for (std::size_t k = 0; k < errors.size(); ++k) {
    const double l = std::log(errors[k]);
    n += 1;
    sk += double(k);
    sl += l;
    skk += double(k) * double(k);
    skl += double(k) * l;
  }
  const double slope = (n * skl - sk * sl) / (n * skk - sk * sk);
  return std::exp(slope);
}

/// The message of the `ConfigurationError` that `f()` throws, or "<no exception>":
/// tests assert that a bad argument is refused and that the message names it.
template <class F>
std::string configuration_error_of(F&& f) {
  try {
    f();
  } catch (const ConfigurationError& e) {
    return e.what();
  }
  return "<no exception>";
}

/// Success when `message` quotes `argument` as the library does ('mu'); the
/// failure shows the message.
::testing::AssertionResult quotes_argument(const std::string& message, std::string_view argument);

}  // namespace adaptobs::testing

/// Expects `expression` to throw a `ConfigurationError` whose message names
/// `argument` as the library quotes it: EXPECT_CONFIGURATION_ERROR_NAMES(f(0), "mu")
/// looks for 'mu'.
#define EXPECT_CONFIGURATION_ERROR_NAMES(expression, argument) \
  EXPECT_TRUE(::adaptobs::testing::quotes_argument(            \
      ::adaptobs::testing::configuration_error_of([&] { (void)(expression); }), argument))

/// A typed test suite `Suite` run in both precisions: `TYPED_TEST(Suite, Name)`
/// then sees the scalar as `TypeParam`.
#define ADAPTOBS_TYPED_SUITE_IN_BOTH_PRECISIONS(Suite) \
  template <typename S>                                \
  class Suite : public ::testing::Test {};             \
  TYPED_TEST_SUITE(Suite, ::adaptobs::testing::BothPrecisions)
