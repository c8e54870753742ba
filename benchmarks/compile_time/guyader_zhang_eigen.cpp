// Compile-time benchmark, hand-written side: the Guyader–Zhang observer (Guyader
// & Zhang 2003, eq. (2a)–(2c)) at the satellite's sizes with fixed-size Eigen types, the
// same 1000 updates and the same two diagnostics (assumption 2: ‖√μ C Υ‖;
// assumption 3: smallest eigenvalue of the average of μ ΥᵀCᵀCΥ over 100 steps).
// Paired with guyader_zhang_observer.cpp.

#include <Eigen/Dense>

#include "satellite_problem.hpp"

#include <cmath>
#include <cstdio>

int main() {
  const SatelliteProblem problem = satellite_problem();
  const Eigen::Matrix4d& A = problem.A;
  const Eigen::Matrix<double, 2, 4>& C = problem.C;
  const Eigen::Matrix<double, 4, 2>& K = problem.K;
  const double mu = 4.0;
  const Eigen::Matrix4d closed_loop = A - K * C;

  Eigen::Vector4d xhat(0.9, 0, 0, 3.14e-4);
  Eigen::Vector2d thetahat(0.5, 0.5);
  Eigen::Matrix<double, 4, 2> upsilon = Eigen::Matrix<double, 4, 2>::Zero();
  Eigen::Matrix2d cu = Eigen::Matrix2d::Zero();  // C Υ of the last step
  Eigen::Matrix2d window[100];                   // μ ΥᵀCᵀCΥ of the last 100 steps

  const Eigen::Vector2d theta(1, 1.5);
  Eigen::Vector4d x(1, 0, 0, 3.49e-4);
  for (int k = 0; k < 1000; ++k) {
    const Eigen::Matrix<double, 4, 2> psi = satellite_regressor(problem, satellite_input(k));
    const Eigen::Vector2d y = C * x;
    x = A * x + psi * theta;

    const Eigen::Vector2d e = y - C * xhat;
    cu = C * upsilon;
    const Eigen::Vector2d step = mu * cu.transpose() * e;       // (2b)
    upsilon = closed_loop * upsilon + psi;                      // (2a)
    xhat = A * xhat + psi * thetahat + K * e + upsilon * step;  // (2c), B = 0
    thetahat += step;
    window[k % 100] = mu * cu.transpose() * cu;
  }

  Eigen::Matrix2d gramian = Eigen::Matrix2d::Zero();
  for (const Eigen::Matrix2d& g : window) gramian += g;
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig;  // closed form for 2 × 2
  const double norm2 = std::sqrt(eig.computeDirect(mu * cu.transpose() * cu, Eigen::EigenvaluesOnly).eigenvalues()(1));
  const double alpha = eig.computeDirect(gramian / 100, Eigen::EigenvaluesOnly).eigenvalues()(0);
  std::printf("xhat %.17g %.17g %.17g %.17g\n", xhat(0), xhat(1), xhat(2), xhat(3));
  std::printf("thetahat %.17g %.17g\n", thetahat(0), thetahat(1));
  std::printf("assumption2_norm %.17g\n", norm2);
  std::printf("excitation_level %.17g\n", alpha);
}
