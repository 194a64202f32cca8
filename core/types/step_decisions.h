// The record of one scan's association decisions, as the engine writes it and the metrics replay it.
#ifndef ARBOR_CORE_TYPES_STEP_DECISIONS_H_
#define ARBOR_CORE_TYPES_STEP_DECISIONS_H_

#include <cstdint>
#include <vector>

#include <tbb/scalable_allocator.h>

#include "core/types/landmark.h"

namespace arbor {

// One scan's association decisions as the particle applied them: per measurement the landmark it updated
// or created, or kNoLandmark where the measurement was judged spurious (clutter); and the landmarks the
// scan's negative evidence removed. Replayed, the record tells which landmarks the map held at every scan,
// which is what scoring the decisions outside the filter needs (core/metrics/decision_score.h).
//
// Every particle records one per scan on its own thread, and resampling frees them on another: tbbmalloc's
// per-thread bins, as for the map and history nodes (core/memory/node_pool.h), where the global heap's locks
// cost 2 % of a Victoria Park run.
struct StepDecisions {
  using Ids = std::vector<LandmarkId, tbb::scalable_allocator<LandmarkId>>;
  std::int64_t step = 0;
  Ids landmarks;
  Ids erased;
};

}  // namespace arbor

#endif  // ARBOR_CORE_TYPES_STEP_DECISIONS_H_
