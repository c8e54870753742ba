#pragma once
/// \file
/// The controlled satellite of Guyader & Zhang (2003) §4 (Guyader & Zhang), shared by the
/// `satellite` example, the tests and the benchmarks.
///
/// Linearized motion about a circular orbit of normalized radius 1 with
/// angular velocity ω (Brockett 1970): state (radial position, radial
/// velocity, angular position, angular velocity), inputs the radial and
/// tangential thrusts, whose unknown efficiencies θ¹, θ² multiply them:
/// \f[ \dot x = \begin{bmatrix} 0&1&0&0\\ 3\omega^2&0&0&2\omega\\ 0&0&0&1\\ 0&-2\omega&0&0\end{bmatrix}x
///     + \begin{bmatrix} 0&0\\ \theta^1&0\\ 0&0\\ 0&\theta^2\end{bmatrix}u. \f]
/// Sampled with a zero-order hold (Ts = 0.1 s) it becomes
/// \f$x_{k+1} = A x_k + \Psi_k\theta\f$ with \f$\Psi_k = H\,\mathrm{diag}\text{-}(u_k)\f$,
/// \f$H = \int_0^{T_s}e^{A_cs}ds\f$ (Guyader & Zhang 2003, §4).

#include <adaptobs/core/dimensions.hpp>
#include <adaptobs/core/discrete_model.hpp>
#include <adaptobs/core/discretization.hpp>
#include <adaptobs/simulation/discrete_plant.hpp>

#include <cmath>

namespace adaptobs::examples::satellite {

template <typename S>
using Dims = Dimensions<S, 4, 2, 2, 2>;

inline constexpr double omega = 3.49e-4;        ///< nominal angular velocity, rad/s
inline constexpr double sampling_period = 0.1;  ///< Ts, s
inline constexpr double mu = 4.0;               ///< step size μ of the paper

template <typename S>
Eigen::Matrix<S, 4, 4> continuous_dynamics(S w = S(omega)) {
  Eigen::Matrix<S, 4, 4> a;
  a << 0, 1, 0, 0,             //
      3 * w * w, 0, 0, 2 * w,  //
      0, 0, 0, 1,              //
      0, -2 * w, 0, 0;
  return a;
}

/// A_d = e^{A_c Ts} and H = ∫₀^Ts e^{A_c s} ds, from the library's Van Loan routine.
template <typename S>
ZeroOrderHold<S, 4, 4> discretized() {
  return discretize_zoh(continuous_dynamics<S>(), Eigen::Matrix<S, 4, 4>::Identity(), S(sampling_period));
}

template <typename S>
Eigen::Matrix<S, 2, 4> output_matrix() {
  Eigen::Matrix<S, 2, 4> c;
  c << 1, 0, 0, 0,  //
      0, 0, 1, 0;
  return c;
}

/// Discrete model (A_d, B = 0, C): the thrusts enter only through Ψ_k θ.
template <typename S>
DiscreteLtiModel<Dims<S>> model() {
  return {discretized<S>().Ad, Eigen::Matrix<S, 4, 2>::Zero(), output_matrix<S>()};
}

/// Observer gain K printed in Guyader & Zhang (2003) §4.
template <typename S>
Eigen::Matrix<S, 4, 2> paper_gain() {
  Eigen::Matrix<S, 4, 2> k;
  k << S(0.1412), S(4.93e-6),  //
      S(0.0932), S(5.26e-5),   //
      S(-4.93e-6), S(0.1412),  //
      S(-5.26e-5), S(0.0932);
  return k;
}

template <typename S>
Eigen::Matrix<S, 2, 1> true_parameters() {
  return {S(1), S(1.5)};
}
template <typename S>
Eigen::Matrix<S, 4, 1> initial_state() {
  return {S(1), S(0), S(0), S(3.49e-4)};
}
template <typename S>
Eigen::Matrix<S, 4, 1> initial_state_estimate() {
  return {S(0.9), S(0), S(0), S(3.14e-4)};
}
template <typename S>
Eigen::Matrix<S, 2, 1> initial_parameter_estimate() {
  return {S(0.5), S(0.5)};
}

/// Square thrust pulses: unit amplitude, 1 s long, every 10 s; radial pulses
/// start at t = 0, 10, 20, ... and tangential ones at t = 5, 15, 25, ...
///
/// Amplitude and width are set by assumption 2 of Guyader & Zhang (2003): a pulse of
/// length d drives C Υ up to about 0.47 d (d in s, unit thrust), so with μ = 4
/// pulses of 1 s keep ‖√μ C Υ‖ ≤ 0.94 ≤ 1, while 5-s pulses would reach 2.2
/// and make the observer diverge.
struct PulseThrusts {
  double amplitude = 1.0;
  double width = 1.0;             ///< s
  double period = 10.0;           ///< s
  double tangential_delay = 5.0;  ///< s

  template <typename S = double>
  Eigen::Matrix<S, 2, 1> operator()(Index k) const {
    // Work on the sample index to avoid rounding at pulse edges.
    const Index per = std::llround(period / sampling_period);
    const Index on = std::llround(width / sampling_period);
    const Index delay = std::llround(tangential_delay / sampling_period);
    const bool radial = k % per < on;
    const bool tangential = k >= delay && (k - delay) % per < on;
    return {radial ? S(amplitude) : S(0), tangential ? S(amplitude) : S(0)};
  }
};

/// \f$\Psi_k = H \begin{bmatrix}0&0\\u^1_k&0\\0&0\\0&u^2_k\end{bmatrix}\f$ (Guyader & Zhang 2003, §4).
template <typename S>
struct ThrustRegressor {
  Eigen::Matrix<S, 4, 4> H = discretized<S>().Bd;
  Eigen::Matrix<S, 4, 2> operator()(Index /*k*/, const Eigen::Matrix<S, 2, 1>& u) const {
    Eigen::Matrix<S, 4, 2> psi;
    psi.col(0) = H.col(1) * u(0);
    psi.col(1) = H.col(3) * u(1);
    return psi;
  }
};

/// The simulated satellite with both outputs disturbed by noise of standard
/// deviation `output_noise` (0.01 in the paper) from `seed`.
template <typename S = double>
auto make_plant(S output_noise = S(0.01), std::uint64_t seed = 2003, PulseThrusts thrusts = {}) {
  PlantNoise<S> noise;
  noise.output = output_noise;
  noise.seed = seed;
  auto input = [thrusts](Index k) { return thrusts.template operator()<S>(k); };
  return DiscreteLinearPlant(model<S>(), initial_state<S>(), true_parameters<S>(), input, ThrustRegressor<S>{}, noise,
                             S(sampling_period));
}

}  // namespace adaptobs::examples::satellite
