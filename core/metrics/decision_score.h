// Scores a particle's recorded association decisions against the scenario's ground-truth ids, outside the
// engine: the filter never reads ground truth to judge itself (DESIGN.md §7).
#ifndef ARBOR_CORE_METRICS_DECISION_SCORE_H_
#define ARBOR_CORE_METRICS_DECISION_SCORE_H_

#include <cstdint>
#include <vector>

#include "core/types/step_decisions.h"
#include "core/types/scenario.h"
#include "core/metrics/association_score.h"

namespace arbor {

// Replays the lineage's decisions (oldest first) to rebuild which landmarks its map held at each scan and
// which true landmark each was started from (the truth id of the measurement that created it, or none for
// clutter). Then, per measurement with a known truth id, the counts of core/metrics/association_score.h,
// where "a landmark of the same true landmark was a candidate" reads "the map held one when the scan began".
// That is wider than the engine's candidate view: a landmark the estimate has carried out of view is still a
// missed match, since the map should have found it.
AssociationCounts score_decisions(const std::vector<StepDecisions>& decisions, const Scenario& scenario);

// Landmarks of the map without a true counterpart of their own: those started from clutter, and every
// landmark beyond the first started from the same true landmark (a duplicate). Reads Landmark::truth_label,
// so it means something only where the measurements carry truth ids.
std::int64_t spurious_landmarks(const std::vector<Landmark>& map);

// True landmarks the scenario's measurements observe at least once (distinct truth ids): what a perfect map
// of this run would hold, where the world's count includes landmarks never in view.
std::int64_t observed_true_landmarks(const Scenario& scenario);

}  // namespace arbor

#endif  // ARBOR_CORE_METRICS_DECISION_SCORE_H_
