// The record of one scan's association decisions, as the engine writes it and the metrics replay it.
#ifndef ARBOR_CORE_TYPES_STEP_DECISIONS_H_
#define ARBOR_CORE_TYPES_STEP_DECISIONS_H_

#include <cstdint>
#include <vector>

#include "core/types/landmark.h"

namespace arbor {

// One scan's association decisions as the particle applied them: per measurement the landmark it updated
// or created, or kNoLandmark where the measurement was judged spurious (clutter); and the landmarks the
// scan's negative evidence removed. Replayed, the record tells which landmarks the map held at every scan,
// which is what scoring the decisions outside the filter needs (core/metrics/decision_score.h).
struct StepDecisions {
  std::int64_t step = 0;
  std::vector<LandmarkId> landmarks;
  std::vector<LandmarkId> erased;
};

}  // namespace arbor

#endif  // ARBOR_CORE_TYPES_STEP_DECISIONS_H_
