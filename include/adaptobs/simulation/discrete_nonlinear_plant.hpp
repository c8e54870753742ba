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

#include <concepts>
#include <utility>

namespace adaptobs {

template <StateSpace D, class TransitionFn, class InputFn, class ParameterFn>
  requires std::invocable<const TransitionFn&, const typename D::State&, const typename D::Input&,
                          const typename D::Parameters&> &&
           std::invocable<InputFn&, Index> && std::invocable<const ParameterFn&, Index>
class DiscreteNonlinearPlant : public SizedBy<D> {
 public:
  using typename SizedBy<D>::Scalar, typename SizedBy<D>::State, typename SizedBy<D>::Parameters;
  using Sample = InputOutputSample<D>;

  DiscreteNonlinearPlant(TransitionFn transition, typename D::OutputMatrix C, State x0, InputFn input,
                         ParameterFn parameters_at, Scalar sampling_period = Scalar(1))
      : transition_(std::move(transition)),
        C_(std::move(C)),
        x_(std::move(x0)),
        input_(std::move(input)),
        parameters_at_(std::move(parameters_at)),
        period_(sampling_period) {
    constexpr std::string_view who = "DiscreteNonlinearPlant";
    detail::require_shape(C_, C_.rows(), x_.rows(), who, "C");
    detail::require_finite(C_, who, "C");
    detail::require_finite(x_, who, "x0");
    detail::require_positive(sampling_period, who, "sampling_period");
    make_sample();
  }

  /// Measured sample of the current step: \f$(u_k, y_k)\f$.
  [[nodiscard]] const Sample& sample() const noexcept { return sample_; }
  /// True state \f$x_k\f$ and parameters \f$\theta_k\f$.
  [[nodiscard]] const State& state() const noexcept { return x_; }
  [[nodiscard]] const Parameters& parameters() const noexcept { return theta_; }
  [[nodiscard]] Index step() const noexcept { return k_; }
  [[nodiscard]] double time() const noexcept { return static_cast<double>(k_) * static_cast<double>(period_); }

  /// Moves to step k + 1.
  void advance() {
    x_ = transition_(std::as_const(x_), std::as_const(sample_.u), std::as_const(theta_));
    ++k_;
    make_sample();
  }

 private:
  void make_sample() {
    theta_ = parameters_at_(k_);
    sample_.u = input_(k_);
    sample_.y.noalias() = C_ * x_;
  }

  TransitionFn transition_;
  typename D::OutputMatrix C_;
  State x_;
  InputFn input_;
  ParameterFn parameters_at_;
  Scalar period_;
  Parameters theta_;
  Sample sample_;
  Index k_ = 0;
};

/// `make_discrete_nonlinear_plant<D>(f, C, x0, input, parameters_at)`: deduces the callables' types.
template <StateSpace D, class TransitionFn, class InputFn, class ParameterFn>
[[nodiscard]] auto make_discrete_nonlinear_plant(TransitionFn transition, typename D::OutputMatrix C,
                                                 typename D::State x0, InputFn input, ParameterFn parameters_at,
                                                 typename D::Scalar sampling_period = typename D::Scalar(1)) {
  return DiscreteNonlinearPlant<D, TransitionFn, InputFn, ParameterFn>(std::move(transition), std::move(C),
                                                                       std::move(x0), std::move(input),
                                                                       std::move(parameters_at), sampling_period);
}

}  // namespace adaptobs
