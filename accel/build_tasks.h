#pragma once
// What the BVH builders need to build on several threads and still write the same nodes at any
// thread count: a thread count resolved into a TBB arena, and node storage carved into slabs.
//
// A builder runs depth first. Where a range is large (kForkPrims or more primitives) its
// children's subtrees become tasks, and each task gets a slab of the node array big enough for any
// subtree of its size; it allocates from the slab's start as the one-thread build allocates from
// the array's end. Where a range forks depends only on its size, never on the threads, so every
// slab lies where it lies at one thread. compact() then closes the gaps between the slabs' used
// runs, in address order, which gives exactly the depth-first layout one thread would have
// written without slabs, and renumbers the child links.
//
// The slabs are an index space, not memory: a slab reserves its subtree's worst case (one node
// per primitive) and the tree uses about a tenth of it. The nodes live in chunks of kChunkNodes,
// handed out in the order they are first written from one arena on huge pages, so the memory
// written is dense. With a plain array behind the index space, every slab's run touched pages
// of its own: 4,500 page faults (4 KiB each) on a million triangles, and huge pages there would
// have made most of the worst case resident.

#include "cache_line_allocator.h"
#include "stats.h"

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <cassert>
#include <cstdint>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <vector>

namespace accel {

/// Ranges of at least this many primitives build their children as parallel tasks.
inline constexpr std::uint32_t kForkPrims = 1u << 12;

/// What a build task counts, merged into its parent's in the children's order once they are
/// done, so that the sums are the same at any thread count.
struct BuildTally {
  double sah = 0.0;  ///< Sum of the SAH terms (traversal cost 1, intersection cost 1), not normalised.
  std::uint64_t leaves = 0, max_leaf_prims = 0;
  int max_depth_reached = 0;
  void merge(const BuildTally& t) {
    sah += t.sah;
    leaves += t.leaves;
    max_leaf_prims = std::max(max_leaf_prims, t.max_leaf_prims);
    max_depth_reached = std::max(max_depth_reached, t.max_depth_reached);
  }
  /// Writes the counts into `stats`, the SAH cost normalised by the root's half-area; a flat or
  /// point-like root (area 0) costs its leaf tests, `primitives`.
  void write_to(BuildStats& stats, float root_area, std::uint64_t primitives) const {
    stats.leaves = leaves;
    stats.max_leaf_prims = max_leaf_prims;
    stats.max_depth_reached = max_depth_reached;
    stats.sah_cost = root_area > 0.0f ? sah / double(root_area) : double(primitives);
  }
};

/// Runs fn() in a TBB arena of `threads` threads (0 = every core); the parallel loops and tasks
/// it starts use at most that many.
template <class Fn>
void run_with_build_threads(int threads, Fn&& fn) {
  tbb::task_arena arena(threads > 0 ? threads : tbb::task_arena::automatic);
  arena.execute(fn);
}

/// A node array handed out in slabs, one per build task, compacted once the build is done.
template <class Node>
class NodeSlabs {
 public:
  /// Where a task allocates: [run_start, next) is its current run of written nodes, and it may
  /// allocate up to `end`.
  struct Cursor {
    std::uint32_t run_start = 0, next = 0, end = 0;
  };

  /// An index space of `capacity` nodes; memory is taken as nodes are written.
  explicit NodeSlabs(std::uint64_t capacity)
      : capacity_(capacity),
        chunk_count_((capacity + kChunkNodes - 1) / kChunkNodes),
        chunks_(std::make_unique<std::atomic<Node*>[]>(std::size_t(chunk_count_))),
        arena_nodes_(std::size_t(chunk_count_) * kChunkNodes),
        arena_(CacheLineAllocator<Node>().allocate(arena_nodes_)) {}
  ~NodeSlabs() { CacheLineAllocator<Node>().deallocate(arena_, arena_nodes_); }
  NodeSlabs(const NodeSlabs&) = delete;
  NodeSlabs& operator=(const NodeSlabs&) = delete;

