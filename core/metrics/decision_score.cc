// Association decisions scored from the record, not inside the filter.
#include "core/metrics/decision_score.h"

#include <unordered_map>
#include <unordered_set>
#include <utility>

#include "core/check.h"

namespace arbor {

AssociationCounts score_decisions(const std::vector<StepDecisions>& decisions, const Scenario& scenario) {
  AssociationCounts counts;
  std::unordered_map<LandmarkId, std::int32_t> origin;  // live landmark -> true id it was started from, or -1
  std::unordered_map<std::int32_t, int> live_of_truth;  // true id -> live landmarks started from it
  std::vector<std::pair<LandmarkId, std::int32_t>> created;
  for (const StepDecisions& d : decisions) {
    ARBOR_CHECK(d.step >= 0 && static_cast<std::size_t>(d.step) < scenario.steps.size(),
                "decision record names step {} but the scenario has {}", d.step, scenario.steps.size());
    const auto& measurements = scenario.steps[d.step].measurements;
    ARBOR_CHECK(d.landmarks.size() == measurements.size(),
                "decision record at step {} has {} decisions for {} measurements", d.step, d.landmarks.size(),
                measurements.size());
    // Every measurement is judged against the map as it stood when the scan began; the landmarks this scan
    // started join it afterwards (the engine creates one landmark per measurement it calls new).
    created.clear();
    for (std::size_t k = 0; k < measurements.size(); ++k) {
      const std::int32_t truth = measurements[k].truth_id;
      const LandmarkId id = d.landmarks[k];
      const auto paired = id == kNoLandmark ? origin.end() : origin.find(id);
      if (id != kNoLandmark && paired == origin.end()) created.emplace_back(id, truth >= 0 ? truth : -1);
      if (truth == kTruthUnknown) continue;
      ++counts.scored;
      if (paired != origin.end()) {
        if (truth >= 0 && paired->second == truth) ++counts.true_matches;
        else ++counts.false_matches;
        continue;
      }
      const auto held = truth >= 0 ? live_of_truth.find(truth) : live_of_truth.end();
      const bool map_held_it = held != live_of_truth.end() && held->second > 0;
      if (map_held_it) ++counts.missed_matches;
      if (id != kNoLandmark && (truth < 0 || map_held_it)) ++counts.false_new;
    }
    for (const auto& [id, truth] : created) {
      origin[id] = truth;
      ++live_of_truth[truth];
    }
    for (const LandmarkId id : d.erased) {
      const auto it = origin.find(id);
      if (it == origin.end()) continue;
      --live_of_truth[it->second];
      origin.erase(it);
    }
  }
  return counts;
}

std::int64_t spurious_landmarks(const std::vector<Landmark>& map) {
  std::unordered_set<std::int32_t> seen;
  std::int64_t spurious = 0;
  for (const Landmark& lm : map) spurious += lm.truth_label < 0 || !seen.insert(lm.truth_label).second;
  return spurious;
}

std::int64_t observed_true_landmarks(const Scenario& scenario) {
  std::unordered_set<std::int32_t> seen;
  for (const ScenarioStep& step : scenario.steps)
    for (const Measurement& m : step.measurements)
      if (m.truth_id >= 0) seen.insert(m.truth_id);
  return static_cast<std::int64_t>(seen.size());
}

}  // namespace arbor
