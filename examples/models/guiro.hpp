#pragma once
/// \file
/// The example of Guiro et al. (2008) §4 (Guiro, Iggidr, Ngom, Touré), shared by the
/// `guiro` example, the tests and the benchmarks:
/// \f[ \dot x = \begin{bmatrix}0&0\\1&0\end{bmatrix}x + \begin{bmatrix}\frac{t+1}{t+2}\\0\end{bmatrix}\theta,
///     \qquad y_k = [0\ \ 1]\,x(kT),\qquad \theta = 5,\ T = 1, \f]
/// with the requested spectrum {1/2, 3/5, 1/5} of U.
///
/// Because \f$e^{(kT-s)A} = I + (kT-s)A\f$, the regressor integral has a closed
/// form: with \f$c_k = kT + 2\f$ and \f$r_k = \ln(1 + T/c_k)\f$,
/// \f[ H_k = \begin{bmatrix}T - r_k\\ T - T^2/2 - c_kr_k\end{bmatrix},\qquad
///     e^{AT}H_k = \begin{bmatrix}T - r_k\\ T + T^2/2 - (c_k + T)r_k\end{bmatrix},\qquad
///     H_\infty = \begin{bmatrix}T\\ -T^2/2\end{bmatrix}; \f]
/// for T = 1, \f$H_0 = (1 - \ln\frac32, \frac12 - \ln\frac94)\f$ as printed.
/// The simulated plant uses these closed forms, so its samples are exact.

#include <adaptobs/core/dimensions.hpp>
#include <adaptobs/core/discrete_model.hpp>
#include <adaptobs/core/sampled_model.hpp>
#include <adaptobs/simulation/discrete_plant.hpp>

#include <Eigen/Core>

#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

namespace adaptobs::examples::guiro {

/// n = 2 states, no input, m = 1 output, p = 1 parameter.
template <typename S>
using Dims = Dimensions<S, 2, 0, 1, 1>;

inline constexpr double period = 1.0;  ///< T (the paper samples at integer times)
inline constexpr double theta = 5.0;   ///< true parameter

template <typename S>
Eigen::Matrix<S, 2, 2> continuous_dynamics() {
  Eigen::Matrix<S, 2, 2> a;
  a << 0, 0,  //
      1, 0;
  return a;
}

template <typename S>
Eigen::Matrix<S, 1, 2> output_matrix() {
  return {S(0), S(1)};
}

/// \f$\varphi(t) = ((t+1)/(t+2),\ 0)\f$.
struct Regressor {
  template <typename S>
  Eigen::Matrix<S, 2, 1> operator()(S t) const {
    return {(t + S(1)) / (t + S(2)), S(0)};
  }
};

/// Closed-form H over the interval \f$[t, t + T]\f$ (see file comment, with \f$c = t + 2\f$).
template <typename S>
Eigen::Matrix<S, 2, 1> interval_H(S start, S T) {
  const S c = start + S(2);
  const S r = std::log1p(T / c);
  return {T - r, T - T * T / S(2) - c * r};
}

/// Closed-form \f$e^{AT}H\f$ over the interval \f$[t, t + T]\f$.
template <typename S>
Eigen::Matrix<S, 2, 1> interval_Psi(S start, S T) {
  const S c = start + S(2);
  const S r = std::log1p(T / c);
  return {T - r, T + T * T / S(2) - (c + T) * r};
}

/// Closed-form \f$H_k\f$ on the regular grid \f$t_k = kT\f$.
template <typename S>
Eigen::Matrix<S, 2, 1> closed_form_H(Index k, S T = S(period)) {
  return interval_H<S>(S(k) * T, T);
}

/// Closed-form \f$\Psi_k = e^{AT}H_k\f$ on the regular grid.
template <typename S>
Eigen::Matrix<S, 2, 1> closed_form_Psi(Index k, S T = S(period)) {
  return interval_Psi<S>(S(k) * T, T);
}

/// \f$e^{AT} = I + TA\f$ (A is nilpotent).
template <typename S>
Eigen::Matrix<S, 2, 2> transition(S T) {
  return Eigen::Matrix<S, 2, 2>::Identity() + T * continuous_dynamics<S>();
}

/// \f$H_\infty = \lim_k H_k = (T, -T^2/2)\f$: φ tends to (1, 0).
template <typename S>
Eigen::Matrix<S, 2, 1> limit_H(S T = S(period)) {
  return {T, -T * T / S(2)};
}

/// Sample times \f$t_0 = 0\f$, \f$t_{k+1} = t_k + T(1 + J\,u_k)\f$ with \f$u_k\f$ uniform in
/// [−1, 1] from a seeded generator: `count` + 1 instants, intervals jittered by ±J.
inline std::vector<double> jittered_sample_times(Index count, double jitter, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::vector<double> t{0.0};
  for (Index k = 0; k < count; ++k) t.push_back(t.back() + period * (1.0 + jitter * unit(rng)));
  return t;
}

/// The spectrum requested for U in §4.
inline Eigen::Vector3d requested_poles() { return {0.5, 0.6, 0.2}; }

/// Gains printed in §4. The printed Γ = 18.730773 makes U unstable; the
/// decimal point is shifted: Γ = 1.8730773 places {1/2, 3/5, 1/5}.
inline Eigen::Vector2d printed_K() { return {0.8436769, 0.8563231}; }
inline constexpr double printed_Gamma = 18.730773;
inline constexpr double corrected_printed_Gamma = 1.8730773;

template <typename S>
Eigen::Matrix<S, 2, 1> initial_state() {
  return {S(1), S(-1)};
}
template <typename S>
Eigen::Matrix<S, 2, 1> initial_state_estimate() {
  return {S(0), S(0)};
}
template <typename S>
Eigen::Matrix<S, 1, 1> initial_parameter_estimate() {
  return Eigen::Matrix<S, 1, 1>(S(0));
}

/// Sampled model \f$(e^{AT}, B_d = 0, C)\f$.
template <typename S>
DiscreteLtiModel<Dims<S>> model(S T = S(period)) {
  return sampled_lti_model<Dims<S>>(continuous_dynamics<S>(), Eigen::Matrix<S, 2, 0>(), output_matrix<S>(), T);
}

/// The plant, sampled exactly: \f$x_{k+1} = e^{AT}x_k + \Psi_k\theta\f$ with the closed-form \f$\Psi_k\f$.
template <typename S = double>
auto make_plant(S T = S(period), Eigen::Matrix<S, 2, 1> x0 = initial_state<S>()) {
  auto input = [](Index) { return Eigen::Matrix<S, 0, 1>(); };
  auto regressor = [T](Index k, const Eigen::Matrix<S, 0, 1>&) { return closed_form_Psi<S>(k, T); };
  return DiscreteLinearPlant(model<S>(T), x0, Eigen::Matrix<S, 1, 1>(S(theta)), input, regressor, PlantNoise<S>{}, T);
}

}  // namespace adaptobs::examples::guiro
