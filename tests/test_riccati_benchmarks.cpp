// The algebraic Riccati solvers on the published benchmark collections
// (P. Benner, A. J. Laub, V. Mehrmann, "A collection of benchmark examples for
// the numerical solution of algebraic Riccati equations", parts I (continuous,
// CAREX, SPC 95_22) and II (discrete, DAREX, SPC 95_23), TU Chemnitz-Zwickau
// 1995) and on hostile cases of their kind: each case is solved to a residual
// of 1e-10 with a stabilizing solution, checked here independently of the
// solver, or refused with the reason the case was built to have.

#include <adaptobs/design/care.hpp>
#include <adaptobs/design/dare.hpp>
#include <adaptobs/design/stability.hpp>

#include "support/eigen_testing.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <vector>

namespace {

using adaptobs::testing::configuration_error_of;
using Matrix = Eigen::MatrixXd;
using adaptobs::testing::solve_by_ldlt;

Matrix rows(int r, int c, std::initializer_list<double> entries) {
  Matrix m(r, c);
  auto it = entries.begin();
  for (int i = 0; i < r; ++i)
    for (int j = 0; j < c; ++j) m(i, j) = *it++;
  return m;
}

Matrix diagonal(std::initializer_list<double> entries) {
  return Eigen::VectorXd::Map(entries.begin(), static_cast<Eigen::Index>(entries.size())).asDiagonal();
}

Matrix scalar(double value) { return Matrix::Constant(1, 1, value); }

/// One benchmark: the data, the exact solution where the collection gives it,
/// and either the accuracy expected against it or the refusal expected.
struct RiccatiCase {
  std::string name;
  Matrix A, B, Q, R;
  Matrix exact = {};           ///< empty: the collection gives none
  double exact_tolerance = 0;  ///< relative Frobenius error allowed against `exact`
  std::string refusal = {};    ///< non-empty: the refusal must contain this text
};

// The residuals the solvers report (the DARE's scaled by its computed terms,
// the CARE's by the norms of their factors), computed here with LDLT instead of LLT.
double dare_residual(const Matrix& X, const RiccatiCase& c) {
  const Matrix btxa = c.B.transpose() * X * c.A;
  const Matrix correction = btxa.transpose() * solve_by_ldlt(c.R + c.B.transpose() * X * c.B, btxa);
  const Matrix ata = c.A.transpose() * X * c.A;
  return (ata - correction + c.Q - X).norm() / (X.norm() + ata.norm() + correction.norm() + c.Q.norm());
}

double care_residual(const Matrix& X, const RiccatiCase& c) {
  const Matrix g = c.B * solve_by_ldlt(c.R, c.B.transpose());
  const Matrix atx = c.A.transpose() * X;
  return (atx + atx.transpose() - X * g * X + c.Q).norm() /
         (2 * c.A.norm() * X.norm() + g.norm() * X.squaredNorm() + c.Q.norm());
}

double relative_error(const Matrix& X, const Matrix& exact) { return (X - exact).norm() / exact.norm(); }

void report(const RiccatiCase& c, const std::string& outcome) {
  std::printf("  %-44s %s\n", c.name.c_str(), outcome.c_str());
}

// The closed-loop figure of a solution, computed here with eigenvalues.
double dare_closed_loop_radius(const Matrix& X, const RiccatiCase& c) {
  const Matrix gain = solve_by_ldlt(c.R + c.B.transpose() * X * c.B, c.B.transpose() * X * c.A);
  return adaptobs::spectral_radius(Matrix(c.A - c.B * gain));
}

double care_closed_loop_abscissa(const Matrix& X, const RiccatiCase& c) {
  return adaptobs::spectral_abscissa(Matrix(c.A - c.B * solve_by_ldlt(c.R, c.B.transpose() * X)));
}

/// How the outcome of one kind of equation is checked: the residual computed
/// here, and the closed-loop figure that must lie below `stable_below`.
struct Check {
  double (*residual)(const Matrix&, const RiccatiCase&);
  double (*closed_loop)(const Matrix&, const RiccatiCase&);
  const char* figure;
  double stable_below;
};

const Check dare_check{dare_residual, dare_closed_loop_radius, "rho(A - BK)", 1.0};
const Check care_check{care_residual, care_closed_loop_abscissa, "abscissa(A - GX)", 0.0};

/// The case's expected refusal, or a solution with residual ≤ 1e-10 (computed
/// here and reported), a stable closed loop and, where the collection gives
/// one, the accuracy against the exact X.
template <class Solve>
void expect_outcome(const RiccatiCase& c, const Check& check, Solve solve) {
  if (!c.refusal.empty()) {
    const std::string message = configuration_error_of([&] { (void)solve(); });
    EXPECT_NE(message.find(c.refusal), std::string::npos) << c.name << ": " << message;
    report(c, "refused: " + message);
    return;
  }
  const auto solution = solve();
  const double residual = check.residual(solution.X, c);
  const double figure = check.closed_loop(solution.X, c);
  EXPECT_LE(residual, 1e-10) << c.name;
  EXPECT_LE(solution.relative_residual, 1e-10) << c.name;
  EXPECT_LT(figure, check.stable_below) << c.name;
  char line[160];
  std::snprintf(line, sizeof line, "residual %.1e (reported %.1e), %s %.6g", residual, solution.relative_residual,
                check.figure, figure);
  std::string outcome = line;
  if (c.exact.size()) {
    const double error = relative_error(solution.X, c.exact);
    EXPECT_LE(error, c.exact_tolerance) << c.name;
    std::snprintf(line, sizeof line, ", error against the exact X %.1e", error);
    outcome += line;
  }
  report(c, outcome);
}

void expect_dare_outcome(const RiccatiCase& c) {
  expect_outcome(c, dare_check, [&] { return adaptobs::solve_dare(c.A, c.B, c.Q, c.R); });
}

void expect_care_outcome(const RiccatiCase& c) {
  expect_outcome(c, care_check, [&] { return adaptobs::solve_care(c.A, c.B, c.Q, c.R); });
}

const double golden = (1 + std::sqrt(5.0)) / 2;

// Householder reflector I − (2/3)11ᵀ of DAREX 13 and CAREX 12.
Matrix reflector() { return Matrix::Identity(3, 3) - (2.0 / 3.0) * Matrix::Ones(3, 3); }

std::vector<RiccatiCase> darex_collection() {
  std::vector<RiccatiCase> cases;
  const Matrix q1 = rows(2, 2, {9, 6, 6, 4});
  cases.push_back({"DAREX 1", rows(2, 2, {4, 3, -4.5, -3.5}), rows(2, 1, {1, -1}), q1, scalar(1), golden * q1, 1e-13});
  cases.push_back({"DAREX 2", diagonal({0.9512, 0.9048}), rows(2, 2, {4.877, 4.877, -1.1895, 3.569}),
                   diagonal({0.005, 0.02}), diagonal({1.0 / 3.0, 3})});
  // R = 0 and, in example 4, a cross term S with a singular R: outside the
  // equation the library solves, which needs R positive definite.
  cases.push_back({"DAREX 3 (R = 0)",
                   rows(2, 2, {2, -1, 1, 0}),
                   rows(2, 1, {1, 0}),
                   diagonal({0, 1}),
                   scalar(0),
                   {},
                   0,
                   "argument 'R' must be positive definite"});
  cases.push_back({"DAREX 4 (singular R)",
                   rows(2, 2, {0, 1, 0, -1}),
                   rows(2, 2, {1, 0, 2, 1}),
                   rows(2, 2, {-4.0 / 11, -4.0 / 11, -4.0 / 11, 7.0 / 11}),
                   rows(2, 2, {9, 3, 3, 1}),
                   {},
                   0,
                   "argument 'Q' must be positive semidefinite"});
  cases.push_back({"DAREX 5", rows(2, 2, {0, 1, 0, 0}), rows(2, 1, {0, 1}), rows(2, 2, {1, 2, 2, 4}), scalar(1),
                   rows(2, 2, {1, 2, 2, 2 + std::sqrt(5.0)}), 1e-14});
  {
    Matrix a = 0.998 * Matrix::Identity(4, 4);
    a(0, 1) = 0.067, a(1, 0) = -0.067, a(2, 3) = 0.153, a(3, 2) = -0.153;
    cases.push_back({"DAREX 6", a, rows(4, 2, {0.0033, 0.02, 0.1, -0.0007, 0.04, 0.0073, -0.0028, 0.1}),
                     rows(4, 4, {1.87, 0, 0, -0.244, 0, 0.744, 0.205, 0, 0, 0.205, 0.589, 0, -0.244, 0, 0, 1.048}),
                     Matrix::Identity(2, 2)});
  }
  cases.push_back({"DAREX 7",
                   rows(4, 4,
                        {0.98475, -0.079903, 0.0009054, -0.0010765, 0.041588, 0.99899, -0.035855, 0.012684, -0.54662,
                         0.044916, -0.32991, 0.19318, 2.6624, -0.10045, -0.92455, -0.26325}),
                   rows(4, 2, {0.0037112, 0.0007361, -0.087051, 9.3411e-6, -1.19844, -4.1378e-4, -3.1927, 9.2535e-4}),
                   0.01 * Matrix::Identity(4, 4), Matrix::Identity(2, 2)});
  {
    Matrix upper_ones = Matrix::Zero(4, 4);
    for (int i = 0; i < 4; ++i) upper_ones.row(i).tail(4 - i).setOnes();
    const Matrix b = -upper_ones + 2 * Matrix::Identity(4, 4);
    Matrix c = upper_ones;
    c(0, 2) += 1, c(1, 3) += 1, c(3, 3) += 3;
    const Matrix q0 = rows(4, 4, {2, -1, 0, 0, -1, 2, -1, 0, 0, -1, 2, 0, 0, 0, 0, 0});
    const Matrix l = rows(4, 4, {0.4, 0, 0, 0, 1, 0.6, 0, 0, 0, 1, 0.8, 0, 0, 0, 0, -0.999982});
    cases.push_back({"DAREX 8", b * l * c, b, c.transpose() * q0 * c, Matrix::Identity(4, 4)});
  }
  cases.push_back({"DAREX 9", 0.01 * rows(5, 5, {95.407, 1.9643, 0.3597, 0.0673, 0.019, 40.849, 41.317, 16.084, 4.4679,
                                                 1.1971, 12.217, 26.326, 36.149, 15.93, 12.383, 4.1118, 12.858, 27.209,
                                                 21.442, 40.976, 0.1305, 0.5808, 1.875, 3.6162, 94.28}),
                   0.01 * rows(5, 2, {0.0434, -0.0122, 2.6606, -1.0453, 3.753, -5.51, 3.6076, -6.6, 0.4617, -0.9148}),
                   Matrix::Identity(5, 5), Matrix::Identity(2, 2)});
  {
    // Example 10 has a cross term S = CᵀD; with R nonsingular it is the
    // equation without one for A − BR⁻¹Sᵀ and Q − SR⁻¹Sᵀ (= Cᵀ(I − DR⁻¹Dᵀ)C ⪰ 0).
    Matrix a = Matrix::Zero(6, 6);
    a(0, 1) = a(1, 2) = a(3, 4) = a(4, 5) = 1;
    Matrix b = Matrix::Zero(6, 2);
    b(2, 0) = b(5, 1) = 1;
    const Matrix c = rows(2, 6, {1, 1, 0, 0, 0, 0, 0, 0, 0, 1, -1, 0});
    const Matrix d = rows(2, 2, {1, 0, 1, 0});
    const Matrix r = Matrix::Identity(2, 2) + d.transpose() * d;
    const Matrix s = c.transpose() * d;
    const Matrix r_inv_st = solve_by_ldlt(r, s.transpose());
    Matrix q = c.transpose() * c - s * r_inv_st;
    q = 0.5 * (q + q.transpose()).eval();
    cases.push_back({"DAREX 10 (cross term removed)", a - b * r_inv_st, b, q, r});
  }
  {
    Matrix a =
        0.001 *
        rows(9, 9, {870.1,  135.0,  11.59,  0.5014, -37.22, 0.3484, 0.0,    4.242,  7.249,  76.55,  897.4,  12.72,
                    0.5504, -40.16, 0.3743, 0.0,    4.53,   7.499,  -127.2, 357.5,  817.0,  1.455,  -102.8, 0.987,
                    0.0,    11.85,  18.72,  -363.5, 633.9,  74.91,  796.6,  -273.5, 2.653,  0.0,    31.72,  48.82,
                    -960.0, 1645.9, -128.9, -5.597, 71.42,  7.108,  0.0,    84.52,  125.9,  -664.4, 112.96, -88.89,
                    -3.854, 84.47,  13.6,   0.0,    144.3,  101.6,  -410.2, 693.0,  -54.71, -2.371, 66.49,  12.49,
                    0.1063, 99.97,  69.67,  -179.9, 301.7,  -23.93, -1.035, 60.59,  22.16,  0.0,    213.9,  35.54,
                    -345.1, 580.4,  -45.96, -1.989, 105.6,  19.86,  0.0,    219.1,  215.2});
    const Matrix b = 0.0001 * rows(3, 9, {4.76,    0.879,  1.482,  3.892,  10.34,  7.203,  4.454,  1.971,  3.773,
                                          -0.5701, -4.773, -13.12, -35.13, -92.75, -61.59, -36.83, -15.54, -30.28,
                                          -83.68,  -2.73,  8.876,  24.8,   66.8,   38.34,  20.29,  6.937,  14.69})
                                  .transpose();
    Matrix q = Matrix::Zero(9, 9);
    q(0, 0) = q(4, 4) = 50;
    cases.push_back({"DAREX 11", a, b, q, Matrix::Identity(3, 3)});
  }
  for (double d : {1e6, 1e8}) {
    cases.push_back({"DAREX 12, d = " + std::to_string(static_cast<long long>(d)), rows(2, 2, {0, d, 0, 0}),
                     rows(2, 1, {0, 1}), Matrix::Identity(2, 2), scalar(1), diagonal({1, 1 + d * d}), 1e-14});
  }
  {
    const double d = 1e6;
    const Matrix u = reflector();
    cases.push_back({"DAREX 13, d = 1e6", u * diagonal({0, 1, 3}) * u, Matrix::Identity(3, 3),
                     d * Matrix::Identity(3, 3), d * Matrix::Identity(3, 3),
                     d * u * diagonal({1, golden, (9 + std::sqrt(85.0)) / 2}) * u, 1e-13});
  }
  for (double tau : {1e4, 1e8}) {
    // alpha = 1 − D/τ, beta = KD/τ with D = K = 1, r = 0.25.
    const double r = 0.25, alpha = 1 - 1 / tau, beta = 1 / tau;
    Matrix a = Matrix::Zero(4, 4);
    a(0, 0) = alpha, a(1, 0) = a(2, 1) = a(3, 2) = 1;
    const double dd = r * tau * tau, d = (alpha + 1) * (alpha - 1);
    Matrix x = Matrix::Identity(4, 4);
    x(0, 0) = dd * d / 2 + 0.5 + std::sqrt(0.25 * (dd * d + 1) * (dd * d + 1) + dd);
    cases.push_back({"DAREX 14, tau = " + std::to_string(static_cast<long long>(tau)), a, rows(4, 1, {beta, 0, 0, 0}),
                     diagonal({0, 0, 0, 1}), scalar(r), x, 1e-8});
  }
  {
    const int n = 100;
    Matrix a = Matrix::Zero(n, n);
    a.diagonal(1).setOnes();
    Matrix b = Matrix::Zero(n, 1);
    b(n - 1, 0) = 1;
    cases.push_back({"DAREX 15, n = 100", a, b, Matrix::Identity(n, n), scalar(1),
                     Eigen::VectorXd::LinSpaced(n, 1, n).asDiagonal().toDenseMatrix(), 1e-14});
  }
  return cases;
}

std::vector<RiccatiCase> carex_collection() {
  std::vector<RiccatiCase> cases;
  cases.push_back({"CAREX 1", rows(2, 2, {0, 1, 0, 0}), rows(2, 1, {0, 1}), diagonal({1, 2}), scalar(1),
                   rows(2, 2, {2, 1, 1, 2}), 1e-14});
  const Matrix q2 = rows(2, 2, {9, 6, 6, 4});
  cases.push_back({"CAREX 2", rows(2, 2, {4, 3, -4.5, -3.5}), rows(2, 1, {1, -1}), q2, scalar(1),
                   (1 + std::sqrt(2.0)) * q2, 1e-13});
  // The Q of example 3 is printed to three digits and has an eigenvalue of
  // -5.1e-4: as given, it is indefinite.
  cases.push_back(
      {"CAREX 3 (printed Q indefinite)",
       rows(4, 4, {0, 1, 0, 0, 0, -1.89, 0.39, -5.53, 0, -0.034, -2.98, 2.43, 0.034, -0.0011, -0.99, -0.21}),
       rows(4, 2, {0, 0, 0.36, -1.6, -0.95, -0.032, 0.03, 0}),
       rows(4, 4,
            {2.313, 2.727, 0.688, 0.023, 2.727, 4.271, 1.148, 0.323, 0.688, 1.148, 0.313, 0.102, 0.023, 0.323, 0.102,
             0.083}),
       Matrix::Identity(2, 2),
       {},
       0,
       "argument 'Q' must be positive semidefinite"});
  {
    Matrix a = Matrix::Zero(8, 8);
    a.diagonal() << -0.991, -1.051, -1.118, -1.548, -1.640, -1.721, -1.823, -1.943;
    a.diagonal(1) << 0.529, 0.596, 0.596, 0.718, 0.799, 0.901, 1.021;
    a.diagonal(-1) << 0.522, 0.522, 0.522, 0.922, 0.922, 0.922, 0.922;
    const Matrix b = 0.001 * rows(2, 8,
                                  {3.84, 4.00, 37.60, 3.08, 2.36, 2.88, 3.08, 3.00, -2.88, -3.04, -2.80, -2.32, -3.32,
                                   -3.82, -4.12, -3.96})
                                 .transpose();
    const Matrix q0 = rows(4, 4, {0.5, 0, 0, 0.1, 0.1, 0, 0, 0, 0, 0.5, 0, 0, 0, 0, 0, 0});
    Matrix q(8, 8);
    q << Matrix::Identity(4, 4), q0, q0.transpose(), 0.1 * Matrix::Identity(4, 4);
    // As printed, this Q has eigenvalues -0.137 and -0.123.
    cases.push_back({"CAREX 4 (printed Q indefinite)",
                     a,
                     b,
                     q,
                     Matrix::Identity(2, 2),
                     {},
                     0,
                     "argument 'Q' must be positive semidefinite"});
  }
  cases.push_back(
      {"CAREX 5",
       rows(9, 9, {-4.019,  5.12,   0,      0,       -2.082,  0,      0,      0,      0.87,   -0.346, 0.986, 0,
                   0,       -2.34,  0,      0,       0,       0.97,   -7.909, 15.407, -4.069, 0,      -6.45, 0,
                   0,       0,      2.68,   -21.816, 35.606,  -0.339, -3.87,  -17.8,  0,      0,      0,     7.39,
                   -60.196, 98.188, -7.907, 0.34,    -53.008, 0,      0,      0,      20.4,   0,      0,     0,
                   0,       94.0,   -147.2, 0,       53.2,    0,      0,      0,      0,      0,      0,     94.0,
                   -147.2,  0,      0,      0,       0,       0,      0,      0,      12.8,   0,      -31.6, 0,
                   0,       0,      0,      0,       12.8,    0,      0,      18.8,   -31.6}),
       rows(3, 9, {0.010, 0.003, 0.009, 0.024, 0.068,  0, 0, 0, 0, -0.011, -0.021, -0.059, -0.162, -0.445,
                   0,     0,     0,     0,     -0.151, 0, 0, 0, 0, 0,      0,      0,      0})
           .transpose(),
       Matrix::Identity(9, 9), Matrix::Identity(3, 3)});
  {
    const double d = 1e-6, dd = d * d, s = std::sqrt(1 + dd), s2 = 2 + s;
    cases.push_back({"CAREX 7, d = 1e-6", diagonal({1, -2}), rows(2, 1, {d, 0}), Matrix::Ones(2, 2), scalar(1),
                     rows(2, 2, {(1 + s) / dd, 1 / s2, 1 / s2, (1 - dd / (s2 * s2)) / 4}), 1e-10});
  }
  {
    const double d = 1e-8;
    cases.push_back({"CAREX 8, d = 1e-8", diagonal({-0.1, -0.02}), rows(2, 2, {0.1, 0, 0.001, 0.01}),
                     rows(2, 2, {100, 1000, 1000, 10000}), rows(2, 2, {1 + d, 1, 1, 1})});
  }
  for (double d : {1e6, 1e9}) {
    const double s = std::sqrt(1 + 2 * d);
    cases.push_back({"CAREX 9, d = " + std::to_string(static_cast<long long>(d)), rows(2, 2, {0, d, 0, 0}),
                     rows(2, 1, {0, 1}), Matrix::Identity(2, 2), scalar(1), rows(2, 2, {s / d, 1, 1, s}), 1e-12});
  }
  {
    const double d = 1e-7, d1 = d + 1;
    const double x1 = (2 * d1 + std::sqrt(2 * d1 * d1 + 2) + std::sqrt(2.0) * d) / 2, x2 = x1 / (x1 - d1);
    cases.push_back({"CAREX 10, d = 1e-7", rows(2, 2, {d1, 1, 1, d1}), Matrix::Identity(2, 2),
                     d * d * Matrix::Identity(2, 2), Matrix::Identity(2, 2), rows(2, 2, {x1, x2, x2, x1}), 1e-9});
  }
  // Example 11 has an indefinite Q, outside the equation solve_care solves
  // (solve_riccati_hamiltonian takes it: see HamiltonianSolverTakesIndefiniteQ).
  cases.push_back({"CAREX 11 (Q indefinite)",
                   rows(2, 2, {3, 1, 4, 2}),
                   rows(2, 1, {1, 1}),
                   rows(2, 2, {-11, -5, -5, -2}),
                   scalar(1),
                   {},
                   0,
                   "argument 'Q' must be positive semidefinite"});
  {
    const double d = 1e6, dd = d * d;
    const Matrix c = reflector();
    const Matrix x = c *
                     diagonal({dd + std::sqrt(1 + dd * dd), 2 * dd + std::sqrt(d + 4 * dd * dd),
                               3 * dd + d * std::sqrt(1 + 9 * dd)}) *
                     c;
    Matrix q = c * diagonal({1 / d, 1, d}) * c;
    q = 0.5 * (q + q.transpose()).eval();
    cases.push_back({"CAREX 12, d = 1e6", d * (c * diagonal({1, 2, 3}) * c), Matrix::Identity(3, 3), q,
                     d * Matrix::Identity(3, 3), x, 1e-10});
  }
  {
    const double d = 1e-6;
    cases.push_back({"CAREX 13, d = 1e-6",
                     rows(4, 4, {0, 0.4, 0, 0, 0, 0, 0.345, 0, 0, -0.524 / d, -0.465 / d, 0.262 / d, 0, 0, 0, -1 / d}),
                     rows(4, 1, {0, 0, 0, 1 / d}), diagonal({1, 0, 1, 0}), scalar(1)});
  }
  {
    // Two oscillators of the same frequency, one damped by d and one excited
    // by d, and a single input: at d = 0 the eigenvalues ±i are double and no
    // single input reaches both, so (A, B) is not stabilizable; for small d
    // the stabilizing closed loop keeps a pair within 1e-12 of the axis,
    // which the working precision cannot tell from a pair on it.
    auto oscillators = [](double d) { return rows(4, 4, {-d, 1, 0, 0, -1, -d, 0, 0, 0, 0, d, 1, 0, 0, -1, d}); };
    cases.push_back({"CAREX 14, d = 1e-6",
                     oscillators(1e-6),
                     Matrix::Ones(4, 1),
                     Matrix::Ones(4, 4),
                     scalar(1),
                     {},
                     0,
                     "too ill-conditioned for this precision"});
    cases.push_back({"CAREX 14, d = 0",
                     oscillators(0),
                     Matrix::Ones(4, 1),
                     Matrix::Ones(4, 4),
                     scalar(1),
                     {},
                     0,
                     "argument 'A, B' must be stabilizable"});
  }
  {
    const int l = 20, n = 2 * l - 1;
    Matrix a = Matrix::Zero(n, n), b = Matrix::Zero(n, l), c = Matrix::Zero(l - 1, n);
    for (int i = 0; i < l - 1; ++i) {
      const int j = 2 * i + 1, k = 2 * i;
      a(k, k) = -1, a(j, k) = 1, a(j, j + 1) = -1, b(k, i) = 1, c(i, j) = 1;
    }
    a(n - 1, n - 1) = -1, b(n - 1, l - 1) = 1;
    cases.push_back({"CAREX 15, l = 20", a, b, 10 * c.transpose() * c, Matrix::Identity(l, l)});
  }
  {
    const int n = 64;
    Matrix a = -2 * Matrix::Identity(n, n);
    a.diagonal(1).setOnes(), a.diagonal(-1).setOnes();
    a(n - 1, 0) = a(0, n - 1) = 1;
    // X is circulant: its first column is the inverse DFT of su (real and even).
    Eigen::VectorXd su(n), first(n);
    for (int k = 0; k < n; ++k) {
      const double c = std::cos(2 * std::numbers::pi * k / n);
      su(k) = -2 + 2 * c + std::sqrt(5 - 8 * c + 4 * c * c);
    }
    for (int k = 0; k < n; ++k) {
      double sum = 0;
      for (int j = 0; j < n; ++j) sum += su(j) * std::cos(2 * std::numbers::pi * j * k / n);
      first(k) = sum / n;
    }
    Matrix x(n, n);
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) x(i, j) = first(std::abs(i - j));
    cases.push_back(
        {"CAREX 16, n = 64", a, Matrix::Identity(n, n), Matrix::Identity(n, n), Matrix::Identity(n, n), x, 1e-13});
  }
  {
    const int n = 21;
    Matrix a = Matrix::Zero(n, n), b = Matrix::Zero(n, 1), q = Matrix::Zero(n, n);
    a.diagonal(1).setOnes();
    b(n - 1, 0) = 1, q(0, 0) = 1;
    cases.push_back({"CAREX 17, n = 21", a, b, q, scalar(1)});
  }
  {
    const int l = 30, n = 2 * l;
    const double mu = 4, delta = 4, kappa = 1;
    Matrix stiffness = 2 * Matrix::Identity(l, l);
    stiffness(0, 0) = stiffness(l - 1, l - 1) = 1;
    stiffness.diagonal(1).setConstant(-1), stiffness.diagonal(-1).setConstant(-1);
    Matrix a = Matrix::Zero(n, n);
    a.topRightCorner(l, l).setIdentity();
    a.bottomLeftCorner(l, l) = -kappa / mu * stiffness;
    a.bottomRightCorner(l, l) = -delta / mu * Matrix::Identity(l, l);
    Matrix b = Matrix::Zero(n, 2);
    b(l, 0) = 1 / mu, b(n - 1, 1) = -1 / mu;
    cases.push_back({"CAREX 19, l = 30", a, b, Matrix::Identity(n, n), Matrix::Identity(2, 2)});
  }
  return cases;
}

