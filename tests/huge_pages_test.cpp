// Huge-page storage for large arrays (accel/huge_pages.h) and the allocator that hands it out
// (accel/cache_line_allocator.h): alignment, contents through growth, and the kernel's advice.

#include "accel/cache_line_allocator.h"
#include "accel/huge_pages.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace {

using accel::kHugePageBytes;

TEST(HugePages, AlignedWritableAndZeroed) {
  for (const std::size_t bytes : {kHugePageBytes, kHugePageBytes + 1, 5 * kHugePageBytes - 4096}) {
    auto* p = static_cast<unsigned char*>(accel::allocate_huge_pages(bytes));
    ASSERT_NE(p, nullptr);
    EXPECT_EQ(reinterpret_cast<std::uintptr_t>(p) % kHugePageBytes, 0u) << bytes;
    // Fresh anonymous memory reads as zero; the last byte is inside the mapping.
    EXPECT_EQ(p[0], 0);
    EXPECT_EQ(p[bytes - 1], 0);
    for (std::size_t i = 0; i < bytes; i += 4096) p[i] = static_cast<unsigned char>(i >> 12);
    for (std::size_t i = 0; i < bytes; i += 4096) ASSERT_EQ(p[i], static_cast<unsigned char>(i >> 12));
    p[bytes - 1] = 7;
    EXPECT_EQ(p[bytes - 1], 7);
    accel::free_huge_pages(p, bytes);
  }
  accel::free_huge_pages(nullptr, kHugePageBytes);  // a no-op, as delete of null is
}

// A vector that grows from small storage across the threshold and back keeps every element and
// its 64-byte alignment, whichever storage holds it.
TEST(HugePages, VectorKeepsItsContentsAcrossTheThreshold) {
  std::vector<std::uint32_t, accel::CacheLineAllocator<std::uint32_t>> v;
  const std::uint32_t n = 3 * kHugePageBytes / sizeof(std::uint32_t);
  for (std::uint32_t i = 0; i < n; ++i) {
    v.push_back(i * 2654435761u);
    if ((i & (i - 1)) == 0) {
      ASSERT_EQ(reinterpret_cast<std::uintptr_t>(v.data()) % 64, 0u) << i;
    }
  }
  for (std::uint32_t i = 0; i < n; ++i) ASSERT_EQ(v[i], i * 2654435761u);
  EXPECT_EQ(reinterpret_cast<std::uintptr_t>(v.data()) % kHugePageBytes, 0u);
  v.resize(100);
  v.shrink_to_fit();  // back to small storage
  EXPECT_EQ(reinterpret_cast<std::uintptr_t>(v.data()) % 64, 0u);
  for (std::uint32_t i = 0; i < 100; ++i) ASSERT_EQ(v[i], i * 2654435761u);
}

#if defined(__linux__)
/// The kernel's transparent huge page mode: "always", "madvise" or "never" (or "" if unknown).
std::string thp_mode() {
  std::ifstream in("/sys/kernel/mm/transparent_hugepage/enabled");
  std::string line;
  std::getline(in, line);
  const auto open = line.find('['), close = line.find(']');
  return open == std::string::npos || close == std::string::npos ? "" : line.substr(open + 1, close - open - 1);
}

/// The "THPeligible" value /proc/self/smaps gives the mapping that holds `address`, or -1.
int thp_eligible(const void* address) {
  std::ifstream in("/proc/self/smaps");
  const auto a = reinterpret_cast<std::uintptr_t>(address);
  bool inside = false;
  for (std::string line; std::getline(in, line);) {
    unsigned long long lo = 0, hi = 0;
    if (std::sscanf(line.c_str(), "%llx-%llx ", &lo, &hi) == 2 && line.find(':') > line.find(' ')) {
      inside = a >= lo && a < hi;
      continue;
    }
    int value = -1;
    if (inside && std::sscanf(line.c_str(), "THPeligible: %d", &value) == 1) return value;
  }
  return -1;
}

// The advice reaches the kernel: where the kernel gives huge pages on request, the array's
// mapping is eligible for them. (Whether the kernel then finds free huge pages is its business.)
TEST(HugePages, TheKernelIsAskedForHugePages) {
  const std::string mode = thp_mode();
  if (mode != "always" && mode != "madvise") GTEST_SKIP() << "transparent huge pages are '" << mode << "' here";
  const std::size_t bytes = 4 * kHugePageBytes;
  void* p = accel::allocate_huge_pages(bytes);
  static_cast<volatile char*>(p)[0] = 1;
  const int eligible = thp_eligible(p);
  accel::free_huge_pages(p, bytes);
  if (eligible < 0) GTEST_SKIP() << "this kernel's smaps has no THPeligible line";
  EXPECT_EQ(eligible, 1);
}
#endif

}  // namespace
