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
    // An entry-wise copy: a plain loop the compiler turns into moves, without
    // instantiating Eigen's assignment for every fixed-size type.
    for (Eigen::Index i = 0; i < Derived::SizeAtCompileTime; ++i) destination.data()[i] = computed.data()[i];
  }
}

}  // namespace adaptobs::detail
