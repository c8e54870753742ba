// Compile-time benchmark, hand-written side: the Bastin–Gevers adaptive
// observer (Zhang 2005, Algorithm 1) in the coordinates x = Tη of form (5), with
// its filter Ξ̇ = A22 Ξ + Ψ2 and θ̂̇ = Γ ξ ε, stepped by a hand-written RK4 (one
// step per sample, u held, y linear between samples) with Eigen alone.
// Paired with bastin_gevers_observer.cpp.

#include <Eigen/Dense>

#include "third_order_problem.hpp"

#include <cmath>
#include <cstdio>

template <class State, class F>
State rk4(const F& f, const State& x, double t, double h) {
  const State k1 = f(x, t), k2 = f(x + h / 2 * k1, t + h / 2);
  const State k3 = f(x + h / 2 * k2, t + h / 2), k4 = f(x + h * k3, t + h);
  return x + h / 6 * (k1 + 2 * k2 + 2 * k3 + k4);
}

int main() {
  const ThirdOrderProblem problem = third_order_problem();
  // References, not a structured binding: clang before 16 cannot capture bindings in a lambda.
  const Eigen::Matrix3d &A = problem.A, &T = problem.T;
  const Eigen::Vector3d &B = problem.B, &K = problem.K, &k = problem.k;
  const Eigen::RowVector3d& C = problem.C;
  const auto Phi = third_order_regressor;
  const Eigen::Matrix3d Tinv = T.inverse();
  const Eigen::RowVector3d Co = C * Tinv;
  const Eigen::Matrix3d Ao = T * A * Tinv - K * Co;
  const Eigen::Vector3d TB = T * B;
  const Eigen::Matrix2d Gamma = 5 * Eigen::Matrix2d::Identity();

  // Observer state s = (x̂, vec Ξ, θ̂), with Ω = [0; Ξ] and ε = y − c_o x̂.
  using State = Eigen::Matrix<double, 9, 1>;
  State s = State::Zero();
  const Eigen::Vector2d theta(2, -1);
  const double ts = 0.01;
  Eigen::Vector3d eta(1, -1, 0.5);
  double u_prev = 0, y_prev = 0;
  for (int n = 0; n <= 2000; ++n) {
    const double t = n * ts, u = 1 + std::sin(0.3 * t), y = C * eta;
    if (n > 0) {
      const auto observer = [&](const State& z, double tau) {
        const double yt = y_prev + (tau - (t - ts)) / ts * (y - y_prev);
        const Eigen::Matrix<double, 3, 2> Psi = T * Phi(tau);
        const Eigen::Map<const Eigen::Matrix2d> Xi(z.data() + 3);
        const double eps = yt - Co * z.head<3>();
        const Eigen::RowVector2d xi = Ao.block<1, 2>(0, 1) * Xi + Psi.row(0);  // ξᵀ = a12 Ξ + Ψ1
        const Eigen::Vector2d dtheta = Gamma * xi.transpose() * eps;
        State dz;
        Eigen::Map<Eigen::Matrix2d>(dz.data() + 3) = Ao.bottomRightCorner<2, 2>() * Xi + Psi.bottomRows<2>();
        dz.head<3>() = Ao * z.head<3>() + TB * u_prev + K * yt + Psi * z.tail<2>() + k * eps;
        dz.segment<2>(1) += Xi * dtheta;  // + Ω θ̂̇
        dz.tail<2>() = dtheta;
        return dz;
      };
      s = rk4(observer, s, t - ts, ts);
    }
    u_prev = u;
    y_prev = y;
    const auto plant = [&](const Eigen::Vector3d& x, double tau) -> Eigen::Vector3d {
      return A * x + B * u + Phi(tau) * theta;
    };
    eta = rk4(plant, eta, t, ts);
  }

  const Eigen::Vector3d etahat = Tinv * s.head<3>();
  std::printf("etahat %.17g %.17g %.17g\n", etahat(0), etahat(1), etahat(2));
  std::printf("thetahat %.17g %.17g\n", s(7), s(8));
}
