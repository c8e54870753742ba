#pragma once
/// \file
/// A permanent-magnet DC motor with an unknown load torque and viscous
/// friction, written as the discrete model of the Guyader–Zhang observer: the
/// plant of the tutorial (docs/tutorial.md), shared by its example and tests.
///
/// Physics, with current i (A), speed ω (rad/s) and voltage V (V):
/// \f[ L\,\frac{di}{dt} = -Ri - K_e\omega + V,\qquad
///     J\,\frac{d\omega}{dt} = K_ti - b\,\omega - T_L. \f]
/// The unknowns are the load torque \f$T_L\f$ (N·m) and the friction
/// coefficient b. Both enter linearly, so they are the parameters; b is
/// scaled by a nominal speed, \f$\theta = (T_L,\ b\,\omega_{ref})\f$, so that both
/// are torques of the same order (the step size μ is one number for all of
/// θ, and a parameter a hundred times smaller than another would converge ten
/// thousand times slower). Then
/// \f[ \dot x = A_cx + B_cV + \Psi_c(\omega)\theta,\quad
///     A_c = \begin{bmatrix} -R/L & -K_e/L\\ K_t/J & 0\end{bmatrix},\quad
///     B_c = \begin{bmatrix} 1/L\\ 0\end{bmatrix},\quad
///     \Psi_c(\omega) = \begin{bmatrix} 0 & 0\\ -1/J & -\omega/(J\omega_{ref})\end{bmatrix}, \f]
/// and both i and ω are measured, y = x. The regressor holds a measured
/// signal, ω, which is allowed: Ψ_k need only be known at step k.
///
/// Sampled with a zero-order hold at Ts (V held, and ω taken at the sample
/// over the interval, which is exact for the load and approximate to
/// \f$O(T_s\,|\dot\omega|/|\omega|)\f$ for the friction):
/// \f$x_{k+1} = A x_k + B V_k + \Psi_k\theta\f$ with \f$A = e^{A_cT_s}\f$,
/// \f$B = \int_0^{T_s}e^{A_cs}ds\,B_c\f$ and \f$\Psi_k = \int_0^{T_s}e^{A_cs}ds\,\Psi_c(\omega_k)\f$.

#include <adaptobs/core/dimensions.hpp>
#include <adaptobs/core/discrete_model.hpp>
#include <adaptobs/core/discretization.hpp>
#include <adaptobs/core/observer.hpp>

#include <Eigen/Core>

#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

namespace adaptobs::examples::dc_motor {

using Dims = Dimensions<double, /*nx*/ 2, /*nu*/ 1, /*ny*/ 2, /*np*/ 2>;

/// The motor's constants (SI units) and sampling period.
struct Motor {
  double R = 2.0;                 ///< armature resistance, Ω
  double L = 0.01;                ///< armature inductance, H
  double Ke = 0.1;                ///< back-EMF constant, V·s/rad
  double Kt = 0.1;                ///< torque constant, N·m/A
  double J = 1e-4;                ///< rotor inertia, kg·m²
  double omega_ref = 100.0;       ///< speed that scales the friction parameter, rad/s
  double sampling_period = 1e-3;  ///< Ts, s (1 kHz)
};

/// θ = (T_L, b ω_ref) of a load torque (N·m) and friction coefficient b (N·m·s/rad).
inline Eigen::Vector2d parameters(const Motor& m, double load_torque, double friction) {
  return {load_torque, friction * m.omega_ref};
}

inline Eigen::Matrix2d continuous_dynamics(const Motor& m) {
  Eigen::Matrix2d a;
  a << -m.R / m.L, -m.Ke / m.L,  //
      m.Kt / m.J, 0.0;
  return a;
}

/// The sampled model: A, B, C = I, and the integral of the exponential that
/// turns \f$\Psi_c(\omega)\f$ into \f$\Psi_k\f$.
struct SampledMotor {
  Motor motor;
  Eigen::Matrix2d A, integral;  // e^{A_c Ts} and ∫_0^{Ts} e^{A_c s} ds
  Eigen::Vector2d B;

