// Landmark RMSE where the estimated landmarks carry no ground-truth id (ACFR Car Park: surveyed beacons,
// unlabelled detections): estimated and surveyed landmarks are paired one-to-one by distance, then the
// RMSE of the pairs is reported with how many were paired.
#ifndef ARBOR_CORE_METRICS_LANDMARK_MATCHING_H_
#define ARBOR_CORE_METRICS_LANDMARK_MATCHING_H_

#include <optional>
#include <vector>

#include "core/types/landmark.h"
#include "core/types/scenario.h"

namespace arbor {

struct MatchedLandmarkError {
  double rmse_m = 0.0;
  int matched = 0;     // pairs within the gate
  int unmatched = 0;   // estimated landmarks left without a surveyed partner (spurious or duplicates)
  int missed = 0;      // surveyed landmarks left without an estimate
};

// Pairs greedily by increasing distance, each landmark at most once, only pairs closer than gate_m, after
// moving the estimate by alignment (e.g. the ATE's SE(2) alignment to GPS). Greedy on sorted distances is
// order-independent and, for well-separated landmarks, equals the optimal assignment.
std::optional<MatchedLandmarkError> matched_landmark_rmse(const std::vector<Landmark>& map,
                                                          const std::vector<TruthLandmark>& truth, double gate_m,
                                                          const Pose2& alignment = Pose2{});

}  // namespace arbor

#endif  // ARBOR_CORE_METRICS_LANDMARK_MATCHING_H_
