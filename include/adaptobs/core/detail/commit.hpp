#pragma once
/// \file
/// Building blocks of the compute-then-commit update used by every observer:
/// a step is computed into workspace, checked for finiteness, and only then
/// moved into the observer's state, so a rejected step changes nothing.

#include <adaptobs/core/detail/finite.hpp>

#include <Eigen/Core>

namespace adaptobs::detail {

/// Moves a computed value into place: a pointer swap for heap storage, a copy
/// for fixed-size storage (where a swap would cost three copies).
template <class Derived>
void commit(Eigen::PlainObjectBase<Derived>& destination, Eigen::PlainObjectBase<Derived>& computed) {
  if constexpr (Derived::SizeAtCompileTime == Eigen::Dynamic) {
    destination.swap(computed);
  } else {
    destination = computed;
  }
}

}  // namespace adaptobs::detail
