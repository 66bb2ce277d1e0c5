#pragma once
// Large arrays on transparent huge pages.
//
// A build writes its arrays (the SAH's copy of the boxes, the nodes, the leaves' rows) into
// fresh memory, and every first touch of a 4 KiB page is a page fault. On a million triangles
// those faults were a third of the build's time on a VM, where each fault also goes through the
// hypervisor (docs/meshes.md, "Huge pages"). Hosts whose transparent huge pages are set to
// `madvise` (Debian's default) back memory with 2 MiB pages only where asked, as Embree asks for
// its own. An array given these pages faults once per 2 MiB, and its traversal misses the TLB
// less.
//
// The mapping is the array's own, so freeing it returns the memory to the system at once.

#include <cstddef>

namespace accel {

/// Allocations at least this large get huge pages (one huge page, x86-64).
inline constexpr std::size_t kHugePageBytes = std::size_t(1) << 21;

/// `bytes` of memory aligned to kHugePageBytes, advised to the kernel as huge pages (where
/// the kernel has them; elsewhere plain pages). Throws std::bad_alloc when the system has no room.
void* allocate_huge_pages(std::size_t bytes);

/// Frees what allocate_huge_pages(bytes) returned, given the same `bytes`.
void free_huge_pages(void* p, std::size_t bytes) noexcept;

}  // namespace accel
