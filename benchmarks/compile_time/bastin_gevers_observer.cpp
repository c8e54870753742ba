// Compile-time benchmark, library side: one adaptobs::BastinGeversObserver
// (Zhang 2005, Algorithm 1) on the third-order SISO plant of the examples, from
// a given transform (T, K) to form (5) and gain k, updated over 2000 samples
// (Ts = 0.01 s) with one RK4 step per sample.
// Paired with bastin_gevers_eigen.cpp (the same job with Eigen alone).

#include <adaptobs/core/runge_kutta.hpp>
#include <adaptobs/observers/bastin_gevers.hpp>

#include "third_order_problem.hpp"

#include <cmath>
#include <cstdio>

using Dims = adaptobs::Dimensions<double, 3, 1, 1, 2>;

int main() {
  const ThirdOrderProblem problem = third_order_problem();
  // References, not a structured binding: clang before 16 cannot capture bindings in a lambda.
  const Eigen::Matrix3d &A = problem.A, &T = problem.T;
  const Eigen::Vector3d &B = problem.B, &K = problem.K, &k = problem.k;
  const Eigen::RowVector3d& C = problem.C;
  const auto Phi = third_order_regressor;

  auto observer = adaptobs::make_bastin_gevers_observer(
      adaptobs::make_continuous_lti_model<Dims>(A, B, C, Phi), adaptobs::StaticTransform<Dims>(T, K), k,
      5 * Eigen::Matrix2d::Identity(), Eigen::Vector3d::Zero(), Eigen::Vector2d::Zero());

  // Plant, θ = (2, −1), u = 1 + sin 0.3t held over each sample period.
  const Eigen::Vector2d theta(2, -1);
  const double ts = 0.01;
  Eigen::Vector3d eta(1, -1, 0.5);
  adaptobs::RungeKutta4<Eigen::Vector3d> rk4(eta);
  for (int k = 0; k <= 2000; ++k) {
    const double t = k * ts;
    const Eigen::Matrix<double, 1, 1> u(1 + std::sin(0.3 * t));
    if (observer.update({.t = t, .u = u, .y = C * eta}) != adaptobs::UpdateStatus::accepted) return 1;
    const auto plant = [&](const Eigen::Vector3d& x, Eigen::Vector3d& dx, double s) {
      dx = A * x + B * u + Phi(s) * theta;
    };
    rk4.step(plant, eta, t, ts, eta);
  }

  const Eigen::Vector3d& etahat = observer.state();
  const Eigen::Vector2d& thetahat = observer.parameters();
  std::printf("etahat %.17g %.17g %.17g\n", etahat(0), etahat(1), etahat(2));
  std::printf("thetahat %.17g %.17g\n", thetahat(0), thetahat(1));
}
