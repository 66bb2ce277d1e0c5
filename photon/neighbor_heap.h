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

#include <bit>
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
/// Cache: the heap keeps each photon's squared distance in its key (off: every comparison
/// recomputes it from the positions).
///
/// The heap orders 64-bit keys (bits of d2 << 32 | original index): d2 >= +0 is never NaN, so
/// its bits order as the floats do, and one integer comparison settles distance and tie alike,
/// without a branch for the tie. The storage slots move alongside the keys.
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
    if (out.slots_.size() < std::size_t(k)) {
      out.items_.resize(std::size_t(k));
      out.keys_.resize(std::size_t(k));
      out.slots_.resize(std::size_t(k));
    }
    keys_ = out.keys_.data();
    slots_ = out.slots_.data();
    bound2_ = std::nextafter(r2, 0.0f);
    if constexpr (Count) c_->lookups++;
  }

  GatherState(const GatherState&) = delete;
  GatherState& operator=(const GatherState&) = delete;

  /// Hands the photons found to the Neighbors (heap order, with their squared distances).
  void finish() {
    Neighbor* items = out_.items_.data();
    for (int i = 0; i < count_; ++i)
      items[i] = {std::bit_cast<float>(std::uint32_t(key_at(i) >> 32)), slots_[i]};
    out_.count_ = count_;
    if constexpr (Count) c_->photons_found += std::uint64_t(count_);
  }

  const Vec3& query() const { return q_; }
  /// Candidates must have d2 <= bound2() (world units squared).
  float bound2() const { return bound2_; }
  GatherCounters* counters() const { return c_; }
  /// Counts `n` photons whose distance the caller computed.
  void count_tested(std::uint32_t n) {
    if constexpr (Count) c_->photons_tested += n;
  }

  /// Counts one node entered.
  void count_node() {
    if constexpr (Count) c_->nodes_visited++;
  }

  /// Offers the photon in `slot`.
  void consider(std::uint32_t slot) {
    if constexpr (Count) c_->photons_tested++;
    offer(slot, distance2(q_, photons_[slot].position));
  }

  /// Offers the photon in `slot` whose squared distance the caller computed with distance2()'s
  /// operations (bucket_tree.h does eight at a time); the caller counts it as tested.
  void offer(std::uint32_t slot, float d2) {
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
  static std::uint64_t make_key(float d2, std::uint32_t id) {
    return std::uint64_t(std::bit_cast<std::uint32_t>(d2)) << 32 | id;
  }
  std::uint32_t id(std::uint32_t slot) const { return ids_ ? ids_[slot] : slot; }
  /// The key of heap entry i: kept (Cache) or recomputed from the photon.
  std::uint64_t key_at(int i) const {
    if constexpr (Cache) return keys_[i];
    const std::uint32_t slot = slots_[i];
    return make_key(distance2(q_, photons_[slot].position), id(slot));
  }
  /// Top-down sift. (Floyd's bottom-up replacement, hole to a leaf then the key up, measured
  /// 20 % more mispredicted branches here: a new key is close to the top's, so it rises far.)
  void sift_down(int i) {
    const std::uint64_t key = key_at(i);
    const std::uint32_t slot = slots_[i];
    for (;;) {
      int child = 2 * i + 1;
      if (child >= count_) break;
      std::uint64_t child_key = key_at(child);
      if (child + 1 < count_) {
        const std::uint64_t right = key_at(child + 1);
        const bool take_right = right > child_key;
        child += take_right;
        child_key = take_right ? right : child_key;
      }
      if (child_key <= key) break;
      if constexpr (Cache) keys_[i] = child_key;
      slots_[i] = slots_[child];
      i = child;
    }
    if constexpr (Cache) keys_[i] = key;
    slots_[i] = slot;
  }
  void insert(float d2, std::uint32_t slot) {
    const std::uint64_t key = make_key(d2, id(slot));
    if (count_ < k_) {
      if constexpr (Cache) keys_[count_] = key;
      slots_[count_++] = slot;
      if constexpr (Count) c_->heap_inserts++;
      if (count_ == k_) {
        for (int i = k_ / 2 - 1; i >= 0; --i) sift_down(i);
        bound2_ = std::bit_cast<float>(std::uint32_t(key_at(0) >> 32));
      }
      return;
    }
    // Full, and d2 <= the top's: at a tie the lower index wins, in the same comparison.
    if (key >= key_at(0)) return;
    if constexpr (Count) c_->heap_inserts++;
    if constexpr (Cache) keys_[0] = key;
    slots_[0] = slot;
    sift_down(0);
    bound2_ = std::bit_cast<float>(std::uint32_t(key_at(0) >> 32));
  }
  const Photon* photons_;
  const std::uint32_t* ids_;
  Vec3 q_, n_;
  int k_;
  int count_ = 0;
  std::uint64_t* keys_ = nullptr;
  std::uint32_t* slots_ = nullptr;
  float bound2_ = 0.0f;
  Neighbors& out_;
  GatherCounters* c_;
};

}  // namespace photon
