// One landmark of one particle's map: a 2x2 EKF (mean, covariance), its existence evidence, an optional
// signature, and its locality (the landmarks seen in the same scan most often; Ge & Lewis 2006, ch. 9).
#ifndef ARBOR_CORE_TYPES_LANDMARK_H_
#define ARBOR_CORE_TYPES_LANDMARK_H_

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

// Covisibility set: the landmarks seen in the same scan as this one most often, at most kCapacity of them,
// kept with the Space-Saving summary (Metwally, Agrawal & El Abbadi, ICDT 2005) so that the set keeps
// learning: a co-observation of a kept id raises its count; a new id takes a free slot, or else replaces the
// kept id with the lowest count (ties: the highest id) and inherits that count plus one. Any id co-observed
// more often than the lowest kept count stays in the set. Counts are 8-bit and halved together when one
// would overflow, which keeps their order (an exponential forgetting of old co-observations). Ids stay sorted
// so that the set, and everything built from it, is deterministic.
class LocalitySet {
 public:
  static constexpr int kCapacity = 6;

  int size() const { return count_; }
  LandmarkId operator[](int i) const { return ids_[i]; }
  const LandmarkId* begin() const { return ids_.data(); }
  const LandmarkId* end() const { return ids_.data() + count_; }
  bool contains(LandmarkId id) const { return std::binary_search(begin(), end(), id); }
  // Co-observations counted for the id at position i (Space-Saving's estimate: an upper bound).
  int weight(int i) const { return hits_[i]; }

  // One co-observation of id.
  void add(LandmarkId id) {
    LandmarkId* pos = std::lower_bound(ids_.data(), ids_.data() + count_, id);
    const int at = static_cast<int>(pos - ids_.data());
    if (at < count_ && *pos == id) {
      raise(at);
      return;
    }
    std::uint8_t inherited = 0;
    if (count_ == kCapacity) {
      int weakest = 0;
      for (int i = 1; i < count_; ++i)
        if (hits_[i] <= hits_[weakest]) weakest = i;  // ties: the highest id (the last in order)
      inherited = hits_[weakest];
      erase_at(weakest);
      pos = std::lower_bound(ids_.data(), ids_.data() + count_, id);
    }
    insert_at(static_cast<int>(pos - ids_.data()), id, inherited);
    raise(static_cast<int>(pos - ids_.data()));
  }
  void remove(LandmarkId id) {
    const LandmarkId* pos = std::lower_bound(begin(), end(), id);
    if (pos != end() && *pos == id) erase_at(static_cast<int>(pos - begin()));
  }
  bool operator==(const LocalitySet& o) const {
    return count_ == o.count_ && std::equal(begin(), end(), o.begin()) &&
           std::equal(hits_.begin(), hits_.begin() + count_, o.hits_.begin());
  }

 private:
  void raise(int i) {
    if (hits_[i] == 255)
      for (int k = 0; k < count_; ++k) hits_[k] = static_cast<std::uint8_t>((hits_[k] + 1) / 2);
    ++hits_[i];
  }
  void insert_at(int i, LandmarkId id, std::uint8_t hits) {
    for (int k = count_; k > i; --k) {
      ids_[k] = ids_[k - 1];
      hits_[k] = hits_[k - 1];
    }
    ids_[i] = id;
    hits_[i] = hits;
    ++count_;
  }
  void erase_at(int i) {
    for (int k = i; k + 1 < count_; ++k) {
      ids_[k] = ids_[k + 1];
      hits_[k] = hits_[k + 1];
    }
    --count_;
  }

  std::array<LandmarkId, kCapacity> ids_{};
  std::array<std::uint8_t, kCapacity> hits_{};
  std::uint8_t count_ = 0;
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
  // The last scan that paired it (or started it): a landmark unseen for long is dormant, and after a loop its
  // re-sighting may fall outside every gate (FastSlamOptions::close_loops). It fills padding that the
  // persistent back ends' reference count leaves free: a leaf stays 112 bytes.
  std::int32_t seen_scan = 0;
  // Scalar signature (tree diameter in Victoria Park); NaN when the sensor gives none.
  float signature = std::numeric_limits<float>::quiet_NaN();
  // Ground-truth id of the measurement that created the landmark (-1: clutter or unknown). Bookkeeping for
  // the association metrics only: no association decision ever reads it.
  std::int32_t truth_label = -1;
  LocalitySet locality;

  bool operator==(const Landmark& o) const {
    return id == o.id && mean == o.mean && cov == o.cov && log_odds == o.log_odds && confirmed == o.confirmed &&
           born_scan == o.born_scan && seen_scan == o.seen_scan &&
           (signature == o.signature || (std::isnan(signature) && std::isnan(o.signature))) &&
           truth_label == o.truth_label && locality == o.locality;
  }
};

}  // namespace arbor

#endif  // ARBOR_CORE_TYPES_LANDMARK_H_
