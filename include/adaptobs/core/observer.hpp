#pragma once
/// \file
/// The `Observer` concept every adaptive observer (and every baseline) satisfies.

#include <adaptobs/core/status.hpp>

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

}  // namespace adaptobs