  /// Node `i` of the index space; its chunk is taken from the arena when first touched.
  Node& operator[](std::uint32_t i) {
    std::atomic<Node*>& slot = chunks_[i / kChunkNodes];
    Node* chunk = slot.load(std::memory_order_acquire);
    if (chunk == nullptr) chunk = take_chunk(slot);
    return chunk[i % kChunkNodes];
  }

  /// A builder that passes its slab would write over another task's nodes: a bug in the
  /// builder's bounds, stopped here rather than left to corrupt the tree (a compare per slab).
  static void check(const Cursor& c) {
    if (c.next > c.end) throw std::logic_error("tree builder: a task outgrew its node slab");
  }

  /// The slab of the whole array.
  Cursor whole() const { return {0, 0, std::uint32_t(capacity_)}; }

  /// `count` consecutive nodes from the cursor's slab; returns the first.
  std::uint32_t allocate(Cursor& c, std::uint32_t count) {
    const std::uint32_t first = c.next;
    c.next += count;
    check(c);
    return first;
  }

  /// Ends the cursor's current run: call before carving slabs out of it, and when its task ends.
  void close_run(Cursor& c) {
    if (c.next > c.run_start) {
      std::lock_guard<std::mutex> lock(mutex_);
      runs_.push_back({c.run_start, c.next - c.run_start, 0});
    }
    c.run_start = c.next;
  }

  /// A slab of `capacity` nodes taken from the cursor's room, which then resumes after it.
  Cursor carve(Cursor& c, std::uint32_t capacity) {
    Cursor slab{c.next, c.next, c.next + capacity};
    c.next += capacity;
    c.run_start = c.next;
    check(c);
    return slab;
  }

  /// Copies the runs, in address order, into `out` (resized to fit), then calls
  /// relink(node, renumber) on every node, where renumber(old index) gives a node's new index.
  template <class Out, class Relink>
  void compact(Out& out, Relink&& relink) {
    std::sort(runs_.begin(), runs_.end(), [](const Run& a, const Run& b) { return a.start < b.start; });
    std::uint32_t total = 0;
    for (Run& r : runs_) {
      r.new_start = total;
      total += r.length;
    }
    out.resize(total);
    const auto renumber = [&](std::uint32_t old) {
      const auto it = std::upper_bound(runs_.begin(), runs_.end(), old,
                                       [](std::uint32_t v, const Run& r) { return v < r.start; });
      const Run& r = *(it - 1);
      return r.new_start + (old - r.start);
    };
    tbb::parallel_for(std::size_t(0), runs_.size(), [&](std::size_t i) {
      const Run& r = runs_[i];
      for (std::uint32_t k = 0; k < r.length; ++k) {
        Node& n = out[r.new_start + k];
        n = (*this)[r.start + k];
        relink(n, renumber);
      }
    });
  }

 private:
  struct Run {
    std::uint32_t start, length, new_start;
  };

  /// Nodes per chunk: 16 KiB of 8-wide nodes, so a short run wastes little of its last chunk.
  static constexpr std::uint32_t kChunkNodes = 64;

  Node* take_chunk(std::atomic<Node*>& slot) {
    std::lock_guard<std::mutex> lock(chunk_mutex_);
    Node* chunk = slot.load(std::memory_order_relaxed);
    if (chunk == nullptr) {
      // Never past the arena: every slot takes at most one chunk.
      chunk = arena_ + std::size_t(chunks_taken_++) * kChunkNodes;
      slot.store(chunk, std::memory_order_release);
    }
    return chunk;
  }

  std::uint64_t capacity_;
  std::uint64_t chunk_count_;
  std::unique_ptr<std::atomic<Node*>[]> chunks_;  ///< Per chunk of the index space: its memory, or null.
  std::size_t arena_nodes_;  ///< One chunk per slot, on huge pages from kHugePageBytes up.
  Node* arena_;
  std::uint64_t chunks_taken_ = 0;
  std::mutex chunk_mutex_;
  std::mutex mutex_;
  std::vector<Run> runs_;
};

}  // namespace accel
