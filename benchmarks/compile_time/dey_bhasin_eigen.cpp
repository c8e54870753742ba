// Compile-time benchmark, hand-written side: the Dey–Bhasin adaptive observer
// (Dey & Bhasin 2022, filters (8)–(13), RLS with covariance resetting (22)–(23)) with
// fixed-size Eigen types, on the same plant, input and 1000 steps.
// Paired with dey_bhasin_observer.cpp.

#include <Eigen/Dense>

#include <cmath>
#include <cstdio>

using Matrix6 = Eigen::Matrix<double, 6, 6>;
using Matrix15 = Eigen::Matrix<double, 15, 15>;

int main() {
  const Eigen::Vector3d a(0.4, 0.11, 0.3), f(0.4, 0.21, 0.2), a0(1, 0.51, 0.6);
  Eigen::Matrix<double, 6, 2> B;
  B << 1, 2, 0.2, -5, 3, 4, 0.1, 0.9, 0.3, 0.2, -1, -1.1;
  Eigen::Matrix<double, 6, 1> x, free;  // plant state; F^t x̂0
  x << -1, 0.2, 1, -3, -2, 2.5;
  free << 0, 1, 2, 0.1, 0.2, 0.3;
  const double k0 = 1000, kmin = 1e-4;

  // A = Ā(a) ⊗ I2 and F = Ā(f) ⊗ I2: first block column a_i I2 (f_i I2), identities above the diagonal.
  Matrix6 A = Matrix6::Zero(), F = Matrix6::Zero();
  for (int i = 0; i < 3; ++i) {
    A.block<2, 2>(2 * i, 0) = a(i) * Eigen::Matrix2d::Identity();
    F.block<2, 2>(2 * i, 0) = f(i) * Eigen::Matrix2d::Identity();
    if (i < 2) A.block<2, 2>(2 * i, 2 * i + 2) = F.block<2, 2>(2 * i, 2 * i + 2) = Eigen::Matrix2d::Identity();
  }
  // p = [a − f; vec(B)], x_t = S_t p + F^t x0, S_{t+1} = F S_t + [I3 ⊗ y_t, u_tᵀ ⊗ I6].
  Eigen::Matrix<double, 15, 1> p;
  p << a0 - f, Eigen::Matrix<double, 12, 1>::Constant(0.5);
  Eigen::Matrix<double, 6, 15> S = Eigen::Matrix<double, 6, 15>::Zero();
  Matrix15 Gamma = k0 * Matrix15::Identity();
  int resets = 0;

  for (int t = 0; t < 1000; ++t) {
    const Eigen::Vector2d u(std::sin(0.3 * t) + std::sin(1.3 * t), std::sin(0.7 * t) + std::sin(2.1 * t));
    const Eigen::Vector2d y = x.head<2>();
    if (t > 0) {  // (16), (22)–(23): φ = Sᵀ Cᵀ, z = y − C F^t x0
      const Eigen::Matrix<double, 15, 2> phi = S.topRows<2>().transpose();
      const Eigen::Vector2d z = y - free.head<2>();
      const Eigen::Matrix2d W = (Eigen::Matrix2d::Identity() + phi.transpose() * Gamma * phi).inverse();  // R = I
      const Eigen::Matrix<double, 15, 2> gain = Gamma * phi * W;
      p += gain * (z - phi.transpose() * p);
      Gamma -= gain * phi.transpose() * Gamma;
      if ((Gamma - kmin * Matrix15::Identity()).llt().info() != Eigen::Success) {  // λmin(Γ) ≤ kmin
        Gamma = k0 * Matrix15::Identity();
        ++resets;
      }
    }
    Eigen::Matrix<double, 6, 15> drive = Eigen::Matrix<double, 6, 15>::Zero();
    for (int i = 0; i < 3; ++i) drive.block<2, 1>(2 * i, i) = y;
    drive.block<6, 6>(0, 3) = u(0) * Matrix6::Identity();
    drive.block<6, 6>(0, 9) = u(1) * Matrix6::Identity();
    S = F * S + drive;
    free = F * free;
    x = A * x + B * u;
  }

  const Eigen::Matrix<double, 6, 1> xhat = S * p + free;  // x̂_{t+1|t}
  std::printf("xhat");
  for (int i = 0; i < 6; ++i) std::printf(" %.17g", xhat(i));
  std::printf("\nphat");
  for (int i = 0; i < 15; ++i) std::printf(" %.17g", p(i));
  std::printf("\nresets %d\n", resets);
}
