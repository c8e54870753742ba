#pragma once
// Counts heap allocations: operator new and the C allocation functions that
// Eigen uses. Every test executable links allocation_counter.cpp, with the
// --wrap link options it needs (tests/CMakeLists.txt): the observer contract
// (support/observer_contract.hpp) checks that fixed-size updates do not allocate.

namespace adaptobs::testing {

/// Heap allocations so far by the executable's own code: operator new, malloc,
/// calloc, realloc, aligned_alloc and posix_memalign.
long allocation_count() noexcept;

/// Allocations made while running `f`.
template <class F>
long allocations_during(F&& f) {
  const long before = allocation_count();
  f();
  return allocation_count() - before;
}

}  // namespace adaptobs::testing