TEST(RiccatiBenchmarks, CarexCollection) {
  std::printf("CAREX (Benner, Laub, Mehrmann 1995):\n");
  for (const RiccatiCase& c : carex_collection()) expect_care_outcome(c);
}

TEST(RiccatiBenchmarks, DarexCollection) {
  std::printf("DAREX (Benner, Laub, Mehrmann 1995):\n");
  for (const RiccatiCase& c : darex_collection()) expect_dare_outcome(c);
}

// Regression cases of the hostile kind: a tiny or huge R, badly scaled data,
// and refusals that must give the true reason in the caller's terms.

TEST(RiccatiHostile, DareWithTinyRMatchesSixtyDigitReferences) {
  // A = diag(1.2, 0.5), B = [1; 1], Q = I. References: Riccati iteration to
  // convergence in 60-digit arithmetic (mpmath), rounded to 17 digits.
  struct Reference {
    double r, x00, x01, x11;
  };
  const Reference references[] = {
      {1e-10, 2.6514606740013496563, -0.68810861412124808053, 1.2867119225563613073},
      {1e-14, 2.6514606739127466324, -0.68810861413030649875, 1.2867119225542949586},
      {1e-300, 2.6514606739127377712, -0.68810861413030740469, 1.286711922554294752},
  };
  for (const Reference& ref : references) {
    const RiccatiCase c{"tiny R",
                        diagonal({1.2, 0.5}),
                        rows(2, 1, {1, 1}),
                        Matrix::Identity(2, 2),
                        scalar(ref.r),
                        rows(2, 2, {ref.x00, ref.x01, ref.x01, ref.x11}),
                        1e-13};
    expect_dare_outcome(c);
  }
}

