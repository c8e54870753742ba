#pragma once
/// \file
/// The `Observer` concept every adaptive observer (and every baseline) satisfies.

#include <adaptobs/core/dimensions.hpp>
#include <adaptobs/core/status.hpp>
#include <adaptobs/core/validation.hpp>

#include <concepts>

namespace adaptobs {

/// A recursive joint estimator of a state and of unknown parameters.
///
/// - `state()` and `parameters()` give the current estimates \f$\hat x, \hat\theta\f$;
/// - `update(sample)` consumes one sample (the type `O::Sample` says what a
///   sample holds) and returns an `UpdateStatus`; a rejected sample leaves the
///   observer exactly as it was;
/// - `reset(x0, theta0)` restarts from new initial estimates, clearing every
///   internal filter.
template <class O>
concept Observer = requires(O& o, const O& co, const typename O::Sample& sample) {
  typename O::Scalar;
  typename O::State;
  typename O::Parameters;
  typename O::Sample;
  { co.state() } -> std::convertible_to<const typename O::State&>;
  { co.parameters() } -> std::convertible_to<const typename O::Parameters&>;
  { o.update(sample) } -> std::same_as<UpdateStatus>;
  o.reset(co.state(), co.parameters());
};

/// An observer that also takes samples with some output channels absent:
/// `update(sample, present)` with an `OutputMask`, where all channels present is
/// `update(sample)` bit for bit and none is the time update.
template <class O>
concept PartialOutputObserver =
    Observer<O> && requires(O& o, const typename O::Sample& sample, const OutputMask<typename O::Dims>& present) {
      { o.update(sample, present) } -> std::same_as<UpdateStatus>;
      { o.sizes() } -> std::same_as<Sizes>;
    };

/// An observer that exposes what a fault detector tests: `output_error()`, the
/// output error \f$\varepsilon_k = y_k - \hat y_k\f$ of its last accepted update
/// (the innovation, from the prediction the update corrected; zero before the
/// first update and in absent channels). Detectors that test it:
/// diagnostics/chi_square_test.hpp.
template <class O>
concept DiagnosableObserver = Observer<O> && requires(const O& co) {
  { co.output_error() } -> std::convertible_to<const typename O::Dims::Output&>;
};

/// `update` with the output channels whose entry of `sample.y` is finite, the
/// others treated as absent: a sensor glitch (NaN or Inf in y) becomes a partial
/// update, or the time update when no entry is finite, instead of a rejected
/// sample after which the observer falls out of step with the plant. A non-finite
/// input or regressor is still rejected, with the observer unchanged. (With a
/// run-time number of outputs the mask is allocated per call.)
template <PartialOutputObserver O>
[[nodiscard]] UpdateStatus update_finite_outputs(O& observer, const typename O::Sample& sample) {
  if constexpr (O::Dims::ny == Eigen::Dynamic)
    require_shape(sample.y, observer.sizes().ny, 1, "update_finite_outputs", "sample.y");
  const OutputMask<typename O::Dims> present = sample.y.array().isFinite();
  return observer.update(sample, present);
}

}  // namespace adaptobs
