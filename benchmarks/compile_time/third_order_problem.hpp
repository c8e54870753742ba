#pragma once
// The third-order SISO plant of the continuous-time examples (Zhang 2005,
// Algorithm 1), with the transform (T, K) to form (5) and the gain k: the data
// both sides of the bastin_gevers pair share, in Eigen types only.

#include <Eigen/Core>

#include <cmath>
#include <numbers>

struct ThirdOrderProblem {
  Eigen::Matrix3d A, T;
  Eigen::Vector3d B;
  Eigen::RowVector3d C;
  Eigen::Vector3d K, k;
};

/// Form (5) with det(sI − A22) = (s + 1)(s + 3); k makes c_o(sI − A_o + k c_o)⁻¹e1 = 1/(s + 2).
inline ThirdOrderProblem third_order_problem() {
  constexpr double r2 = std::numbers::sqrt2;
  ThirdOrderProblem p;
  p.A << -1, 2, 0, -1, -1, 1, 0.5, 0, -2;
  p.B << 0, 1, 0.5;
  p.C << 1, 0, 1;
  p.T << 1, 0, 1, -0.16, 1, -0.16, 0.12 * r2, 0, 1.12 * r2;
  p.K << 0, -1.4, 0.8 * r2;
  p.k << 2, 0, 0;
  return p;
}

/// Φ(t): η̇ = Aη + Bu + Φ(t)θ.
inline Eigen::Matrix<double, 3, 2> third_order_regressor(double t) {
  Eigen::Matrix<double, 3, 2> phi;
  phi << std::sin(t), 0, std::cos(1.7 * t), 1, 0, std::sin(0.6 * t);
  return phi;
}
