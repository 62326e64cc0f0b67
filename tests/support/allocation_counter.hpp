#pragma once
// Counts every allocation through the global operator new in a test binary, to prove that
// real-time code allocates nothing. Replacement allocation functions may not be inline, so this
// header defines them: include it in exactly one source file of a test binary.

#include <cstdlib>
#include <new>

#include "allocation_count.hpp"

// These replace the global allocation functions (malloc underneath), so free() is the right
// partner; GCC cannot see that and warns in some builds.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
void* operator new(std::size_t size) {
  avar::testing::allocations.fetch_add(1, std::memory_order_relaxed);
  ++avar::testing::thread_allocations;
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}
// std::stable_sort's buffer comes from the nothrow form: replaced too, or a sanitizer's own
// nothrow new would be paired with the free() below (alloc-dealloc-mismatch).
void* operator new(std::size_t size, const std::nothrow_t&) noexcept {
  avar::testing::allocations.fetch_add(1, std::memory_order_relaxed);
  ++avar::testing::thread_allocations;
  return std::malloc(size == 0 ? 1 : size);
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete(void* p, const std::nothrow_t&) noexcept { std::free(p); }
#pragma GCC diagnostic pop
