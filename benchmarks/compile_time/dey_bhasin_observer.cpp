// Compile-time benchmark, library side: one adaptobs::DeyBhasinObserver (order
// 3, 2 outputs, 2 inputs, 15 unknowns; RLS with covariance resetting) on the
// MIMO plant of Dey & Bhasin (2022) §5 driven by its sufficiently rich input, 1000 steps.
// Paired with dey_bhasin_eigen.cpp (the same job with Eigen alone).

#include <adaptobs/observers/dey_bhasin.hpp>

#include <cmath>
#include <cstdio>

int main() {
  using Observer = adaptobs::DeyBhasinObserver<double, 3, 2, 2>;
  const Eigen::Vector3d a(0.4, 0.11, 0.3), f(0.4, 0.21, 0.2), a0(1, 0.51, 0.6);
  Eigen::Matrix<double, 6, 2> B;
  B << 1, 2, 0.2, -5, 3, 4, 0.1, 0.9, 0.3, 0.2, -1, -1.1;
  Eigen::Matrix<double, 6, 1> x, xhat0;
  x << -1, 0.2, 1, -3, -2, 2.5;
  xhat0 << 0, 1, 2, 0.1, 0.2, 0.3;

  Observer observer(f, xhat0, a0, Eigen::Matrix<double, 6, 2>::Constant(0.5),
                    {.k0 = 1000, .kmin = 1e-4, .R = Eigen::Matrix2d::Identity()});

  // Plant in observable canonical form: A = Ā(a) ⊗ I2, C = [I2 0 0].
  const Eigen::Matrix<double, 6, 6> A = adaptobs::block_companion_matrix<2>(a);
  for (int t = 0; t < 1000; ++t) {
    const Eigen::Vector2d u(std::sin(0.3 * t) + std::sin(1.3 * t), std::sin(0.7 * t) + std::sin(2.1 * t));
    const Observer::Sample sample{u, x.head<2>()};
    if (observer.update(sample) != adaptobs::UpdateStatus::accepted) return 1;
    x = A * x + B * u;
  }

  const Eigen::Matrix<double, 6, 1>& xhat = observer.state();
  const Eigen::Matrix<double, 15, 1>& p = observer.parameters();
  std::printf("xhat");
  for (int i = 0; i < 6; ++i) std::printf(" %.17g", xhat(i));
  std::printf("\nphat");
  for (int i = 0; i < 15; ++i) std::printf(" %.17g", p(i));
  std::printf("\nresets %ld\n", long(observer.law().reset_count()));
}
