// Compile-time benchmark, hand-written side: the Takagi–Sugeno adaptive
// observer (Srinivasarengan et al. 2018, eq. (65)) on the waste water plant of §6 with Eigen
// alone: the 8 vertices of the sector-nonlinearity model, the memberships (10)
// at the estimates, the printed gains, the same 500 steps.
// Paired with takagi_sugeno_observer.cpp.

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

constexpr double a0 = 0.5, b = 0.4, c = 0.4, d = 2.0;  // Table 1, Ts = 1

int main() {
  // Sectors of (z1, z2, θ), eq. (74), (76); vertex i takes the upper bound of
  // variable j when bit 2 − j of i is set (the printed order A1, ..., A8).
  const double lower[3] = {0, 0.01 / 3.4, -0.3}, upper[3] = {0.4, 6 / 0.41, 0.3};
  Eigen::Matrix2d A[8];
  for (int i = 0; i < 8; ++i) {
    double v[3];
    for (int j = 0; j < 3; ++j) v[j] = (i >> (2 - j)) & 1 ? upper[j] : lower[j];
    const double a = a0 + v[2];
    A[i] << 1 - v[0], a * v[1], 0, 1 - c * a * v[1] - v[0];
  }
  const Eigen::Vector2d B(0, d);
  const double l[8][2] = {{0.23, 0.24},  {0.23, 0.24},  {0.31, 0.21},  {0.61, 0.09},
                          {-0.41, 0.30}, {-0.41, 0.30}, {-0.41, 0.30}, {-0.27, 0.24}};
  const double K = 0.03;

  Eigen::Vector2d xhat(3, 0.6);
  double thetahat = 0;
  const double theta = 0.05;
  Eigen::Vector2d x(4, 0.3);
  for (int k = 0; k < 500; ++k) {
    const double u = 0.225 + 0.05 * std::sin(2 * std::numbers::pi * k / 100);
    const double y = x(0);
    // Memberships μ² (upper bound) of ẑ1 = u, ẑ2 = x̂1 / (x̂2 + b) and θ̂, each clipped to its sector.
    const double v[3] = {u, xhat(0) / (xhat(1) + b), thetahat};
    double upper_weight[3];
    for (int j = 0; j < 3; ++j) upper_weight[j] = std::clamp((v[j] - lower[j]) / (upper[j] - lower[j]), 0.0, 1.0);
    const double e = y - xhat(0);
    Eigen::Vector2d next = Eigen::Vector2d::Zero();
    double step = 0;
    for (int i = 0; i < 8; ++i) {
      double h = 1;
      for (int j = 0; j < 3; ++j) h *= (i >> (2 - j)) & 1 ? upper_weight[j] : 1 - upper_weight[j];
      next += h * (A[i] * xhat + B * u + Eigen::Vector2d(l[i][0], l[i][1]) * e);
      step += h * K * e;
    }
    xhat = next;
    thetahat += step;
    const double growth = (a0 + theta) * x(0) * x(1) / (x(1) + b);
    x = Eigen::Vector2d(x(0) + growth - x(0) * u, x(1) - c * growth + (d - x(1)) * u);
  }

  std::printf("xhat %.17g %.17g\nthetahat %.17g\n", xhat(0), xhat(1), thetahat);
}
