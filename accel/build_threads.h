#pragma once
// The knob that sets how many threads a build may use, shared by every structure with a parallel
// build: the BVHs (build_tasks.h) and Embree's peers, whose TBB builder takes the same count.

namespace accel {

inline constexpr const char* kBuildThreadsKnob = "build_threads";

}  // namespace accel