TEST(RiccatiHostile, DareWithHugeRIsAccurateNormwise) {
  // R = 1e300: X is of order R (X00 = 4.4e299, exactly r (a² − 1) / b² to leading
  // order); without scaling, the doubling overflows.
  const RiccatiCase c{"huge R", diagonal({1.2, 0.5}), rows(2, 1, {1, 1}), Matrix::Identity(2, 2), scalar(1e300)};
  const auto solution = adaptobs::solve_dare(c.A, c.B, c.Q, c.R);
  EXPECT_NEAR(solution.X(0, 0) / 4.4e299, 1.0, 1e-14);
  // Entries far below ‖X‖ carry accuracy relative to ‖X‖ only: against the
  // 60-digit X (X01 = −0.41905, X11 = 1.33333), the error is at rounding
  // relative to X00 (norms taken entry by entry: ‖X‖_F² would overflow).
  const double worst = std::max({std::abs(solution.X(0, 0) - 4.4e299), std::abs(solution.X(0, 1) + 0.41904761904761905),
                                 std::abs(solution.X(1, 1) - 1.3333333333333333)});
  EXPECT_LE(worst / 4.4e299, 1e-14);
  EXPECT_LE(solution.relative_residual, 1e-15);
}

TEST(RiccatiHostile, DareResidualDoesNotReadLargeWhenHugeTermsCancel) {
  // A11 = 1 − 1e6: AᵀXA is of order 1e30 and cancels against the correction.
  // The unscaled residual ‖X − Ric(X)‖/‖X‖ of an accurate solution reads
  // 1.2e-4; scaled per term it is rounding. 60-digit reference (mpmath).
  // Terms of 1e30 cancel to X00 = 2e18, so a residual at rounding level (an
  // absolute 1e14 in those terms) pins X00 down only to about 1e-4 relative:
  // X's normwise error depends on the rounding of the doubling steps, from 2e-14
  // to 3e-4 as a11 moves by 0.5 ... 4e4 around 1 − 1e6. The normwise bound says
  // only that the answer is the right one; X01 and X11 are checked entry by entry.
  const RiccatiCase c{"a = 1 - 1e6",
                      diagonal({1 - 1e6, 0.3}),
                      rows(2, 1, {1e-3, 1}),
                      Matrix::Identity(2, 2),
                      scalar(1),
                      rows(2, 2, {2.0460072683098997e+18, 313803140.30803836, 313803140.30803836, 1.0941410500370998}),
                      1e-3};
  expect_dare_outcome(c);
  const auto solution = adaptobs::solve_dare(c.A, c.B, c.Q, c.R);
  EXPECT_LE(solution.relative_residual, 1e-15);
  EXPECT_NEAR(solution.X(0, 1), c.exact(0, 1), 1e-9 * c.exact(0, 1));
  EXPECT_NEAR(solution.X(1, 1), c.exact(1, 1), 1e-9 * c.exact(1, 1));
}

