// The non-template test helpers of eigen_testing.hpp, compiled once for all
// test executables.

#include "support/eigen_testing.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <Eigen/QR>

#include <cmath>
#include <sstream>

namespace adaptobs::testing {

::testing::AssertionResult dense_matrices_near(const char* a_expr, const char* b_expr, const Eigen::MatrixXd& a,
                                               const Eigen::MatrixXd& b, double abs_tol, double rel_tol) {
  if (a.rows() != b.rows() || a.cols() != b.cols()) {
    return ::testing::AssertionFailure() << a_expr << " is " << a.rows() << "x" << a.cols() << " but " << b_expr
                                         << " is " << b.rows() << "x" << b.cols();
  }
  double worst = 0;
  Eigen::Index wi = 0, wj = 0;
  bool ok = true;
  for (Eigen::Index j = 0; j < a.cols(); ++j) {
    for (Eigen::Index i = 0; i < a.rows(); ++i) {
      const double allowed = abs_tol + rel_tol * std::abs(b(i, j));
      const double err = std::abs(a(i, j) - b(i, j));
      if (!(err <= allowed)) {
        ok = false;
        if (!(err <= worst)) {
          worst = err;
          wi = i;
          wj = j;
        }
      }
    }
  }
  if (ok) return ::testing::AssertionSuccess();
  std::ostringstream os;
  os.precision(17);
  os << a_expr << " and " << b_expr << " differ (abs tol " << abs_tol << ", rel tol " << rel_tol << "); worst at ("
     << wi << "," << wj << "): " << a(wi, wj) << " vs " << b(wi, wj) << "\n"
     << a_expr << " =\n"
     << a << "\n"
     << b_expr << " =\n"
     << b;
  return ::testing::AssertionFailure() << os.str();
}

Eigen::MatrixXd random_orthogonal(RandomMatrices& rng, Eigen::Index n) {
  return Eigen::HouseholderQR<Eigen::MatrixXd>(rng.uniform<Eigen::MatrixXd>(n, n)).householderQ() *
         Eigen::MatrixXd::Identity(n, n);
}

Eigen::MatrixXd solve_by_ldlt(const Eigen::MatrixXd& m, const Eigen::MatrixXd& b) { return m.ldlt().solve(b); }

Eigen::MatrixXd solve_by_llt(const Eigen::MatrixXd& m, const Eigen::MatrixXd& b) { return m.llt().solve(b); }

Eigen::MatrixXd symmetric_exponential(const Eigen::MatrixXd& m) {
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(m);
  return eig.eigenvectors() * eig.eigenvalues().array().exp().matrix().asDiagonal() * eig.eigenvectors().transpose();
}

Eigen::Index lu_rank(const Eigen::MatrixXd& m) { return Eigen::FullPivLU<Eigen::MatrixXd>(m).rank(); }

::testing::AssertionResult quotes_argument(const std::string& message, std::string_view argument) {
  std::string quoted;
  quoted.reserve(argument.size() + 2);
  quoted.append(1, '\'').append(argument).append(1, '\'');
  if (message.find(quoted) != std::string::npos) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "the message does not name " << quoted << ": " << message;
}

}  // namespace adaptobs::testing
