#pragma once
// Counts heap allocations: operator new and the C allocation functions that
// Eigen uses. Only the test executable `test_no_allocation` links
// allocation_counter.cpp (with the --wrap link options it needs); each observer
// adds its own no_allocation_<observer>.cpp there.

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