TEST(RiccatiHostile, DareRefusalsNameTheTrueReason) {
  const Matrix identity = Matrix::Identity(2, 2);
  auto dare_error = [](const Matrix& a, const Matrix& b, const Matrix& q, const Matrix& r,
                       adaptobs::DareOptions options = {}) {
    return configuration_error_of([&] { (void)adaptobs::solve_dare(a, b, q, r, options); });
  };
  // Mode 1 on the unit circle, reached by B but unobserved by Q: no stabilizing solution.
  EXPECT_NE(dare_error(diagonal({1, 0.5}), identity, diagonal({0, 1}), identity)
                .find("argument 'A, Q' leave a mode of A on the unit circle unobserved by Q"),
            std::string::npos);
  // The same mode observed but not reached by B.
  EXPECT_NE(dare_error(diagonal({1, 0.5}), rows(2, 1, {0, 1}), identity, scalar(1))
                .find("argument 'A, B' must be stabilizable"),
            std::string::npos);
  // An unstable mode unobserved by Q is not a reason to refuse: B moves it to
  // its mirror image 1/2 (X00 = 3 solves x = 4x − 4x²/(1 + x)).
  const auto undetectable = adaptobs::solve_dare(diagonal({2, 0.5}), identity, diagonal({0, 1}), identity);
  EXPECT_NEAR(undetectable.X(0, 0), 3.0, 1e-14);
  // Mode 1 on the circle again, with a mode inside: the Newton steps converge
  // only linearly towards a closed loop with radius 1, which the margin rejects.
  EXPECT_NE(dare_error(diagonal({1, 0.9}), identity, diagonal({0, 1}), identity)
                .find("argument 'A, Q' leave a mode of A on the unit circle unobserved by Q"),
            std::string::npos);
  // An unobserved mode outside the circle is no reason to refuse: when an
  // impossible demand makes the solver refuse, it does not blame that mode.
  // (The demand is on the closed loop, ρ < 0.001: Newton's steps can drive the
  // computed residual of this diagonal case to exactly zero.)
  adaptobs::DareOptions strict;
  strict.stability_margin = 0.999;
  const std::string outside = dare_error(diagonal({2, 0.5}), identity, diagonal({0, 1}), identity, strict);
  EXPECT_NE(outside.find("too ill-conditioned"), std::string::npos) << outside;
  // A residual tolerance no solution can meet: the refusal says so, with the figures.
  adaptobs::DareOptions impossible;
  impossible.residual_tolerance = 1e-300;
  const std::string message = dare_error(diagonal({1.2, 0.5}), rows(2, 1, {1, 1}), identity, scalar(1), impossible);
  EXPECT_NE(message.find("argument 'A, B, Q, R' give a Riccati equation too ill-conditioned"), std::string::npos)
      << message;
  EXPECT_NE(message.find("at most 1e-300 required"), std::string::npos) << message;
}

