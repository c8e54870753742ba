// Two threads integrating one observer's right-hand side at once, through one
// `odeint_system` object, must each get the single-threaded result bit for bit,
// and ThreadSanitizer must see no data race: `derivative` is const and writes
// only its output (core/continuous_update.hpp). Built with -fsanitize=thread by
// its own CMakeLists.txt; exits non-zero on a mismatch, and ThreadSanitizer
// exits non-zero on a race (TSAN_OPTIONS=halt_on_error=1 in scripts/test.sh).
//
// The observers: Besançon's (Algorithm 3 of Zhang 2005) on the time-varying
// periodic MIMO plant, whose right-hand side forms the transformed system (2),
// the projected filter matrix F(t) = G A_o(t) H of eq. (3a) and the gradient law
// at each call, and the Kalman–Bucy filter on the same plant. Run-time sizes
// too, whose right-hand side works in buffers of its own.

#include <adaptobs/baselines/kalman_bucy.hpp>
#include <adaptobs/core/sampled_integration.hpp>
#include <adaptobs/observers/besancon.hpp>

#include "models/periodic_mimo.hpp"

#include <Eigen/Core>

#include <cmath>
#include <cstdio>
#include <latch>
#include <thread>

namespace {

namespace periodic = adaptobs::examples::periodic;

// u(t) and y(t), smooth and unrelated to any plant.
struct Signals {
  template <class U, class Y>
  void operator()(double t, U& u, Y& y) const {
    u(0) = std::sin(0.4 * t);
    y(0) = std::sin(t) + 0.3 * std::cos(2 * t);
    y(1) = std::cos(0.5 * t) - 0.2;
  }
};

// Classical RK4 with step h from s over `steps` steps of the system f(s, ds, t).
template <class System, class State>
State integrate(const System& f, State s, double h, int steps) {
  State k1 = s, k2 = s, k3 = s, k4 = s;
  for (int i = 0; i < steps; ++i) {
    const double t = i * h;
    f(s, k1, t);
    f(State(s + h / 2 * k1), k2, t + h / 2);
    f(State(s + h / 2 * k2), k3, t + h / 2);
    f(State(s + h * k3), k4, t + h);
    s += h / 6 * (k1 + 2 * k2 + 2 * k3 + k4);
  }
  return s;
}

// The state after 5 s (500 steps) on one thread, then on two at once with the
// same system object; 0 when all three agree exactly and are not all zero.
template <class Observer>
int check_shared(const char* label, const Observer& observer) {
  using State = typename Observer::InternalState;
  const auto system = adaptobs::odeint_system(observer, Signals{});
  State s0 = observer.internal_state();
  s0.setConstant(0.1);  // a state away from the initial zeros, so that every term acts
  const State alone = integrate(system, s0, 0.01, 500);
  State results[2];
  std::latch start(2);
  const auto run = [&](int i) {
    start.arrive_and_wait();
    results[i] = integrate(system, s0, 0.01, 500);
  };
  std::thread first(run, 0), second(run, 1);
  first.join();
  second.join();
  const bool moved = (alone - s0).cwiseAbs().maxCoeff() > 1e-3;
  const bool equal = (results[0].array() == alone.array()).all() && (results[1].array() == alone.array()).all();
  std::printf("%s: %s\n", label, equal && moved ? "threads agree with the single-threaded run" : "MISMATCH");
  return equal && moved ? 0 : 1;
}

template <class D>
auto besancon() {
  const Eigen::MatrixXd T = periodic::coordinate_change<double>();
  const adaptobs::StaticTransform<D> transform(T, Eigen::MatrixXd::Zero(4, 2));
  const auto model = adaptobs::make_continuous_ltv_model<D>(
      [](double t) {
        const auto s = periodic::system<double>(t);
        return adaptobs::ContinuousSystem<D>{s.A, s.B, s.C};
      },
      [](double t) { return typename D::RegressorMatrix(periodic::Regressor{}.operator()<double>(t)); },
      adaptobs::Sizes{4, 1, 2, 2});
  return adaptobs::make_besancon_observer(
      model, transform, typename D::OutputMatrixSquare(2 * Eigen::Matrix2d::Identity()),
      typename D::ParameterMatrix(10 * Eigen::Matrix2d::Identity()), typename D::State(Eigen::Vector4d::Zero()),
      typename D::Parameters(Eigen::Vector2d::Zero()));
}

auto kalman_bucy() {
  using Cov = adaptobs::AugmentedKalmanCovariances<periodic::Dims<double>>;
  const Cov covariances{Cov::AugmentedMatrix::Identity(), Cov::AugmentedMatrix::Identity(),
                        Eigen::Matrix2d::Identity()};
  return adaptobs::AugmentedKalmanBucyFilter(periodic::model<double>(), Eigen::Vector4d::Zero().eval(),
                                             Eigen::Vector2d::Zero().eval(), covariances);
}

}  // namespace

int main() {
  using Fixed = periodic::Dims<double>;
  using Dynamic = adaptobs::Dimensions<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::Dynamic, Eigen::Dynamic>;
  int failures = 0;
  failures += check_shared("Besancon, fixed sizes", besancon<Fixed>());
  failures += check_shared("Besancon, run-time sizes", besancon<Dynamic>());
  failures += check_shared("Kalman-Bucy, fixed sizes", kalman_bucy());
  return failures;
}
