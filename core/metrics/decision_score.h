// Scores a particle's recorded association decisions against the scenario's ground-truth ids, outside the
// engine: the filter never reads ground truth to judge itself (DESIGN.md §7).
#ifndef ARBOR_CORE_METRICS_DECISION_SCORE_H_
#define ARBOR_CORE_METRICS_DECISION_SCORE_H_

#include <vector>

#include "core/engine/persistent_history.h"
#include "core/io/scenario.h"
#include "core/metrics/association_score.h"

namespace arbor {

// Replays the lineage's decisions (oldest first) to rebuild which landmarks its map held at each scan and
// which true landmark each was started from (the truth id of the measurement that created it, or none for
// clutter). Then, per measurement with a known truth id, the counts of core/metrics/association_score.h,
// where "a landmark of the same true landmark was a candidate" reads "the map held one when the scan began".
// That is wider than the engine's candidate view: a landmark the estimate has carried out of view is still a
// missed match, since the map should have found it.
AssociationCounts score_decisions(const std::vector<StepDecisions>& decisions, const Scenario& scenario);

}  // namespace arbor

#endif  // ARBOR_CORE_METRICS_DECISION_SCORE_H_
