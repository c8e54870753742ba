#pragma once
/// \file
/// Whether a model, discrete or continuous, gives the same (A, B, C) at every
/// instant, known at compile time or, for a model type that may hold either kind,
/// at run time.

#include <concepts>

namespace adaptobs {

/// True when `model` gives the same (A, B, C) at every step or time:
/// `M::time_invariant`, or, for a model type that may hold either kind
/// (`M::time_invariant` false), its own run-time answer `model.is_time_invariant()`
/// when it has one. An observer caches what depends on the matrices alone (A − KC,
/// a transformed system) only when this holds.
template <class M>
[[nodiscard]] constexpr bool is_time_invariant(const M& model) {
  if constexpr (M::time_invariant)
    return true;
  else if constexpr (requires {
                       { model.is_time_invariant() } -> std::convertible_to<bool>;
                     })
    return model.is_time_invariant();
  else
    return false;
}

}  // namespace adaptobs
