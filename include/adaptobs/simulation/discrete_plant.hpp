#pragma once
/// \file
/// Simulated discrete-time plant with unknown parameters and optional noise
/// (Guyader & Zhang 2003, eq. (1)):
/// \f[ \theta_{k+1} = \theta_k + e_k,\quad x_{k+1} = A_kx_k + B_ku_k + f_k + \Psi_k\theta_k + w_k,\quad
///     y_k = C_kx_k + v_k. \f]
/// Inputs and regressors are user callables `input(k)` and `regressor(k, u_k)`;
/// the known input term \f$f_k\f$ (Guyader & Zhang 2003, Remark 1), when given, is
/// the callable `known_input(k, u_k, y_k)` of the measured \f$u_k\f$ and (noisy) \f$y_k\f$.

#include <adaptobs/core/detail/products.hpp>
#include <adaptobs/core/dimensions.hpp>
#include <adaptobs/core/discrete_model.hpp>
#include <adaptobs/core/validation.hpp>
#include <adaptobs/simulation/plant_state.hpp>

#include <cmath>
#include <cstdint>
#include <random>
#include <type_traits>
#include <utility>

namespace adaptobs {

/// The `known_input` of a `DiscreteLinearPlant` without a known input term: its
/// samples' `f` stays empty (\f$f_k = 0\f$).
struct NoKnownInput {};

/// Noise of a simulated plant: zero mean, standard deviations per signal, from a fixed seed.
template <typename Scalar>
struct PlantNoise {
  enum class Distribution { gaussian, uniform };
  Distribution distribution = Distribution::gaussian;  ///< uniform noise is bounded, as theorem 2 assumes
  Scalar output = 0;                                   ///< std of each entry of v_k
  Scalar state = 0;                                    ///< std of each entry of w_k
  Scalar parameter = 0;                                ///< std of each entry of e_k
  std::uint64_t seed = 1;
};

/// The plant of the file comment; its sample of step k is \f$(u_k, y_k, \Psi_k)\f$,
/// and \f$f_k\f$ = `known_input(k, u_k, y_k)` when a known input is given
/// (nx entries, or none for \f$f_k = 0\f$).
template <DiscreteModel Model, class InputFn, class RegressorFn, class KnownInputFn = NoKnownInput>
class DiscreteLinearPlant : public DiscretePlantState<typename Model::Dims, DiscreteSample<typename Model::Dims>> {
  using Base = DiscretePlantState<typename Model::Dims, DiscreteSample<typename Model::Dims>>;
  using Base::x_, Base::theta_, Base::sample_, Base::k_;

 public:
  using typename Base::Scalar, typename Base::State, typename Base::Parameters, typename Base::Sample;

  DiscreteLinearPlant(Model model, State x0, Parameters theta, InputFn input, RegressorFn regressor,
                      PlantNoise<Scalar> noise = {}, Scalar sampling_period = Scalar(1), KnownInputFn known_input = {})
      : Base(std::move(x0), std::move(theta), sampling_period),
        model_(std::move(model)),
        input_(std::move(input)),
        regressor_(std::move(regressor)),
        known_input_(std::move(known_input)),
        noise_(noise),
        rng_(noise.seed) {
    constexpr std::string_view who = "DiscreteLinearPlant";
    require_initial_estimates(x_, model_.sizes().nx, theta_, model_.sizes().np, who, "x0", "theta");
    require_non_negative(noise.output, who, "noise.output");
    require_non_negative(noise.state, who, "noise.state");
    require_non_negative(noise.parameter, who, "noise.parameter");
    require_positive(sampling_period, who, "sampling_period");
    make_sample();
  }

  [[nodiscard]] const Model& model() const noexcept { return model_; }

  /// Sets \f$\theta\f$ from this step on, e.g. to inject a fault; the current
  /// sample is unchanged (θ_k enters x_{k+1}, not y_k).
  void set_parameters(const Parameters& theta) {
    require_finite_shape(theta, theta_.rows(), 1, "DiscreteLinearPlant::set_parameters", "theta");
    theta_ = theta;
  }

  /// Moves to step k + 1. An input, regressor, known input or model matrix of
  /// the wrong size throws a `ConfigurationError` naming the callable, and the
  /// plant stays at step k (its noise generator excepted, when the known input
  /// throws: that one is called with the noisy \f$y_{k+1}\f$).
  void advance() {
    const Index k = k_ + 1;
    // What may throw comes first: the callables of step k + 1.
    decltype(auto) following = model_.at(k);
    Sample next_sample;
    signals_at(k, next_sample);
    decltype(auto) system = model_.at(k_);
    State next = system.A * x_;
    detail::add_product(next, system.B, sample_.u);
    detail::add_known_input(next, sample_.f);
    detail::add_product(next, sample_.Psi, theta_);
    add_noise(next, noise_.state);
    Parameters next_theta = theta_;
    add_noise(next_theta, noise_.parameter);
    next_sample.y = following.C * next;
    add_noise(next_sample.y, noise_.output);
    known_input_at(k, next_sample);
    x_ = std::move(next);
    theta_ = std::move(next_theta);
    k_ = k;
    sample_ = std::move(next_sample);
  }

 private:
  void make_sample() {
    signals_at(k_, sample_);
    sample_.y = model_.at(k_).C * x_;
    add_noise(sample_.y, noise_.output);
    known_input_at(k_, sample_);
  }

  /// \f$f_k\f$ = `known_input(k, u_k, y_k)` into the sample, its size checked; nothing without one.
  void known_input_at(Index k, Sample& sample) {
    if constexpr (!std::is_same_v<KnownInputFn, NoKnownInput>) {
      constexpr std::string_view who = "DiscreteLinearPlant", callable = "known_input(k, u, y)";
      // Checked before it is stored: with a fixed nx, `f` holds at most nx entries.
      decltype(auto) f = known_input_(k, std::as_const(sample.u), std::as_const(sample.y));
      require_vector(f, who, callable);
      if (f.size() != 0 && f.size() != model_.sizes().nx)
        fail_argument(who, callable, "must return nx entries, or none for no known input term");
      require_finite(f, who, callable);
      sample.f = f;
    }
  }

  /// \f$u_k\f$ and \f$\Psi_k\f$ from the callables, their sizes checked.
  void signals_at(Index k, Sample& sample) {
    constexpr std::string_view who = "DiscreteLinearPlant";
    const Sizes s = model_.sizes();
    sample.u = detail::require_returned_shape(input_(k), s.nu, 1, who, "input(k)");
    sample.Psi =
        detail::require_returned_shape(regressor_(k, std::as_const(sample.u)), s.nx, s.np, who, "regressor(k, u)");
  }

  template <class Derived>
  void add_noise(Eigen::MatrixBase<Derived>& v, Scalar std_dev) {
    if (std_dev == Scalar(0)) return;
    for (Index i = 0; i < v.size(); ++i) v(i) += draw(std_dev);
  }

  Scalar draw(Scalar std_dev) {
    if (noise_.distribution == PlantNoise<Scalar>::Distribution::gaussian)
      return std::normal_distribution<Scalar>(Scalar(0), std_dev)(rng_);
    const Scalar half_width = std_dev * std::sqrt(Scalar(3));
    return std::uniform_real_distribution<Scalar>(-half_width, half_width)(rng_);
  }

  Model model_;
  InputFn input_;
  RegressorFn regressor_;
  [[no_unique_address]] KnownInputFn known_input_;
  PlantNoise<Scalar> noise_;
  std::mt19937_64 rng_;
};

}  // namespace adaptobs
