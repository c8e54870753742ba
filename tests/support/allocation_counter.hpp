#pragma once
// Counts calls of the global allocation functions. Only the test executable
// `test_no_allocation` links allocation_counter.cpp, which replaces
// operator new; each observer adds its own no_allocation_<observer>.cpp there.

namespace adaptobs::testing {

/// Number of global operator new calls so far in this process.
long allocation_count() noexcept;

/// Allocations made while running `f`.
template <class F>
long allocations_during(F&& f) {
  const long before = allocation_count();
  f();
  return allocation_count() - before;
}

}  // namespace adaptobs::testing
