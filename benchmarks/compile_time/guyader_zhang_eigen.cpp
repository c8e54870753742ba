// Compile-time benchmark, hand-written side: the Guyader–Zhang observer (paper
// 000, eq. (2a)–(2c)) at the satellite's sizes with fixed-size Eigen types, the
// same 1000 updates and the same two diagnostics (assumption 2: ‖√μ C Υ‖;
// assumption 3: smallest eigenvalue of the average of μ ΥᵀCᵀCΥ over 100 steps).
// Paired with guyader_zhang_observer.cpp.

#include <Eigen/Dense>

#include <cmath>
#include <cstdio>

int main() {
  Eigen::Matrix4d A, H;
  A << 1.000000001827015, 0.099999999979699827, 0, 3.4899999996457628e-06,                    //
      3.6540299992582279e-08, 0.99999999939099504, 0, 6.9799999985830497e-05,                  //
      -4.2508548997411251e-14, -3.4899999996457632e-06, 1, 0.099999999918799348,               //
      -1.2752564698705613e-12, -6.9799999985830497e-05, 0, 0.99999999756398017;
  H << 0.10000000006090048, 0.0049999999994924963, 0, 1.163333333262486e-07,                   //
      1.8270149998145573e-09, 0.099999999979699841, 0, 3.4899999996457628e-06,                 //
      -1.0627137249568544e-15, -1.1633333332624865e-07, 0.10000000000000001, 0.0049999999979699851,  //
      -4.2508548997411239e-14, -3.4899999996457632e-06, 0, 0.099999999918799348;
  Eigen::Matrix<double, 2, 4> C;
  C << 1, 0, 0, 0,  //
      0, 0, 1, 0;
  Eigen::Matrix<double, 4, 2> K;
  K << 0.1412, 4.93e-6, 0.0932, 5.26e-5, -4.93e-6, 0.1412, -5.26e-5, 0.0932;
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
    const Eigen::Vector2d u(k % 100 < 10, k >= 50 && (k - 50) % 100 < 10);
    Eigen::Matrix<double, 4, 2> psi;
    psi << H.col(1) * u(0), H.col(3) * u(1);
    const Eigen::Vector2d y = C * x;
    x = A * x + psi * theta;

    const Eigen::Vector2d e = y - C * xhat;
    cu = C * upsilon;
    const Eigen::Vector2d step = mu * cu.transpose() * e;   // (2b)
    upsilon = closed_loop * upsilon + psi;                  // (2a)
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
