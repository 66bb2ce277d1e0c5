// harness::pin_to_current_cpu leaves the calling thread, and the threads it starts afterwards,
// allowed on exactly the one CPU it returns. Run on a thread of its own, so that the test
// process's main thread stays free.

#include "harness/cpu_pinning.h"

#include <gtest/gtest.h>

#include <sched.h>

#include <thread>

namespace {

TEST(CpuPinning, KeepsTheThreadAndItsChildrenOnTheCpuItReturns) {
  int pinned = -2, allowed = 0, child_cpu = -2;
  bool allowed_is_pinned = false;
  std::thread t([&] {
    pinned = harness::pin_to_current_cpu();
    cpu_set_t set;
    CPU_ZERO(&set);
    ASSERT_EQ(sched_getaffinity(0, sizeof set, &set), 0);
    allowed = CPU_COUNT(&set);
    allowed_is_pinned = pinned >= 0 && CPU_ISSET(pinned, &set);
    std::thread child([&] { child_cpu = sched_getcpu(); });
    child.join();
  });
  t.join();
  ASSERT_GE(pinned, 0);
  EXPECT_EQ(allowed, 1);
  EXPECT_TRUE(allowed_is_pinned);
  EXPECT_EQ(child_cpu, pinned);
}

}  // namespace
