#pragma once
// Counts heap allocations inside a scope, for tests that prove a loop allocates nothing.
//
// The test binary interposes malloc, calloc, realloc, posix_memalign, aligned_alloc and
// memalign and forwards them to glibc's own entry points (__libc_malloc, ...); everything
// that allocates goes through these: operator new, Eigen (aligned_malloc → malloc),
// CHOLMOD/KLU (SuiteSparse_malloc → malloc). free() is not replaced (the memory comes from
// glibc's allocator either way). Include this header in exactly one source file of a test
// binary (it defines the C functions). Counting is global (all threads); the solvers under
// test run single-threaded inside the counted scope.
#include <atomic>
#include <cstddef>
#include <cstdlib>
#include <malloc.h>

extern "C" {
void* __libc_malloc(std::size_t size);
void* __libc_calloc(std::size_t count, std::size_t size);
void* __libc_realloc(void* ptr, std::size_t size);
void* __libc_memalign(std::size_t alignment, std::size_t size);
}

namespace lcprelax::test {

inline std::atomic<bool> g_count_allocations{false};
inline std::atomic<long> g_allocations{0};

inline void note_allocation() {
  if (g_count_allocations.load(std::memory_order_relaxed)) g_allocations.fetch_add(1, std::memory_order_relaxed);
}

/// Counts the allocations made between construction and count() (or destruction).
class AllocationCounter {
 public:
  AllocationCounter() {
    g_allocations.store(0);
    g_count_allocations.store(true);
  }
  ~AllocationCounter() { g_count_allocations.store(false); }
  AllocationCounter(const AllocationCounter&) = delete;
  AllocationCounter& operator=(const AllocationCounter&) = delete;
  /// Allocations so far (stops counting).
  long stop() {
    g_count_allocations.store(false);
    return g_allocations.load();
  }
};

}  // namespace lcprelax::test

extern "C" {
void* malloc(std::size_t size) noexcept {
  lcprelax::test::note_allocation();
  return __libc_malloc(size);
}
void* calloc(std::size_t count, std::size_t size) noexcept {
  lcprelax::test::note_allocation();
  return __libc_calloc(count, size);
}
void* realloc(void* ptr, std::size_t size) noexcept {
  lcprelax::test::note_allocation();
  return __libc_realloc(ptr, size);
}
void* memalign(std::size_t alignment, std::size_t size) noexcept {
  lcprelax::test::note_allocation();
  return __libc_memalign(alignment, size);
}
void* aligned_alloc(std::size_t alignment, std::size_t size) noexcept {
  lcprelax::test::note_allocation();
  return __libc_memalign(alignment, size);
}
int posix_memalign(void** out, std::size_t alignment, std::size_t size) noexcept {
  lcprelax::test::note_allocation();
  void* p = __libc_memalign(alignment, size);
  if (!p) return 12;  // ENOMEM
  *out = p;
  return 0;
}
}
