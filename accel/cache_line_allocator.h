#pragma once
// Storage aligned to cache lines, for arrays the traversals read in SIMD-sized pieces: node
// arrays (siblings the builder places at an even index share a line) and the leaves'
// structure-of-arrays (a batch load crosses as few lines as its offset allows).

#include <cstddef>
#include <new>

namespace accel {

/// Hands out cache-line (64-byte) aligned storage.
template <class T>
struct CacheLineAllocator {
  using value_type = T;
  static constexpr std::align_val_t kAlign{64};
  CacheLineAllocator() = default;
  template <class U>
  CacheLineAllocator(const CacheLineAllocator<U>&) {}
  T* allocate(std::size_t n) { return static_cast<T*>(::operator new(n * sizeof(T), kAlign)); }
  void deallocate(T* p, std::size_t) { ::operator delete(p, kAlign); }
  bool operator==(const CacheLineAllocator&) const = default;
};

}  // namespace accel