  explicit SampledMotor(const Motor& m)
      : motor(m),
        A(discretize_zoh(continuous_dynamics(m), Eigen::Vector2d(1 / m.L, 0), m.sampling_period).Ad),
        integral(integral_of_exponential(continuous_dynamics(m), m.sampling_period)),
        B(integral * Eigen::Vector2d(1 / m.L, 0)) {}

  /// \f$\Psi_k\f$ at the measured speed ω_k.
  [[nodiscard]] Eigen::Matrix2d regressor(double omega) const {
    Eigen::Matrix2d psi_c;
    psi_c << 0.0, 0.0,  //
        -1 / motor.J, -omega / (motor.J * motor.omega_ref);
    return integral * psi_c;
  }

  [[nodiscard]] DiscreteLtiModel<Dims> model() const { return {A, B, Eigen::Matrix2d::Identity()}; }
};

/// The test voltage: ±`amplitude` V, a square wave of `period` seconds. A
/// two-sided wave drives ω through both signs, which separates the load
/// (constant) from the friction (proportional to ω).
inline double voltage(double t, double amplitude = 10.0, double period = 0.5) {
  return std::fmod(t, period) < period / 2 ? amplitude : -amplitude;
}

/// One simulated run of the motor: what the observer is given at each sample
/// (u_k, y_k, and Ψ_k built from the *measured* speed), and the truth beside it.
struct Run {
  std::vector<DiscreteSample<Dims>> samples;
  std::vector<Eigen::Vector2d> states, parameters;
};

/// The tutorial's experiment: the test voltage from rest, noisy sensors, and
/// the friction multiplied by `friction_factor` from `fault_time` on.
struct Scenario {
  double load_torque = 0.02;                                    ///< T_L, N·m
  double friction = 1e-4;                                       ///< b before the fault, N·m·s/rad
  double current_noise = 0.01;                                  ///< standard deviation of the current sensor, A
  double speed_noise = 0.5;                                     ///< of the speed from the encoder, rad/s
  double fault_time = std::numeric_limits<double>::infinity();  ///< s
  double friction_factor = 1;

  /// θ at time t.
  [[nodiscard]] Eigen::Vector2d parameters_at(const Motor& m, double t) const {
    return parameters(m, load_torque, t >= fault_time ? friction * friction_factor : friction);
  }

  /// `seconds` of samples at the motor's rate, the noise drawn from `seed`.
  [[nodiscard]] Run simulate(const SampledMotor& plant, double seconds, std::uint64_t seed) const {
    std::mt19937_64 rng(seed);
    std::normal_distribution<double> gauss;
    const double ts = plant.motor.sampling_period;
    const auto steps = static_cast<Index>(std::llround(seconds / ts));
    Run run;
    Eigen::Vector2d x = Eigen::Vector2d::Zero();
    for (Index k = 0; k < steps; ++k) {
      const double t = static_cast<double>(k) * ts;
      const Eigen::Vector2d theta = parameters_at(plant.motor, t);
      const Eigen::Matrix<double, 1, 1> u(voltage(t));
      // The two draws in a fixed order (function arguments are evaluated in an
      // unspecified order, which g++ and clang++ do not share).
      const double speed_error = speed_noise * gauss(rng);
      const Eigen::Vector2d y = x + Eigen::Vector2d(current_noise * gauss(rng), speed_error);
      run.samples.push_back({u, y, plant.regressor(y(1))});
      run.states.push_back(x);
      run.parameters.push_back(theta);
      x = plant.A * x + plant.B * u + plant.regressor(x(1)) * theta;
    }
    return run;
  }
};

/// The Ψ_k of a run, for the tuning routines (design/guyader_zhang_tuning.hpp).
inline std::vector<Eigen::Matrix2d> regressors_of(const Run& run) {
  std::vector<Eigen::Matrix2d> psi;
  for (const auto& s : run.samples) psi.push_back(s.Psi);
  return psi;
}

}  // namespace adaptobs::examples::dc_motor
