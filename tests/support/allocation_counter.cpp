// Counts every heap allocation the test executable's own code makes.
//
// Eigen allocates with std::malloc (or posix_memalign/aligned_alloc), not
// operator new, so replacing operator new alone would miss it. The executable
// is therefore linked with --wrap for each C allocation function (see
// tests/CMakeLists.txt): every call to malloc from the project's objects goes to
// __wrap_malloc below, which counts it and calls the real one (the C library's,
// or a sanitizer's interceptor). operator new, replaced here, counts itself and
// allocates through __real_malloc, so that it is not counted twice.

#include "support/allocation_counter.hpp"

#include <atomic>
#include <cstddef>
#include <new>

namespace {
std::atomic<long> allocations{0};
}  // namespace

extern "C" {
void* __real_malloc(std::size_t size);
void* __real_calloc(std::size_t count, std::size_t size);
void* __real_realloc(void* p, std::size_t size);
void* __real_aligned_alloc(std::size_t alignment, std::size_t size);
int __real_posix_memalign(void** p, std::size_t alignment, std::size_t size);

void* __wrap_malloc(std::size_t size) {
  ++allocations;
  return __real_malloc(size);
}
void* __wrap_calloc(std::size_t count, std::size_t size) {
  ++allocations;
  return __real_calloc(count, size);
}
void* __wrap_realloc(void* p, std::size_t size) {
  ++allocations;
  return __real_realloc(p, size);
}
void* __wrap_aligned_alloc(std::size_t alignment, std::size_t size) {
  ++allocations;
  return __real_aligned_alloc(alignment, size);
}
int __wrap_posix_memalign(void** p, std::size_t alignment, std::size_t size) {
  ++allocations;
  return __real_posix_memalign(p, alignment, size);
}
}  // extern "C"

long adaptobs::testing::allocation_count() noexcept { return allocations.load(); }

void* operator new(std::size_t size) {
  ++allocations;
  if (void* p = __real_malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}
void* operator new[](std::size_t size) { return ::operator new(size); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
