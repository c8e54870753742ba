#pragma once
// The satellite of Guyader & Zhang (2003) §4 with its printed matrices (Ts = 0.1 s) and
// printed gain, and the thrust pulses that excite it: the data both sides of
// the guyader_zhang pair share, in Eigen types only, so that it costs both the same.

#include <Eigen/Core>

struct SatelliteProblem {
  Eigen::Matrix4d A, H;           // x_{k+1} = A x_k + Ψ_k θ,  Ψ_k = H [0 0; u¹ 0; 0 0; 0 u²]
  Eigen::Matrix<double, 2, 4> C;  // y_k = C x_k
  Eigen::Matrix<double, 4, 2> K;  // the printed observer gain
};

inline SatelliteProblem satellite_problem() {
  SatelliteProblem p;
  p.A << 1.000000001827015, 0.099999999979699827, 0, 3.4899999996457628e-06,      //
      3.6540299992582279e-08, 0.99999999939099504, 0, 6.9799999985830497e-05,     //
      -4.2508548997411251e-14, -3.4899999996457632e-06, 1, 0.099999999918799348,  //
      -1.2752564698705613e-12, -6.9799999985830497e-05, 0, 0.99999999756398017;
  p.H << 0.10000000006090048, 0.0049999999994924963, 0, 1.163333333262486e-07,                       //
      1.8270149998145573e-09, 0.099999999979699841, 0, 3.4899999996457628e-06,                       //
      -1.0627137249568544e-15, -1.1633333332624865e-07, 0.10000000000000001, 0.0049999999979699851,  //
      -4.2508548997411239e-14, -3.4899999996457632e-06, 0, 0.099999999918799348;
  p.C << 1, 0, 0, 0,  //
      0, 0, 1, 0;
  p.K << 0.1412, 4.93e-6, 0.0932, 5.26e-5, -4.93e-6, 0.1412, -5.26e-5, 0.0932;
  return p;
}

/// Unit thrust pulses of 1 s every 10 s, tangential ones 5 s later.
inline Eigen::Vector2d satellite_input(int k) { return {k % 100 < 10, k >= 50 && (k - 50) % 100 < 10}; }

/// Ψ_k for the input u.
inline Eigen::Matrix<double, 4, 2> satellite_regressor(const SatelliteProblem& p, const Eigen::Vector2d& u) {
  Eigen::Matrix<double, 4, 2> psi;
  psi << p.H.col(1) * u(0), p.H.col(3) * u(1);
  return psi;
}
