#pragma once
// Storage aligned to cache lines, for arrays the traversals read in SIMD-sized pieces: node
// arrays (siblings the builder places at an even index share a line) and the leaves'
// structure-of-arrays (a batch load crosses as few lines as its offset allows). Arrays of a huge
// page or more get huge pages of their own (huge_pages.h), which cost a build far fewer page
// faults and a traversal fewer TLB misses.

#include "huge_pages.h"

#include <cstddef>
#include <new>

namespace accel {

/// Hands out cache-line (64-byte) aligned storage; huge pages from kHugePageBytes up.
template <class T>
struct CacheLineAllocator {
  using value_type = T;
  static constexpr std::align_val_t kAlign{64};
  CacheLineAllocator() = default;
  template <class U>
  CacheLineAllocator(const CacheLineAllocator<U>&) {}
  T* allocate(std::size_t n) {
    if (n > std::size_t(-1) / sizeof(T)) throw std::bad_array_new_length();
    const std::size_t bytes = n * sizeof(T);
    if (bytes >= kHugePageBytes) return static_cast<T*>(allocate_huge_pages(bytes));
    return static_cast<T*>(::operator new(bytes, kAlign));
  }
  void deallocate(T* p, std::size_t n) {
    const std::size_t bytes = n * sizeof(T);
    if (bytes >= kHugePageBytes) return free_huge_pages(p, bytes);
    ::operator delete(p, kAlign);
  }
  bool operator==(const CacheLineAllocator&) const = default;
};

}  // namespace accel
