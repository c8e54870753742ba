// Compile-time benchmark, hand-written side: the README's usage program with
// Eigen alone — the steady-state Kalman gain by the structure-preserving
// doubling algorithm, the Guyader–Zhang update (2a)–(2c) with the second output
// missing one sample in seven (its rows of C set to zero), ten updates, and the
// two diagnostics (‖√μ C Υ‖₂; smallest eigenvalue of the average of μ ΥᵀCᵀCΥ
// over the last 100 steps). Paired with examples/readme_usage.cpp.

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <limits>

int main() {
  Eigen::Matrix4d A, H;
  A << 1, 0.1, 0, 3.49e-6, 3.66e-8, 1, 0, 6.98e-5, -4.25e-14, -3.49e-6, 1, 0.1, -1.28e-12, -6.98e-5, 0, 1;
  H << 0.1, 0.005, 0, 1.16e-7, 1.83e-9, 0.1, 0, 3.49e-6, -1.06e-15, -1.16e-7, 0.1, 0.005, -4.25e-14, -3.49e-6, 0, 0.1;
  Eigen::Matrix<double, 2, 4> C;
  C << 1, 0, 0, 0, 0, 0, 1, 0;
  const Eigen::Vector2d theta{1.0, 1.5};
  const Eigen::Matrix4d Q = Eigen::Matrix4d::Identity() * 1e-4;
  const Eigen::Matrix2d R = Eigen::Matrix2d::Identity() * 1e-2;

  // Dual DARE (Aᵀ, Cᵀ, Q, R) by doubling: a ← Aᵀ, g ← CᵀR⁻¹C, h ← Q; then K = A P Cᵀ (C P Cᵀ + R)⁻¹.
  Eigen::Matrix4d a = A.transpose(), g = C.transpose() * R.llt().solve(C), h = Q;
  for (int j = 0; j < 100; ++j) {
    const Eigen::PartialPivLU<Eigen::Matrix4d> w(Eigen::Matrix4d::Identity() + g * h);
    const Eigen::Matrix4d w_inv_a = w.solve(a), w_inv_g = w.solve(g);
    const Eigen::Matrix4d h_next = h + a.transpose() * h * w_inv_a;
    const Eigen::Matrix4d g_next = g + a * w_inv_g * a.transpose();
    a = a * w_inv_a;
    const double change = (h_next - h).norm();
    h = 0.5 * (h_next + h_next.transpose());
    g = 0.5 * (g_next + g_next.transpose());
    if (change <= 100 * std::numeric_limits<double>::epsilon() * std::max(1.0, h.norm())) break;
  }
  const Eigen::Matrix<double, 4, 2> K = (C * h * C.transpose() + R).llt().solve(C * h * A.transpose()).transpose();

  const double mu = 4.0;
  const Eigen::Matrix4d closed_loop = A - K * C;
  Eigen::Vector4d xhat{0.9, 0, 0, 3.14e-4};
  Eigen::Vector2d thetahat{0.5, 0.5};
  Eigen::Matrix<double, 4, 2> upsilon = Eigen::Matrix<double, 4, 2>::Zero();
  Eigen::Matrix2d cu, window[100];                     // C Υ of the last step; μ ΥᵀCᵀCΥ of the last 100 steps
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig;  // closed form for 2 × 2
  double norm2 = 0;
  Eigen::Vector4d x{1, 0, 0, 3.49e-4};
  int k = 0;
  for (; k < 10; ++k) {
    const Eigen::Vector2d u{k % 100 < 10 ? 1.0 : 0.0, (k + 50) % 100 < 10 ? 1.0 : 0.0};
    Eigen::Matrix<double, 4, 2> Psi;
    Psi << H.col(1) * u(0), H.col(3) * u(1);
    Eigen::Vector2d e = C * x - C * xhat;
    x = A * x + Psi * theta;
    cu = C * upsilon;
    const bool second_present = k % 7 != 3;  // the second sensor loses one sample in seven
    if (!second_present) {
      e(1) = 0;
      cu.row(1).setZero();
    }
    const Eigen::Vector2d step = mu * cu.transpose() * e;  // (2b)
    upsilon = second_present ? Eigen::Matrix<double, 4, 2>(closed_loop * upsilon + Psi)
                             : Eigen::Matrix<double, 4, 2>(A * upsilon - K * cu + Psi);  // (2a)
    xhat = A * xhat + Psi * thetahat + K * e + upsilon * step;                           // (2c)
    thetahat += step;
    window[k % 100] = mu * cu.transpose() * cu;
    norm2 = std::sqrt(eig.computeDirect(window[k % 100], Eigen::EigenvaluesOnly).eigenvalues()(1));
    if (norm2 > 1) std::cerr << "mu too large for the current regressor\n";
  }
  double alpha = 0;  // only once the window is full
  if (k >= 100) {
    Eigen::Matrix2d gramian = Eigen::Matrix2d::Zero();
    for (const Eigen::Matrix2d& gi : window) gramian += gi;
    alpha = eig.computeDirect(gramian / 100, Eigen::EigenvaluesOnly).eigenvalues()(0);
  }
  const Eigen::IOFormat row(17, Eigen::DontAlignCols, " ", " ");
  std::cout << std::setprecision(17) << "K " << K.format(row) << '\n'
            << "xhat " << xhat.format(row) << '\n'
            << "thetahat " << thetahat.format(row) << '\n'
            << "assumption2_norm " << norm2 << '\n'
            << "excitation_level " << alpha << '\n';
}
