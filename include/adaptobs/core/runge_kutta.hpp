#pragma once
/// \file
/// Classical fourth-order Runge–Kutta step for any state with vector-space operations.
///
/// A *system* is a callable `f(const State& x, State& dxdt, t)` — the system
/// concept of Boost.Odeint — so a right-hand side written for adaptobs runs
/// unchanged under an adaptive integrator, and vice versa. One step from t to
/// t + h evaluates
/// \f[ k_1 = f(x, t),\; k_2 = f(x + \tfrac h2 k_1, t + \tfrac h2),\;
///     k_3 = f(x + \tfrac h2 k_2, t + \tfrac h2),\; k_4 = f(x + h k_3, t + h), \f]
/// \f[ x(t + h) \approx x + \tfrac h6 (k_1 + 2k_2 + 2k_3 + k_4). \f]
/// The stage buffers are members sized once from a model state, so a step on
/// fixed-size Eigen types (and on pre-sized dynamic ones) never allocates.

#include <concepts>

namespace adaptobs {

/// A right-hand side in the Boost.Odeint convention: `f(x, dxdt, t)`.
template <class F, class State, class Time>
concept OdeSystem = std::invocable<F&, const State&, State&, Time>;

/// A state with the vector-space operations a Runge–Kutta step needs
/// (Eigen vectors and matrices qualify).
template <class State, class Scalar>
concept VectorSpaceState = std::copyable<State> && requires(const State& a, const State& b, Scalar s, State& out) {
  out = a + s * b;
  out = a + s * (b + b);
};

/// Fixed-step classical Runge–Kutta integrator with its stage workspace.
template <class State>
class RungeKutta4 {
 public:
  /// \param like a state of the right size (only its shape is used).
  explicit RungeKutta4(const State& like) : k1_(like), k2_(like), k3_(like), k4_(like), stage_(like) {}

  /// `out` ← x advanced from t to t + h. `out` may be `x` itself.
  template <class Time, class System>
    requires OdeSystem<System, State, Time> && VectorSpaceState<State, Time>
  void step(System&& f, const State& x, Time t, Time h, State& out) {
    const Time half = h / Time(2);
    f(x, k1_, t);
    stage_ = x + half * k1_;
    f(stage_, k2_, t + half);
    stage_ = x + half * k2_;
    f(stage_, k3_, t + half);
    stage_ = x + h * k3_;
    f(stage_, k4_, t + h);
    k2_ += k3_;
    out = x + (h / Time(6)) * (k1_ + Time(2) * k2_ + k4_);
  }

  /// `steps` equal steps from t0 to t1, in place.
  template <class Time, class System>
    requires OdeSystem<System, State, Time> && VectorSpaceState<State, Time>
  void integrate(System&& f, State& x, Time t0, Time t1, int steps) {
    const Time h = (t1 - t0) / Time(steps);
    for (int i = 0; i < steps; ++i) step(f, x, t0 + Time(i) * h, h, x);
  }

 private:
  State k1_, k2_, k3_, k4_, stage_;
};

}  // namespace adaptobs