TEST(RiccatiHostile, KalmanGainRefusalsSpeakOfCAndTheNoise) {
  const Matrix identity = Matrix::Identity(2, 2);
  auto kalman_error = [](const Matrix& a, const Matrix& c, const Matrix& q, const Matrix& r) {
    return configuration_error_of([&] { (void)adaptobs::steady_state_kalman_gain(a, c, q, r); });
  };
  EXPECT_NE(kalman_error(diagonal({1.2, 0.5}), rows(1, 2, {0, 1}), identity, scalar(1))
                .find("steady_state_kalman_gain: argument 'A, C' must be detectable"),
            std::string::npos);
  EXPECT_NE(kalman_error(diagonal({0.5, 0.5}), rows(1, 2, {std::nan(""), 1}), identity, scalar(1))
                .find("steady_state_kalman_gain: argument 'C' must contain only finite numbers"),
            std::string::npos);
  EXPECT_NE(kalman_error(diagonal({1, 0.5}), identity, diagonal({0, 1}), identity)
                .find("argument 'A, Q' leave a mode of A on the unit circle unexcited by the process noise Q"),
            std::string::npos);
  auto bucy_error = [](const Matrix& a, const Matrix& c, const Matrix& q, const Matrix& r) {
    return configuration_error_of([&] { (void)adaptobs::kalman_bucy_gain(a, c, q, r); });
  };
  EXPECT_NE(bucy_error(diagonal({1, -1}), rows(1, 2, {0, 1}), identity, scalar(1))
                .find("kalman_bucy_gain: argument 'A, C' must be detectable"),
            std::string::npos);
  EXPECT_NE(bucy_error(rows(2, 2, {0, 1, 0, 0}), rows(1, 2, {std::nan(""), 0}), identity, scalar(1))
                .find("kalman_bucy_gain: argument 'C' must contain only finite numbers"),
            std::string::npos);
}

