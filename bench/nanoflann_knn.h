#pragma once
// nanoflann 1.4.3 (Debian libnanoflann-dev) over photon positions: the outside opinion in the
// kNN tests and the peer in bench_photon. nanoflann 1.4.3 has no radius-bounded kNN (rknnSearch
// arrived in 1.5.1), so the search gets a result set of our own in nanoflann's style, a sorted
// array filled by insertion like its KNNResultSet, whose worst distance starts at max_radius^2:
// nanoflann offers only points with d2 < worstDist(), which is the same "closer than
// max_radius" rule as photon::PhotonMap::gather. Ties at equal distance are kept in the order
// nanoflann offers them (it has no index tie-break), so callers compare distances, not indices,
// where photons tie.

#include "photon/photon.h"

#include <nanoflann.hpp>

#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <span>
#include <vector>

namespace bench_photon {

/// nanoflann's view of the photon positions.
struct PhotonCloud {
  std::span<const photon::Photon> photons;

  std::size_t kdtree_get_point_count() const { return photons.size(); }
  float kdtree_get_pt(std::uint32_t i, std::size_t dim) const {
    const photon::Vec3& p = photons[i].position;
    return dim == 0 ? p.x : (dim == 1 ? p.y : p.z);
  }
  template <class Box>
  bool kdtree_get_bbox(Box&) const {
    return false;
  }
};

/// The k nearest with d2 < max_radius^2, kept sorted by distance (insertion, as nanoflann's own
/// KNNResultSet does).
class RadiusKnnResultSet {
 public:
  using DistanceType = float;
  using IndexType = std::uint32_t;

  RadiusKnnResultSet(std::size_t k, float max_radius2, std::uint32_t* indices, float* dists)
      : indices_(indices), dists_(dists), capacity_(k), max_radius2_(max_radius2) {}

  std::size_t size() const { return count_; }
  bool full() const { return count_ == capacity_; }
  float worstDist() const { return full() ? dists_[capacity_ - 1] : max_radius2_; }

  /// Called by nanoflann for a point with d2 < worstDist(); always continues the search.
  bool addPoint(float d2, std::uint32_t index) {
    std::size_t i = count_;
    for (; i > 0 && dists_[i - 1] > d2; --i) {
      if (i < capacity_) {
        dists_[i] = dists_[i - 1];
        indices_[i] = indices_[i - 1];
      }
    }
    if (i < capacity_) {
      dists_[i] = d2;
      indices_[i] = index;
    }
    if (count_ < capacity_) ++count_;
    return true;
  }

 private:
  std::uint32_t* indices_;
  float* dists_;
  std::size_t capacity_;
  std::size_t count_ = 0;
  float max_radius2_;
};

/// A nanoflann kd-tree over photon positions.
class NanoflannPhotons {
 public:
  using Index = nanoflann::KDTreeSingleIndexAdaptor<
      nanoflann::L2_Simple_Adaptor<float, PhotonCloud, float, std::uint32_t>, PhotonCloud, 3,
      std::uint32_t>;

  /// Builds over `photons` (kept by reference) with nanoflann's leaf_max_size (its default 10).
  explicit NanoflannPhotons(std::span<const photon::Photon> photons, std::size_t leaf_max_size = 10)
      : cloud_{photons},
        index_(std::make_unique<Index>(3, cloud_,
                                       nanoflann::KDTreeSingleIndexAdaptorParams(leaf_max_size))) {}

  /// The k nearest photons closer than max_radius (+inf: unbounded), nearest first: fills
  /// indices and d2 (squared distances) and returns how many were found.
  std::size_t knn(const photon::Vec3& q, std::size_t k, float max_radius,
                  std::vector<std::uint32_t>& indices, std::vector<float>& d2) const {
    if (indices.size() < k) indices.resize(k);
    if (d2.size() < k) d2.resize(k);
    const float r2 = max_radius * max_radius;
    RadiusKnnResultSet result(k, std::isinf(r2) ? std::numeric_limits<float>::max() : r2,
                              indices.data(), d2.data());
    const float qv[3] = {q.x, q.y, q.z};
    index_->findNeighbors(result, qv, nanoflann::SearchParams());
    return result.size();
  }

  /// nanoflann's own unbounded kNN (its KNNResultSet), nearest first; returns how many were
  /// found (k, or all photons when there are fewer).
  std::size_t knn_unbounded(const photon::Vec3& q, std::size_t k, std::vector<std::uint32_t>& indices,
                            std::vector<float>& d2) const {
    if (indices.size() < k) indices.resize(k);
    if (d2.size() < k) d2.resize(k);
    const float qv[3] = {q.x, q.y, q.z};
    return index_->knnSearch(qv, k, indices.data(), d2.data());
  }

 private:
  PhotonCloud cloud_;
  std::unique_ptr<Index> index_;
};

}  // namespace bench_photon
