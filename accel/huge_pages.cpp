#include "huge_pages.h"

#include <cstdint>
#include <new>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace accel {

namespace {

std::size_t round_up(std::size_t bytes) { return (bytes + kHugePageBytes - 1) & ~(kHugePageBytes - 1); }

}  // namespace

#if defined(__linux__)

void* allocate_huge_pages(std::size_t bytes) {
  const std::size_t length = round_up(bytes);
  if (length < bytes) throw std::bad_alloc();
  // mmap aligns to 4 KiB only: map one huge page more, then unmap what lies before the first
  // 2 MiB boundary and after the array. A huge page is used only where the whole 2 MiB lies in
  // the mapping, so without the alignment up to two of the array's pages would be small ones.
  const std::size_t padded = length + kHugePageBytes;
  void* mapped = mmap(nullptr, padded, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  if (mapped == MAP_FAILED) throw std::bad_alloc();
  const auto start = reinterpret_cast<std::uintptr_t>(mapped);
  const std::uintptr_t aligned = round_up(start);
  if (aligned > start) munmap(mapped, aligned - start);
  const std::uintptr_t tail = aligned + length, end = start + padded;
  if (end > tail) munmap(reinterpret_cast<void*>(tail), end - tail);
  // Only advice: a kernel without transparent huge pages (or with them off) refuses it, and the
  // array then lives on small pages, as it would have anyway.
  madvise(reinterpret_cast<void*>(aligned), length, MADV_HUGEPAGE);
  return reinterpret_cast<void*>(aligned);
}

void free_huge_pages(void* p, std::size_t bytes) noexcept {
  if (p != nullptr) munmap(p, round_up(bytes));
}

#else

// Without mmap and madvise: plain aligned storage.
void* allocate_huge_pages(std::size_t bytes) { return ::operator new(round_up(bytes), std::align_val_t{kHugePageBytes}); }

void free_huge_pages(void* p, std::size_t) noexcept { ::operator delete(p, std::align_val_t{kHugePageBytes}); }

#endif

}  // namespace accel
