// RK4 stepping of the continuous-time observers against an independent
// high-accuracy integration (Boost.Odeint, Dormand–Prince 5(4) with
// tolerances 1e-12), both driven by the same smooth signals u(t), y(t). The
// observers' right-hand sides are passed to Odeint unchanged: they follow its
// system concept.

#include <adaptobs/simulation/continuous_plant.hpp>

#include "unified_fixtures.hpp"

#include <gtest/gtest.h>
#include <boost/numeric/odeint.hpp>
#include <boost/numeric/odeint/external/eigen/eigen.hpp>

#include <cmath>

namespace {

using namespace adaptobs::testing::unified;
namespace odeint = boost::numeric::odeint;

// Smooth signals, unrelated to any plant: an observer is an ODE driven by u and y.
struct MimoSignals {
  void operator()(double t, Eigen::Matrix<double, 1, 1>& u, Eigen::Vector2d& y) const {
    u(0) = std::sin(0.4 * t);
    y << std::sin(t) + 0.3 * std::cos(2 * t), std::cos(0.5 * t) - 0.2;
  }
};
struct SisoSignals {
  void operator()(double t, Eigen::Matrix<double, 1, 1>& u, Eigen::Matrix<double, 1, 1>& y) const {
    u(0) = 1 + std::sin(0.3 * t);
    y(0) = std::sin(0.9 * t) + 0.5 * std::cos(1.3 * t);
  }
};

// The observer's update() with samples at t_k and midpoints, one RK4 step per
// interval h, against Odeint on adaptobs::odeint_system(observer, signals).
template <class Observer, class Signals>
void compare_with_odeint(Observer observer, Signals signals, double h, double duration) {
  using Sample = typename Observer::Sample;
  const auto sample_at = [&](double t, bool with_midpoint) {
    Sample s;
    s.t = t;
    signals(t, s.u, s.y);
    if (with_midpoint) {
      typename Sample::Midpoint m;
      signals(t - h / 2, m.u, m.y);
      s.midpoint = m;
    }
    return s;
  };
  auto reference = observer.internal_state();
  ASSERT_EQ(observer.update(sample_at(0.0, false)), adaptobs::UpdateStatus::accepted);
  const long steps = std::lround(duration / h);
  for (long k = 1; k <= steps; ++k)
    ASSERT_EQ(observer.update(sample_at(double(k) * h, true)), adaptobs::UpdateStatus::accepted);

  using State = typename Observer::InternalState;
  using Stepper = odeint::runge_kutta_dopri5<State, double, State, double, odeint::vector_space_algebra>;
  odeint::integrate_adaptive(odeint::make_controlled(1e-12, 1e-12, Stepper()),
                             adaptobs::odeint_system(observer, signals), reference, 0.0, duration, 1e-3);
  const double scale = std::max(1.0, reference.cwiseAbs().maxCoeff());
  EXPECT_LT((observer.internal_state() - reference).cwiseAbs().maxCoeff(), 1e-8 * scale);
}

TEST(RungeKutta, MatchesOdeintDormandPrince) {
  compare_with_odeint(zhang_observer<double>(10.0), MimoSignals{}, 0.005, 10.0);
  compare_with_odeint(besancon_observer<double>(), MimoSignals{}, 0.005, 10.0);
  compare_with_odeint(bastin_gevers_observer<double>(), SisoSignals{}, 0.005, 10.0);
  compare_with_odeint(marino_tomei_observer<double>(), SisoSignals{}, 0.005, 10.0);
  compare_with_odeint(kalman_bucy_filter<double>(1.0), SisoSignals{}, 0.005, 10.0);
}

// The step itself on a linear ODE with a known solution: x' = Ax, x(t) = e^{At}x0.
TEST(RungeKutta, FourthOrderOnALinearSystem) {
  Eigen::Matrix2d a;
  a << 0, 1, -4, -0.4;
  const Eigen::Vector2d x0(1, 0);
  const auto exact = [&](double t) {
    // Underdamped oscillator: eigenvalues −0.2 ± i√3.96.
    const double w = std::sqrt(3.96);
    const double c = std::cos(w * t), s = std::sin(w * t), e = std::exp(-0.2 * t);
    return Eigen::Vector2d(e * (c + 0.2 / w * s), e * (-4.0 / w * s));
  };
  double previous_error = 0;
  for (int steps : {100, 200, 400}) {
    Eigen::Vector2d x = x0;
    adaptobs::RungeKutta4<Eigen::Vector2d> rk4(x);
    rk4.integrate([&](const Eigen::Vector2d& v, Eigen::Vector2d& dv, double) { dv = a * v; }, x, 0.0, 5.0, steps);
    const double error = (x - exact(5.0)).norm();
    if (previous_error > 0) {
      EXPECT_NEAR(previous_error / error, 16.0, 1.0) << steps;
    }
    previous_error = error;
  }
  EXPECT_LT(previous_error, 1e-6);
}

}  // namespace
