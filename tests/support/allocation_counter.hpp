// Counts heap allocations in a test executable: malloc and friends are interposed (include this
// header in exactly one source file of the executable) and counted while g_counting is set, in
// all (g_allocations) and per thread (t_allocations).
// glibc only; off under AddressSanitizer or ThreadSanitizer, which own malloc
// (TACTA_COUNT_ALLOCATIONS is then 0 and tests should skip).
#pragma once

#include <cstddef>
#include <cstdlib>  // glibc declares these noexcept; the definitions below match

#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
#define TACTA_COUNT_ALLOCATIONS 0
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define TACTA_COUNT_ALLOCATIONS 0
#endif
#endif
#ifndef TACTA_COUNT_ALLOCATIONS
#define TACTA_COUNT_ALLOCATIONS 1
#endif

namespace {
bool g_counting = false;  // count while true
long g_allocations = 0;
// The same count per thread: a test whose other threads allocate by design (a worker) reads the
// thread it checks.
thread_local long t_allocations = 0;
// Heap allocations on every thread while `work` runs (0 where TACTA_COUNT_ALLOCATIONS is 0).
template <class Work>
long allocations_in(Work&& work) {
  g_allocations = 0;
  g_counting = true;
  work();
  g_counting = false;
  return g_allocations;
}
}  // namespace

#if TACTA_COUNT_ALLOCATIONS
extern "C" {
void* __libc_malloc(size_t);
void* __libc_calloc(size_t, size_t);
void* __libc_realloc(void*, size_t);
void* __libc_memalign(size_t, size_t);
void* malloc(size_t size) noexcept {
  if (g_counting) ++g_allocations, ++t_allocations;
  return __libc_malloc(size);
}
void* calloc(size_t count, size_t size) noexcept {
  if (g_counting) ++g_allocations, ++t_allocations;
  return __libc_calloc(count, size);
}
void* realloc(void* pointer, size_t size) noexcept {
  if (g_counting) ++g_allocations, ++t_allocations;
  return __libc_realloc(pointer, size);
}
int posix_memalign(void** out, size_t alignment, size_t size) noexcept {
  if (g_counting) ++g_allocations, ++t_allocations;
  *out = __libc_memalign(alignment, size);
  return *out ? 0 : 12;  // ENOMEM
}
void* aligned_alloc(size_t alignment, size_t size) noexcept {
  if (g_counting) ++g_allocations, ++t_allocations;
  return __libc_memalign(alignment, size);
}
}
#endif
