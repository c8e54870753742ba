#pragma once
/// \file
/// Simulated continuous-time plant with unknown parameters (Zhang 2005, eq. (1)):
/// \f[ \dot\eta = A(t)\eta + B(t)u(t) + \Phi\theta,\qquad y = C(t)\eta + v, \f]
/// integrated with RK4 (inputs and regressor evaluated exactly at the stage
/// times) and sampled every `period`: each sample carries \f$u, y\f$ at \f$t_k\f$ and
/// at the midpoint of \f$[t_{k-1}, t_k]\f$, so observers may use any
/// `SignalReconstruction`. It satisfies the `Plant` concept of `runner.hpp`.
/// `derivative` exposes the plant's right-hand side for joint plant–observer
/// integration (`joint_integration.hpp`).

#include <adaptobs/core/continuous_model.hpp>
#include <adaptobs/core/detail/products.hpp>
#include <adaptobs/core/dimensions.hpp>
#include <adaptobs/core/runge_kutta.hpp>
#include <adaptobs/core/validation.hpp>
#include <adaptobs/simulation/plant_state.hpp>

#include <cmath>
#include <cstdint>
#include <random>
#include <utility>

namespace adaptobs {

/// Sampling and noise of a simulated continuous-time plant.
template <typename Scalar>
struct ContinuousPlantOptions {
  Scalar period = Scalar(0.01);  ///< sampling period
  int substeps = 2;              ///< RK4 steps per half period
  Scalar output_noise = 0;       ///< standard deviation of each entry of v (Gaussian)
  std::uint64_t seed = 1;
  Scalar start_time = 0;
};

template <ContinuousModel Model, class InputFn>
class ContinuousLinearPlant : public Model::Dims {
 public:
  using Dims = typename Model::Dims;
  using typename Dims::Scalar, typename Dims::State, typename Dims::Parameters, typename Dims::Input,
      typename Dims::Output;
  using Sample = ContinuousSample<Dims>;

  ContinuousLinearPlant(Model model, State eta0, Parameters theta, InputFn input,
                        ContinuousPlantOptions<Scalar> options = {})
      : model_(std::move(model)),
        eta_(std::move(eta0)),
        theta_(std::move(theta)),
        input_(std::move(input)),
        options_(options),
        origin_(options.start_time),
        rk4_(eta_),
        rng_(options.seed) {
    constexpr std::string_view who = "ContinuousLinearPlant";
    require_initial_estimates(eta_, model_.sizes().nx, theta_, model_.sizes().np, who, "eta0", "theta");
    require_positive(options.period, who, "options.period");
    require(options.substeps >= 1, who, "options.substeps", "must be at least 1");
    require_non_negative(options.output_noise, who, "options.output_noise");
    require(std::isfinite(options.start_time), who, "options.start_time", "must be finite");
    sample_.t = origin_;
    sample_.u = input_at(sample_.t);
    sample_.y = measure(sample_.t, eta_);
  }

  /// Measured sample at the current time (with the midpoint of the last interval after the first advance).
  [[nodiscard]] const Sample& sample() const noexcept { return sample_; }
  [[nodiscard]] const State& state() const noexcept { return eta_; }
  [[nodiscard]] const Parameters& parameters() const noexcept { return theta_; }
  [[nodiscard]] double time() const noexcept { return static_cast<double>(sample_.t); }
  [[nodiscard]] const Model& model() const noexcept { return model_; }

  /// Moves one period forward.
  void advance() {
    const Scalar half = options_.period / Scalar(2);
    const Scalar t0 = sample_.t;
    const auto f = [this](const State& x, State& dx, Scalar t) { derivative(x, dx, t); };
    rk4_.integrate(f, eta_, t0, t0 + half, options_.substeps);
    typename Sample::Midpoint mid{input_at(t0 + half), measure(t0 + half, eta_)};
    rk4_.integrate(f, eta_, t0 + half, t0 + options_.period, options_.substeps);
    // The clock counts periods from its origin: adding the period at each step
    // would accumulate its rounding (a float clock would drift by a period in 10⁵ steps).
    ++periods_;
    sample_.t = origin_ + Scalar(periods_) * options_.period;
    sample_.u = input_at(sample_.t);
    sample_.y = measure(sample_.t, eta_);
    sample_.midpoint = std::move(mid);
  }

  /// \f$\dot\eta = A(t)\eta + B(t)u(t) + \Phi\theta\f$.
  void derivative(const State& eta, State& deta, Scalar t) const {
    decltype(auto) s = model_.at(t);
    const Input u = input_at(t);
    const Output y = s.C * eta;
    deta.noalias() = s.A * eta;
    detail::add_product(deta, s.B, u);
    detail::add_product(deta, model_.regressor(t, u, y), theta_);
  }

  /// Noise-free input and output at time t for the state η (for joint integration).
  void signals(Scalar t, const State& eta, Input& u, Output& y) const {
    u = input_at(t);
    y.noalias() = model_.at(t).C * eta;
  }

  /// Places the plant at (η, t) (after a joint integration step); the sample is re-measured without midpoint.
  void set_state(const State& eta, Scalar t) {
    eta_ = eta;
    origin_ = t;
    periods_ = 0;
    sample_.t = t;
    sample_.u = input_at(t);
    sample_.y = measure(t, eta_);
    sample_.midpoint.reset();
  }

 private:
  /// u(t), its size checked: a wrong one would be read past B's columns.
  Input input_at(Scalar t) const {
    return detail::require_returned_shape(input_(t), model_.sizes().nu, 1, "ContinuousLinearPlant", "input(t)");
  }

  Output measure(Scalar t, const State& eta) {
    Output y = model_.at(t).C * eta;
    if (options_.output_noise > 0) {
      std::normal_distribution<Scalar> noise(Scalar(0), options_.output_noise);
      for (Index i = 0; i < y.size(); ++i) y(i) += noise(rng_);
    }
    return y;
  }

  Model model_;
  State eta_;
  Parameters theta_;
  InputFn input_;
  ContinuousPlantOptions<Scalar> options_;
  Scalar origin_;          ///< start time, or the time of the last `set_state`
  long long periods_ = 0;  ///< periods advanced since origin_
  RungeKutta4<State> rk4_;
  std::mt19937_64 rng_;
  Sample sample_;
};

}  // namespace adaptobs
