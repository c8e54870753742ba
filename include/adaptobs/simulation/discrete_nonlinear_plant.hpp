#pragma once
/// \file
/// Simulated nonlinear discrete-time plant
/// \f[ x_{k+1} = f(x_k, u_k, \theta_k),\qquad y_k = Cx_k, \f]
/// with user callables for the transition `f(x, u, theta)`, the input `input(k)`
/// and the (possibly time-varying) parameters `parameters_at(k)`. Its samples are
/// `InputOutputSample`s \f$(u_k, y_k)\f$, so it drives observers of nonlinear or
/// polytopic models through `simulate()`.

#include <adaptobs/core/dimensions.hpp>
#include <adaptobs/core/discrete_model.hpp>
#include <adaptobs/core/validation.hpp>
#include <adaptobs/simulation/plant_state.hpp>

#include <concepts>
#include <utility>

namespace adaptobs {

/// The plant of the file comment; its sample of step k is \f$(u_k, y_k)\f$.
template <StateSpace D, class TransitionFn, class InputFn, class ParameterFn>
  requires std::invocable<const TransitionFn&, const typename D::State&, const typename D::Input&,
                          const typename D::Parameters&> &&
           std::invocable<InputFn&, Index> && std::invocable<const ParameterFn&, Index>
class DiscreteNonlinearPlant : public DiscretePlantState<D, InputOutputSample<D>> {
  using Base = DiscretePlantState<D, InputOutputSample<D>>;
  using Base::x_, Base::theta_, Base::sample_, Base::k_;

 public:
  using typename Base::Scalar, typename Base::State, typename Base::Parameters;

  DiscreteNonlinearPlant(TransitionFn transition, typename D::OutputMatrix C, State x0, InputFn input,
                         ParameterFn parameters_at, Scalar sampling_period = Scalar(1))
      : Base(std::move(x0), sampling_period),
        transition_(std::move(transition)),
        C_(std::move(C)),
        input_(std::move(input)),
        parameters_at_(std::move(parameters_at)) {
    constexpr std::string_view who = "DiscreteNonlinearPlant";
    require_finite_shape(C_, C_.rows(), x_.rows(), who, "C");
    require_finite(x_, who, "x0");
    require_positive(sampling_period, who, "sampling_period");
    // The plant has no model to give nu and np: step 0's input and parameters
    // set them (with run-time sizes), and every later step must keep them.
    sample_.u = input_(Index{0});
    theta_ = parameters_at_(Index{0});
    require_shape(sample_.u, sample_.u.rows(), 1, who, "input(k)");
    require_finite(theta_, who, "parameters_at(k)");
    sample_.y.noalias() = C_ * x_;
  }

  /// Moves to step k + 1. An input or parameters of another size than at
  /// step 0, non-finite parameters, or a transition returning a state of another size, throws a
  /// `ConfigurationError` naming the callable, with the plant at step k.
  void advance() {
    constexpr std::string_view who = "DiscreteNonlinearPlant";
    const Index k = k_ + 1;
    // What may throw comes first, before anything moves.
    typename D::Input u = detail::require_returned_shape(input_(k), sample_.u.rows(), 1, who, "input(k)");
    Parameters theta = detail::require_returned_shape(parameters_at_(k), theta_.rows(), 1, who, "parameters_at(k)");
    require_finite(theta, who, "parameters_at(k)");
    x_ = detail::require_returned_shape(transition_(std::as_const(x_), std::as_const(sample_.u), std::as_const(theta_)),
                                        x_.rows(), 1, who, "transition(x, u, theta)");
    k_ = k;
    sample_.u = std::move(u);
    theta_ = std::move(theta);
    sample_.y.noalias() = C_ * x_;
  }

 private:
  TransitionFn transition_;
  typename D::OutputMatrix C_;
  InputFn input_;
  ParameterFn parameters_at_;
};

/// `make_discrete_nonlinear_plant<D>(f, C, x0, input, parameters_at)`: deduces the callables' types.
template <StateSpace D, class TransitionFn, class InputFn, class ParameterFn>
[[nodiscard]] auto make_discrete_nonlinear_plant(TransitionFn transition, typename D::OutputMatrix C,
                                                 typename D::State x0, InputFn input, ParameterFn parameters_at,
                                                 typename D::Scalar sampling_period = typename D::Scalar(1)) {
  return DiscreteNonlinearPlant<D, TransitionFn, InputFn, ParameterFn>(
      std::move(transition), std::move(C), std::move(x0), std::move(input), std::move(parameters_at), sampling_period);
}

}  // namespace adaptobs
