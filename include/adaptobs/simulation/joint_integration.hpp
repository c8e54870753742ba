#pragma once
/// \file
/// Plant and observer integrated as one ODE: the ideal continuous-time observer.
///
/// A sampled observer sees y only at the samples, which leaves an accuracy
/// floor (`core/sampled_integration.hpp`). Stacking the plant state η and the
/// observer's internal state s into one vector and stepping both with the same
/// RK4 feeds the observer \f$y = C(t)\eta\f$ at every stage: the error system of
/// the observers is linear and homogeneous, RK4 commutes with that structure,
/// and the estimates converge to machine precision. Used to test the
/// algorithms themselves and to draw their exact trajectories.

#include <adaptobs/core/dimensions.hpp>
#include <adaptobs/core/runge_kutta.hpp>
#include <adaptobs/core/status.hpp>
#include <adaptobs/core/validation.hpp>

#include <Eigen/Core>

namespace adaptobs {

template <class Plant, class Observer>
class JointIntegration {
 public:
  using Scalar = typename Plant::Scalar;
  using PlantState = typename Plant::State;
  using ObserverState = typename Observer::InternalState;
  static constexpr int size = sum_of_sizes(PlantState::RowsAtCompileTime, ObserverState::RowsAtCompileTime);
  using JointState = Eigen::Matrix<Scalar, size, 1>;

  JointIntegration(Plant& plant, Observer& observer)
      : plant_(plant), observer_(observer), x_(pack()), rk4_(x_), t_(Scalar(plant.time())) {
    u_.setZero(plant.sample().u.rows());
    y_.setZero(plant.sample().y.rows());
    eta_.setZero(plant.state().rows());
    deta_.setZero(plant.state().rows());
    s_.setZero(observer.internal_state().rows());
    ds_.setZero(observer.internal_state().rows());
  }

  /// One RK4 step of length h for the joint state; plant and observer are
  /// updated together. A step that leaves the floating-point range, or that
  /// the observer refuses (`set_internal_state`), changes neither and returns
  /// `UpdateStatus::nonfinite_result`. An h not finite and positive throws a
  /// `ConfigurationError` naming `h`.
  UpdateStatus step(Scalar h) {
    detail::require_positive(h, "JointIntegration::step", "h");
    const Index n = plant_.state().rows();
    const auto f = [&](const JointState& x, JointState& dx, Scalar t) {
      eta_ = x.head(n);
      s_ = x.tail(x.rows() - n);
      plant_.signals(t, eta_, u_, y_);
      plant_.derivative(eta_, deta_, t);
      observer_.derivative(s_, ds_, t, u_, y_);
      dx.head(n) = deta_;
      dx.tail(x.rows() - n) = ds_;
    };
    rk4_.step(f, x_, t_, h, trial_);
    if (!trial_.allFinite() || !observer_.set_internal_state(trial_.tail(trial_.rows() - n)))
      return UpdateStatus::nonfinite_result;
    x_ = trial_;
    t_ += h;
    plant_.set_state(x_.head(n), t_);
    return UpdateStatus::accepted;
  }

  [[nodiscard]] Scalar time() const noexcept { return t_; }

 private:
  JointState pack() const {
    const Index n = plant_.state().rows();
    const Index m = observer_.internal_state().rows();
    JointState x(n + m);
    x.head(n) = plant_.state();
    x.tail(m) = observer_.internal_state();
    return x;
  }

  Plant& plant_;
  Observer& observer_;
  JointState x_;
  JointState trial_ = x_;  ///< the step's result, kept only once both sides accept it
  RungeKutta4<JointState> rk4_;
  Scalar t_;
  typename Plant::Input u_;
  typename Plant::Output y_;
  PlantState eta_, deta_;
  ObserverState s_, ds_;
};

}  // namespace adaptobs