TEST(RiccatiHostile, CareOnBadlyScaledStatesAndUndampedOscillators) {
  // CAREX 1 in the states x = S x̃, S = diag(1, s): X = S⁻ᵀ X₀ S⁻¹ with X₀ = [2 1; 1 2].
  for (double s : {1e3, 1e9, 1e12}) {
    const Matrix scaling = diagonal({1, s}), inverse = diagonal({1, 1 / s});
    const RiccatiCase c{"CAREX 1 scaled",
                        scaling * rows(2, 2, {0, 1, 0, 0}) * inverse,
                        scaling * rows(2, 1, {0, 1}),
                        inverse * diagonal({1, 2}) * inverse,
                        scalar(1),
                        inverse * rows(2, 2, {2, 1, 1, 2}) * inverse,
                        1e-14};
    expect_care_outcome(c);
  }
  // An undamped oscillator (eigenvalues ±i) driven through its velocity is
  // stabilizable: solved.
  expect_care_outcome(
      {"undamped oscillator", rows(2, 2, {0, 1, -1, 0}), rows(2, 1, {0, 1}), Matrix::Identity(2, 2), scalar(1)});
  // Its mode unobserved by Q: no stabilizing solution, and the reason.
  expect_care_outcome({"oscillator unobserved by Q",
                       rows(3, 3, {0, 1, 0, -1, 0, 0, 0, 0, -1}),
                       Matrix::Identity(3, 3),
                       diagonal({0, 0, 1}),
                       Matrix::Identity(3, 3),
                       {},
                       0,
                       "argument 'A, Q' leave a mode of A on the imaginary axis unobserved by Q"});
  // Not reached by B at all.
  expect_care_outcome({"oscillator without input",
                       rows(2, 2, {0, 1, -1, 0}),
                       Matrix::Zero(2, 1),
                       Matrix::Identity(2, 2),
                       scalar(1),
                       {},
                       0,
                       "argument 'A, B' must be stabilizable"});
  // A stable mode at −1e-9 that B does not reach leaves (A, B) stabilizable:
  // solved, or refused as ill-conditioned, but never as unstabilizable.
  const std::string slow = configuration_error_of([&] {
    (void)adaptobs::solve_care(diagonal({-1e-9, -1}), rows(2, 1, {0, 1}), Matrix::Identity(2, 2), scalar(1));
  });
  EXPECT_EQ(slow.find("stabilizable"), std::string::npos) << slow;
  // The discrete counterpart: a rotation (eigenvalues on the unit circle) reached by B.
  const double angle = 0.3;
  expect_dare_outcome({"rotation", rows(2, 2, {std::cos(angle), std::sin(angle), -std::sin(angle), std::cos(angle)}),
                       rows(2, 1, {0, 1}), Matrix::Identity(2, 2), scalar(1)});
}

