#pragma once
/// \file
/// A MIMO linear time-varying plant (n = 4, m = 2, p = 2, period 2π), used by
/// the `besancon` and `zhang_continuous` examples, the tests and the benchmarks.
///
/// In coordinates \f$x = T\eta\f$ it has the form (8) of Zhang (2005, §III-C),
/// \f$C_o = [I\ 0]\f$, without output injection:
/// \f[ A_o(t) = \begin{bmatrix} -1 & 0.5 + 0.5\sin t & 1 & 0\\ -0.5 & -1.5 & 0.5\cos t & 1
///     \\ 0.3 & 0 & -2 & w(t)\\ 0 & -0.3 & -w(t) & -2\end{bmatrix},\quad w(t) = 1 + 0.5\sin t, \f]
/// where \f$A_{22} + A_{22}^T = -4I\f$ makes \f$|e_2(t)| = e^{-2t}|e_2(0)|\f$ exactly.
/// The plant itself lives in \f$\eta = T^{-1}x\f$ with
/// \f$T = \begin{bmatrix} 1&0&1&0\\ 0&1&0&-1\\ 0&0&1&0\\ 0&0&0&1\end{bmatrix}\f$, so
/// \f$C = C_oT = \begin{bmatrix} 1&0&1&0\\ 0&1&0&-1\end{bmatrix}\f$ (not [I 0]):
/// \f$A(t) = T^{-1}A_o(t)T\f$, B = (0, 1, 0, 1), u = sin 0.4t,
/// \f$\Phi(t) = \begin{bmatrix} \sin t & 0\\ 0 & \cos 0.7t\\ 1 & 0\\ 0 & \sin 1.3t\end{bmatrix}\f$,
/// θ = (1, −2), η(0) = (1, 0.5, −1, 0.8). Floquet exponents of A(t):
/// −1.34, −1.34, −1.82, −2.01; with K = T⁻¹[3I; 0], those of A − KC are
/// −1.98, −2.01, −4.13, −4.38.

#include <adaptobs/core/continuous_model.hpp>
#include <adaptobs/core/dimensions.hpp>
#include <adaptobs/simulation/continuous_plant.hpp>

#include <cmath>
#include <numbers>

namespace adaptobs::examples::periodic {

template <typename S>
using Dims = Dimensions<S, 4, 1, 2, 2>;

inline constexpr double period = 2 * std::numbers::pi;

template <typename S>
Eigen::Matrix<S, 4, 4> coordinate_change() {
  Eigen::Matrix<S, 4, 4> t;
  t << 1, 0, 1, 0,  //
      0, 1, 0, -1,  //
      0, 0, 1, 0,   //
      0, 0, 0, 1;
  return t;
}

/// \f$A_o(t)\f$ in the coordinates of form (8).
template <typename S>
Eigen::Matrix<S, 4, 4> form8_dynamics(S t) {
  const S w = S(1) + S(0.5) * std::sin(t);
  Eigen::Matrix<S, 4, 4> a;
  a << -1, S(0.5) + S(0.5) * std::sin(t), 1, 0,   //
      S(-0.5), S(-1.5), S(0.5) * std::cos(t), 1,  //
      S(0.3), 0, -2, w,                           //
      0, S(-0.3), -w, -2;
  return a;
}

template <typename S>
Eigen::Matrix<S, 4, 4> coordinate_change_inverse() {
  Eigen::Matrix<S, 4, 4> t;
  t << 1, 0, -1, 0,  //
      0, 1, 0, 1,    //
      0, 0, 1, 0,    //
      0, 0, 0, 1;
  return t;
}

/// The plant's matrices at time t: \f$A = T^{-1}A_o(t)T\f$, B, \f$C = [I\ 0]T\f$.
template <typename S>
ContinuousSystem<Dims<S>> system(S t) {
  Eigen::Matrix<S, 2, 4> c;
  c << 1, 0, 1, 0,  //
      0, 1, 0, -1;
  return {coordinate_change_inverse<S>() * form8_dynamics<S>(t) * coordinate_change<S>(),
          Eigen::Matrix<S, 4, 1>(0, 1, 0, 1), c};
}

struct Regressor {
  template <typename S>
  Eigen::Matrix<S, 4, 2> operator()(S t) const {
    Eigen::Matrix<S, 4, 2> phi;
    phi << std::sin(t), 0,        //
        0, std::cos(S(0.7) * t),  //
        1, 0,                     //
        0, std::sin(S(1.3) * t);
    return phi;
  }
};

struct Input {
  template <typename S>
  Eigen::Matrix<S, 1, 1> operator()(S t) const {
    return Eigen::Matrix<S, 1, 1>(std::sin(S(0.4) * t));
  }
};

template <typename S>
Eigen::Matrix<S, 2, 1> true_parameters() {
  return {S(1), S(-2)};
}
template <typename S>
Eigen::Matrix<S, 4, 1> initial_state() {
  return {S(1), S(0.5), S(-1), S(0.8)};
}

/// Output injection of Algorithm 4 in the plant's coordinates: \f$K = T^{-1}[3I; 0]\f$.
template <typename S>
Eigen::Matrix<S, 4, 2> zhang_gain() {
  Eigen::Matrix<S, 4, 2> k = Eigen::Matrix<S, 4, 2>::Zero();
  k.topRows(2) = 3 * Eigen::Matrix<S, 2, 2>::Identity();
  return coordinate_change_inverse<S>() * k;
}

template <typename S>
auto model() {
  return make_continuous_ltv_model<Dims<S>>([](S t) { return system<S>(t); },
                                            [](S t) { return Regressor{}.operator()<S>(t); });
}

template <typename S>
using Model = decltype(model<S>());

template <typename S>
auto make_plant(ContinuousPlantOptions<S> options = {}) {
  return ContinuousLinearPlant(
      model<S>(), initial_state<S>(), true_parameters<S>(), [](S t) { return Input{}.operator()<S>(t); }, options);
}

}  // namespace adaptobs::examples::periodic
