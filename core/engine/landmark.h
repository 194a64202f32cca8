// One landmark of one particle's map: a 2x2 EKF (mean, covariance), its existence evidence, an optional
// signature, and its locality (the landmarks seen in the same scan at least once; Ge & Lewis 2006, ch. 9).
#ifndef ARBOR_CORE_ENGINE_LANDMARK_H_
#define ARBOR_CORE_ENGINE_LANDMARK_H_

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>

#include "core/math/eigen_types.h"

namespace arbor {

// Landmark ids are assigned by the engine from a per-particle serial in creation order, the same way whatever
// the map back end, so every back end sees the same ids and does the same arithmetic in the same order.
using LandmarkId = std::int32_t;
inline constexpr LandmarkId kNoLandmark = -1;

// Covisibility set: sorted ids, capped at kCapacity. A full set keeps its lowest ids (deterministic).
class LocalitySet {
 public:
  static constexpr int kCapacity = 6;

  int size() const { return count_; }
  LandmarkId operator[](int i) const { return ids_[i]; }
  const LandmarkId* begin() const { return ids_.data(); }
  const LandmarkId* end() const { return ids_.data() + count_; }
  bool contains(LandmarkId id) const { return std::binary_search(begin(), end(), id); }

  // Inserts id in order; when full, a larger id than all kept ones is dropped, else the largest is evicted.
  void add(LandmarkId id) {
    LandmarkId* pos = std::lower_bound(ids_.data(), ids_.data() + count_, id);
    if (pos != ids_.data() + count_ && *pos == id) return;
    if (count_ == kCapacity) {
      if (pos == ids_.data() + count_) return;
      --count_;
    }
    std::copy_backward(pos, ids_.data() + count_, ids_.data() + count_ + 1);
    *pos = id;
    ++count_;
  }
  void remove(LandmarkId id) {
    LandmarkId* pos = std::lower_bound(ids_.data(), ids_.data() + count_, id);
    if (pos == ids_.data() + count_ || *pos != id) return;
    std::copy(pos + 1, ids_.data() + count_, pos);
    --count_;
  }
  bool operator==(const LocalitySet& o) const { return std::equal(begin(), end(), o.begin(), o.end()); }

 private:
  std::array<LandmarkId, kCapacity> ids_{};
  std::int32_t count_ = 0;
};

struct Landmark {
  Vec2 mean = Vec2::Zero();
  Mat2 cov = Mat2::Identity();
  LandmarkId id = kNoLandmark;
  // Existence evidence in log-odds: raised when seen, lowered when predicted in view and missed.
  float log_odds = 0.0f;
  // A landmark starts provisional and is confirmed, for good, once its log-odds reach the confirmation
  // level; only confirmed landmarks are the filter's map (FastSlamOptions::log_odds_confirm).
  bool confirmed = false;
  // The scan (counted from 0) that started it: a provisional landmark not confirmed within a few scans is
  // dropped (FastSlamOptions::provisional_scans).
  std::int32_t born_scan = 0;
  // Scalar signature (tree diameter in Victoria Park); NaN when the sensor gives none.
  float signature = std::numeric_limits<float>::quiet_NaN();
  // Ground-truth id of the measurement that created the landmark (-1: clutter or unknown). Bookkeeping for
  // the association metrics only: no association decision ever reads it.
  std::int32_t truth_label = -1;
  LocalitySet locality;

  bool operator==(const Landmark& o) const {
    return id == o.id && mean == o.mean && cov == o.cov && log_odds == o.log_odds && confirmed == o.confirmed &&
           born_scan == o.born_scan &&
           (signature == o.signature || (std::isnan(signature) && std::isnan(o.signature))) &&
           truth_label == o.truth_label && locality == o.locality;
  }
};

// Axis-aligned box in world coordinates [m], for spatial queries.
struct Box2 {
  Vec2 min;
  Vec2 max;
  bool contains(const Vec2& p) const {
    return p.x() >= min.x() && p.x() <= max.x() && p.y() >= min.y() && p.y() <= max.y();
  }
  bool intersects(const Box2& o) const {
    return min.x() <= o.max.x() && o.min.x() <= max.x() && min.y() <= o.max.y() && o.min.y() <= max.y();
  }
};

}  // namespace arbor

#endif  // ARBOR_CORE_ENGINE_LANDMARK_H_