// Smith's doubling stopped once no term exceeded ε·max|X|, so the entries of a
// small diagonal block were summed to the largest entry's accuracy: with
// W = diag(1, 1e-20) and F = diag(0.1, 0.999), X(1, 1) read 1.58e-19 for 5.0e-18.
TEST(RiccatiHostile, SteinDoublingSumsEverySemidefiniteEntryToItsOwnScale) {
  const Matrix x = adaptobs::solve_stein_doubling<double>(diagonal({0.1, 0.999}), diagonal({1, 1e-20}));
  EXPECT_NEAR(x(0, 0) * (1 - 0.01), 1.0, 1e-14);
  EXPECT_NEAR(x(1, 1) * (1 - 0.999 * 0.999) / 1e-20, 1.0, 1e-12);
}

TEST(RiccatiHostile, EmptyStateAndNoInput) {
  EXPECT_EQ(adaptobs::solve_dare(Matrix(0, 0), Matrix(0, 1), Matrix(0, 0), scalar(1)).X.size(), 0);
  EXPECT_EQ(adaptobs::solve_care(Matrix(0, 0), Matrix(0, 1), Matrix(0, 0), scalar(1)).X.size(), 0);
  // No input: X solves the Stein (Lyapunov) equation when A is stable, and
  // (A, B) is not stabilizable when it is not.
  const auto stein = adaptobs::solve_dare(diagonal({0.5, 0.2}), Matrix(2, 0), Matrix::Identity(2, 2), Matrix(0, 0));
  EXPECT_MATRIX_NEAR(stein.X, diagonal({1 / 0.75, 1 / 0.96}), 0, 1e-14);
  const auto lyapunov = adaptobs::solve_care(diagonal({-1, -2}), Matrix(2, 0), Matrix::Identity(2, 2), Matrix(0, 0));
  EXPECT_MATRIX_NEAR(lyapunov.X, diagonal({0.5, 0.25}), 0, 1e-14);
  EXPECT_NE(configuration_error_of([] {
              (void)adaptobs::solve_dare(diagonal({1.5, 0.2}), Matrix(2, 0), Matrix::Identity(2, 2), Matrix(0, 0));
            }).find("argument 'A, B' must be stabilizable"),
            std::string::npos);
}

