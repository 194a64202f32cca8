// Landmark existence evidence in log-odds (FastSlamOptions::log_odds_*; Montemerlo et al. 2003, §4): a
// pairing raises it; a landmark predicted well inside the view and not paired loses some, and below the prune
// level it is dropped; a provisional landmark that outlives its window unconfirmed is dropped too.
#ifndef ARBOR_CORE_ENGINE_EXISTENCE_H_
#define ARBOR_CORE_ENGINE_EXISTENCE_H_

#include <algorithm>
#include <cstdint>
#include <span>
#include <vector>

#include "core/engine/fastslam_options.h"
#include "core/engine/loop_closing.h"
#include "core/engine/map_concept.h"
#include "core/engine/sensor_view.h"
#include "core/engine/touched_landmark.h"
#include "core/math/pose2.h"
#include "core/models/range_bearing_model.h"
#include "core/types/landmark.h"

namespace arbor {

class ExistenceEvidence {
 public:
  // prune: whether evidence may drop a landmark (not with known association, whose ids say what exists,
  // unless FastSlamOptions::prune_with_known_association).
  ExistenceEvidence(const FastSlamOptions& options, bool prune)
      : initial_(options.log_odds_initial), hit_(options.log_odds_hit), miss_(options.log_odds_miss),
        max_(options.log_odds_max), prune_level_(options.log_odds_prune), confirm_(options.log_odds_confirm),
        provisional_scans_(options.provisional_scans), prune_(prune) {}

  // A landmark started at this scan: provisional unless the initial evidence already confirms it.
  void start(Landmark* lm, std::int32_t scan_index) const {
    lm->log_odds = static_cast<float>(initial_);
    lm->confirmed = lm->log_odds >= confirm_;
    lm->born_scan = lm->seen_scan = scan_index;
  }

  // A landmark paired at this scan; once confirmed, it stays confirmed.
  void seen(Landmark* lm, std::int32_t scan_index) const {
    lm->log_odds = static_cast<float>(std::min<double>(max_, lm->log_odds + hit_));
    lm->confirmed |= lm->log_odds >= confirm_;
    lm->seen_scan = scan_index;
  }

  // Negative evidence: the landmarks in nearby (gathered at this scan, before its update) that the scan did not
  // touch lose evidence where pose predicts them well inside the view, and are dropped from *map below the
  // prune level or when expired; *erased lists the dropped ones, so the decisions can be replayed. Loop
  // closing (when on) exempts an alias a measurement was paired through and drops a retired one.
  template <LandmarkMap Map>
  void miss_unseen(std::span<const Landmark> nearby, std::span<const TouchedLandmark> touched, const Pose2& pose,
                   std::int32_t scan_index, const SensorView& view, const LoopClosingScan* loops, Map* map,
                   std::vector<LandmarkId>* erased) const {
    erased->clear();
    const BearingBound bearing_bound(pose, view.evidence_cos_bound());
    for (const Landmark& lm : nearby) {
      if (touches(touched, lm.id)) continue;
      const auto drop = [&] {
        map->erase(lm.id);
        erased->push_back(lm.id);
      };
      if (loops) {
        if (LoopClosing::seen_through_alias(*loops, lm.id)) continue;
        if (LoopClosing::retired(*loops, lm.id)) {
          drop();
          continue;
        }
      }
      if (prune_ && expired(lm, scan_index)) {
        drop();
        continue;
      }
      const double range_m = predicted_range(pose, lm.mean);
      if (!view.in_evidence_range(range_m)) continue;  // most of the box: no atan2
      if (bearing_bound.certainly_beyond(lm.mean, range_m)) continue;  // behind the sensor: no atan2 either
      if (!view.in_evidence_view(range_bearing_predict(pose, lm.mean))) continue;
      Landmark updated = lm;
      updated.log_odds = static_cast<float>(lm.log_odds - miss_);
      if (prune_ && updated.log_odds < prune_level_) drop();
      else map->set(updated);
    }
  }

 private:
  bool expired(const Landmark& lm, std::int32_t scan_index) const {
    return !lm.confirmed && provisional_scans_ > 0 && scan_index - lm.born_scan >= provisional_scans_;
  }

  double initial_, hit_, miss_, max_, prune_level_, confirm_;
  int provisional_scans_;
  bool prune_;
};

}  // namespace arbor

#endif  // ARBOR_CORE_ENGINE_EXISTENCE_H_
