// Loop closing (FastSlamOptions::close_loops), a policy beside the engine: a young landmark found to be a
// drifted copy of an old, dormant one becomes its alias, and later measurements paired with the copy update
// the original. The engine holds it only when the option is on; off, no step runs any of it.
#ifndef ARBOR_CORE_ENGINE_LOOP_CLOSING_H_
#define ARBOR_CORE_ENGINE_LOOP_CLOSING_H_

#include <algorithm>
#include <cstdint>
#include <span>
#include <vector>

#include "core/engine/touched_landmark.h"
#include "core/math/eigen_types.h"
#include "core/math/ldlt_solve2.h"
#include "core/types/landmark.h"

namespace arbor {

// A young landmark found to be a drifted copy of an old, dormant one: a measurement paired with the copy
// updates the old landmark.
struct LandmarkAlias {
  LandmarkId copy = kNoLandmark;
  LandmarkId original = kNoLandmark;
};

// One particle's loop-closing bookkeeping for one scan (per-thread scratch).
struct LoopClosingScan {
  std::vector<LandmarkId> redirected;  // per measurement: the alias it was paired through, or kNoLandmark
  std::vector<LandmarkId> retired;     // aliases whose original this scan paired directly
};

class LoopClosing {
 public:
  // loop_drift_m: FastSlamOptions::loop_drift_m; gate: the association's chi-square gate (2 dof).
  LoopClosing(double loop_drift_m, double gate, int dormant_scans)
      : drift_(Vec3(loop_drift_m, loop_drift_m, 0.0).cwiseAbs2().asDiagonal()), gate_(gate), dormant_scans_(dormant_scans) {}

  // FastSlamOptions::loop_drift_m as a pose covariance (position only).
  const Mat3& drift() const { return drift_; }

  // Step 1: a measurement the association paired with an alias is paired with its original instead, whatever
  // the gate says, as known association would pair it. Once the association pairs the original itself, the
  // pose is back on the old map and the copy is retired. find(id) is the landmark the particle's map holds now
  // (or null). Without aliases s->redirected stays empty.
  template <class FindLandmark>
  void redirect(const std::vector<LandmarkAlias>& aliases, const FindLandmark& find, std::vector<LandmarkId>* decision,
                LoopClosingScan* s) const {
    s->redirected.clear();
    s->retired.clear();
    if (aliases.empty()) return;
    s->redirected.assign(decision->size(), kNoLandmark);
    for (const LandmarkAlias& a : aliases) {
      const auto end = decision->end();
      const auto copy = std::find(decision->begin(), end, a.copy);
      if (std::find(decision->begin(), end, a.original) != end) {
        if (copy == end) s->retired.push_back(a.copy);
        continue;
      }
      if (copy == end || find(a.original) == nullptr) continue;
      s->redirected[copy - decision->begin()] = a.copy;
      *copy = a.original;
    }
  }

  // Whether measurement k was paired through an alias. Its weight then allows the loop's drift
  // (FastSlamOptions::loop_drift_m), which the particle's covariance does not hold and which put the copy where
  // it is: weighted with the particle's covariance alone, the closing particles would lose to those that keep
  // the copy.
  static bool redirected(const LoopClosingScan& s, std::size_t k) {
    return k < s.redirected.size() && s.redirected[k] != kNoLandmark;
  }

  // An alias a measurement was paired through was seen too (the measurement updated its original instead):
  // no negative evidence against it.
  static bool seen_through_alias(const LoopClosingScan& s, LandmarkId id) {
    return std::find(s.redirected.begin(), s.redirected.end(), id) != s.redirected.end();
  }
  static bool retired(const LoopClosingScan& s, LandmarkId id) {
    return std::find(s.retired.begin(), s.retired.end(), id) != s.retired.end();
  }

  // Step 2: a landmark confirmed this scan is a copy of a dormant landmark when it lies inside the gate of
  // exactly that one, widened by the loop's drift; with two in the gate, one re-sighting cannot say which.
  // Why wait for the copy to be confirmed rather than pair the re-sighting itself: a widened gate takes in
  // clutter, and pairing at once took rooms with clutter 5 from 1.58 to 2.50 (JCBB / known ATE,
  // results/association/61e6ed5_vm_gcc-12.2.0); a landmark seen twice is no clutter. nearby: the landmarks
  // in the particle's query box before this scan's update.
  void find_aliases(std::span<const TouchedLandmark> touched, std::span<const Landmark> nearby, std::int32_t scan_index,
                    std::vector<LandmarkAlias>* aliases, std::int64_t* loop_closures) const {
    const auto aliased = [&](LandmarkId id) {
      for (const LandmarkAlias& a : *aliases)
        if (a.copy == id || a.original == id) return true;
      return false;
    };
    for (const TouchedLandmark& t : touched) {
      if (t.is_new || t.was_confirmed || !t.landmark.confirmed) continue;
      const Landmark& copy = t.landmark;
      const Landmark* original = nullptr;
      int matches = 0;
      for (const Landmark& lm : nearby) {
        if (!lm.confirmed || scan_index - lm.seen_scan < dormant_scans_ || touches(touched, lm.id) || aliased(lm.id))
          continue;
        const Vec2 d = copy.mean - lm.mean;
        const Mat2 C = copy.cov + lm.cov + drift_.topLeftCorner<2, 2>();
        if (d.dot(ldlt_solve2(C, d)) > gate_) continue;
        original = &lm;
        ++matches;
      }
      if (matches != 1) continue;
      aliases->push_back({copy.id, original->id});
      ++*loop_closures;
    }
  }

  // An alias whose copy or original left the map closes nothing any more.
  static void drop_aliases_of(std::vector<LandmarkAlias>* aliases, std::span<const LandmarkId> erased) {
    if (aliases->empty() || erased.empty()) return;
    std::erase_if(*aliases, [&](const LandmarkAlias& a) {
      return std::find(erased.begin(), erased.end(), a.copy) != erased.end() ||
             std::find(erased.begin(), erased.end(), a.original) != erased.end();
    });
  }

 private:
  Mat3 drift_;
  double gate_;
  int dormant_scans_;
};

}  // namespace arbor

#endif  // ARBOR_CORE_ENGINE_LOOP_CLOSING_H_