// The Hamiltonian solver takes an indefinite Q (and G): X = I is the stabilizing
// solution of AᵀX + XA − XGX + Q = 0 for Q = −(Aᵀ + A − G), here indefinite,
// since A − G has the double eigenvalue −1.
TEST(RiccatiHostile, HamiltonianSolverTakesIndefiniteQ) {
  const Matrix a = rows(2, 2, {1, 2, 0, -1}), g = Matrix::Ones(2, 2);
  const Matrix q = -(a.transpose() + a - g);
  ASSERT_LT(q.determinant(), 0);  // indefinite
  const auto x = adaptobs::solve_riccati_hamiltonian(a, g, q);
  ASSERT_TRUE(x.has_value());
  EXPECT_MATRIX_NEAR(x->X, Matrix::Identity(2, 2), 1e-13, 0);
  EXPECT_LE(x->relative_residual, 1e-14);
  // With G = −I too, a negative quadratic term: the solution is checked by its
  // residual and by its closed loop A − GX.
  const Matrix a2 = rows(2, 2, {-3, 1, 0, -2}), g2 = -Matrix::Identity(2, 2), q2 = rows(2, 2, {1, 0.5, 0.5, -0.2});
  const auto x2 = adaptobs::solve_riccati_hamiltonian(a2, g2, q2);
  ASSERT_TRUE(x2.has_value());
  const Matrix residual = a2.transpose() * x2->X + x2->X * a2 - x2->X * g2 * x2->X + q2;
  EXPECT_LE(residual.norm(), 1e-13);
  EXPECT_TRUE(adaptobs::is_hurwitz_stable(Matrix(a2 - g2 * x2->X)));

  // Arguments that are not square, finite, of one size or symmetric are refused by name.
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_CONFIGURATION_ERROR_NAMES(adaptobs::solve_riccati_hamiltonian(Matrix::Zero(2, 3), g, q), "A");
  EXPECT_CONFIGURATION_ERROR_NAMES(adaptobs::solve_riccati_hamiltonian(rows(2, 2, {1, nan, 0, -1}), g, q), "A");
  EXPECT_CONFIGURATION_ERROR_NAMES(adaptobs::solve_riccati_hamiltonian(a, Matrix::Ones(3, 3), q), "G");
  EXPECT_CONFIGURATION_ERROR_NAMES(adaptobs::solve_riccati_hamiltonian(a, rows(2, 2, {1, 2, 0, 1}), q), "G");
  EXPECT_CONFIGURATION_ERROR_NAMES(adaptobs::solve_riccati_hamiltonian(a, g, Matrix::Zero(2, 1)), "Q");
  EXPECT_CONFIGURATION_ERROR_NAMES(adaptobs::solve_riccati_hamiltonian(a, g, rows(2, 2, {1, 0, 0, nan})), "Q");
  EXPECT_CONFIGURATION_ERROR_NAMES(adaptobs::solve_riccati_hamiltonian(a, g, q, 0), "max_iterations");
}

}  // namespace
