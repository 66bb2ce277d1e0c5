#pragma once
// The heart of every gather: the bounded max-heap of the k nearest photons and the acceptance
// test that every tree variant (and brute force) calls for each candidate photon.
//
// Exactness: a candidate is accepted when (d2, index) is smaller than the heap's top, or, while
// fewer than k are held, when d2 < max_radius^2. Both are one comparison `d2 <= bound2`, with
// bound2 the largest float below max_radius^2 while filling and the top's d2 once full (a tie
// with the top is then settled by index). Trees skip a subtree only when a lower bound of every
// squared distance in it, computed with the same float operations, exceeds bound2; float
// subtraction, squaring and the sum of non-negative terms are monotonic, so such a bound never
// exceeds a distance computed by distance2(), and no photon is missed.

#include "knn.h"
#include "photon.h"

#include <cmath>
#include <cstdint>
#include <limits>

namespace photon {

/// Squared distance from q to p, the one formula used by every variant: (q-p).x^2 +
/// (q-p).y^2 + (q-p).z^2, summed left to right.
inline float distance2(const Vec3& q, const Vec3& p) {
  const float dx = q.x - p.x, dy = q.y - p.y, dz = q.z - p.z;
  return dx * dx + dy * dy + dz * dz;
}

/// One gather in progress. Count: update counters; Cull: hemisphere test before the heap;
/// Cache: heap entries keep their squared distance (off: recomputed at every comparison).
template <bool Count, bool Cull, bool Cache>
class GatherState {
 public:
  /// `ids` maps a storage slot to the photon's original index (nullptr: the identity).
  GatherState(const Photon* photons, const std::uint32_t* ids, const Vec3& query,
              const Vec3& normal, int k, float max_radius, Neighbors& out,
              GatherCounters* counters)
      : photons_(photons), ids_(ids), q_(query), n_(normal), k_(k), out_(out), c_(counters) {
    const float r2 = max_radius * max_radius;
    out.k_ = k;
    out.count_ = 0;
    out.max_radius2_ = r2;
    out.sorted_ = false;
    if (out.items_.size() < std::size_t(k)) out.items_.resize(std::size_t(k));
    heap_ = out.items_.data();
    bound2_ = std::nextafter(r2, 0.0f);
    if constexpr (Count) c_->lookups++;
  }

  GatherState(const GatherState&) = delete;
  GatherState& operator=(const GatherState&) = delete;

  /// Hands the photons found to the Neighbors (with their squared distances).
  void finish() {
    if constexpr (!Cache) {
      for (int i = 0; i < count_; ++i) heap_[i].d2 = d2_of(heap_[i]);
    }
    out_.count_ = count_;
    if constexpr (Count) c_->photons_found += std::uint64_t(count_);
  }

  const Vec3& query() const { return q_; }
  /// Candidates must have d2 <= bound2() (world units squared).
  float bound2() const { return bound2_; }
  GatherCounters* counters() const { return c_; }

  /// Counts one node entered.
  void count_node() {
    if constexpr (Count) c_->nodes_visited++;
  }

  /// Offers the photon in `slot`.
  void consider(std::uint32_t slot) {
    if constexpr (Count) c_->photons_tested++;
    const float d2 = distance2(q_, photons_[slot].position);
    if (d2 > bound2_) return;
    if constexpr (Cull) {
      if (!photons_[slot].arrives_from_side_of(n_)) {
        if constexpr (Count) c_->photons_culled++;
        return;
      }
    }
    insert(d2, slot);
  }

 private:
  std::uint32_t id(std::uint32_t slot) const { return ids_ ? ids_[slot] : slot; }
  float d2_of(const Neighbor& e) const {
    if constexpr (Cache) return e.d2;
    return distance2(q_, photons_[e.slot].position);
  }
  /// (d2, id) of a strictly after b.
  bool after(const Neighbor& a, const Neighbor& b) const {
    const float da = d2_of(a), db = d2_of(b);
    return da > db || (da == db && id(a.slot) > id(b.slot));
  }
  void sift_down(int i) {
    const Neighbor e = heap_[i];
    for (;;) {
      int child = 2 * i + 1;
      if (child >= count_) break;
      if (child + 1 < count_ && after(heap_[child + 1], heap_[child])) ++child;
      if (!after(heap_[child], e)) break;
      heap_[i] = heap_[child];
      i = child;
    }
    heap_[i] = e;
  }
  void insert(float d2, std::uint32_t slot) {
    if (count_ < k_) {
      heap_[count_++] = {Cache ? d2 : 0.0f, slot};
      if constexpr (Count) c_->heap_inserts++;
      if (count_ == k_) {
        for (int i = k_ / 2 - 1; i >= 0; --i) sift_down(i);
        bound2_ = d2_of(heap_[0]);
      }
      return;
    }
    // Full: d2 <= top; at a tie the lower index wins.
    if (d2 == bound2_ && id(slot) > id(heap_[0].slot)) return;
    if constexpr (Count) c_->heap_inserts++;
    heap_[0] = {Cache ? d2 : 0.0f, slot};
    sift_down(0);
    bound2_ = d2_of(heap_[0]);
  }

  const Photon* photons_;
  const std::uint32_t* ids_;
  Vec3 q_, n_;
  int k_;
  int count_ = 0;
  Neighbor* heap_ = nullptr;
  float bound2_ = 0.0f;
  Neighbors& out_;
  GatherCounters* c_;
};

}  // namespace photon
