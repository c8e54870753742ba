// Compile-time benchmark, library side: one adaptobs::TakagiSugenoObserver
// (eq. (65), 8 vertices) on the waste water plant of Srinivasarengan et al. (2018) §6 with the
// printed gains, 500 steps with θ = 0.05.
// Paired with takagi_sugeno_eigen.cpp (the same job with Eigen alone).

#include <adaptobs/observers/takagi_sugeno.hpp>

#include <cmath>
#include <cstdio>
#include <numbers>

using Dims = adaptobs::Dimensions<double, 2, 1, 1, 1>;
using Vector1 = Eigen::Matrix<double, 1, 1>;
constexpr double a0 = 0.5, b = 0.4, c = 0.4, d = 2.0;  // Table 1, Ts = 1

int main() {
  // A(z, θ) of (72) with z = (u, x1 / (x2 + b)) and a = a0 + θ, and its sectors (74), (76).
  const auto quasi_lpv = [](const Eigen::Vector2d& z, const Vector1& theta) {
    const double a = a0 + theta(0);
    adaptobs::TakagiSugenoVertex<Dims> m;
    m.A << 1 - z(0), a * z(1), 0, 1 - c * a * z(1) - z(0);
    m.B << 0, d;
    return m;
  };
  const auto premises = [](const Eigen::Vector2d& x, const Vector1& u, const Vector1&) {
    return Eigen::Vector2d(u(0), x(0) / (x(1) + b));
  };
  const adaptobs::SectorBounds<double, 2> z_bounds{{0, 0.01 / 3.4}, {0.4, 6 / 0.41}};
  const adaptobs::SectorBounds<double, 1> theta_bounds{Vector1(-0.3), Vector1(0.3)};
  const auto model = adaptobs::make_takagi_sugeno_model<Dims, 2>(quasi_lpv, Eigen::RowVector2d(1, 0), premises,
                                                                 z_bounds, theta_bounds);

  adaptobs::TakagiSugenoGains<Dims> gains;
  const double l[8][2] = {{0.23, 0.24},  {0.23, 0.24},  {0.31, 0.21},  {0.61, 0.09},
                          {-0.41, 0.30}, {-0.41, 0.30}, {-0.41, 0.30}, {-0.27, 0.24}};
  for (const auto& li : l) {
    gains.L.emplace_back(li[0], li[1]);
    gains.K.emplace_back(0.03);
  }
  adaptobs::TakagiSugenoObserver observer(model, gains, Eigen::Vector2d(3, 0.6), Vector1(0));

  const double theta = 0.05;
  Eigen::Vector2d x(4, 0.3);
  for (int k = 0; k < 500; ++k) {
    const double u = 0.225 + 0.05 * std::sin(2 * std::numbers::pi * k / 100);
    if (observer.update({Vector1(u), Vector1(x(0))}) != adaptobs::UpdateStatus::accepted) return 1;
    const double growth = (a0 + theta) * x(0) * x(1) / (x(1) + b);
    x = Eigen::Vector2d(x(0) + growth - x(0) * u, x(1) - c * growth + (d - x(1)) * u);
  }

  const Eigen::Vector2d& xhat = observer.state();
  std::printf("xhat %.17g %.17g\nthetahat %.17g\n", xhat(0), xhat(1), observer.parameters()(0));
}
