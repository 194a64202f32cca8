// Association decisions scored from the record (core/metrics/decision_score.h): each kind of count from a
// hand-made lineage, removals taken into account, and unknown truth skipped.
#include <gtest/gtest.h>

#include "core/metrics/decision_score.h"

namespace arbor {
namespace {

// A scenario whose step k holds one measurement per entry of truth_ids[k].
Scenario scans(const std::vector<std::vector<std::int32_t>>& truth_ids) {
  Scenario s;
  for (const auto& ids : truth_ids) {
    ScenarioStep step;
    step.has_scan = true;
    for (const std::int32_t id : ids) step.measurements.push_back({10.0, 0.0, std::numeric_limits<float>::quiet_NaN(), id});
    s.steps.push_back(step);
  }
  return s;
}

TEST(DecisionScore, EachKindOfDecisionCountsWhereTheDefinitionsSay) {
  // Step 0: landmarks 0 (true 7) and 1 (true 8) are started, 2 from clutter: one false new (clutter).
  // Step 1: 7 -> 0 true match; 8 -> 0 false match; clutter -> 2 false match; 7 judged spurious: missed.
  // Step 2: 8 started again as landmark 3 while 1 still stands: missed match and false new.
  const Scenario s = scans({{7, 8, -1}, {7, 8, -1, 7}, {8}});
  const std::vector<StepDecisions> decisions{{0, {0, 1, 2}, {}}, {1, {0, 0, 2, kNoLandmark}, {}}, {2, {3}, {}}};
  const AssociationCounts c = score_decisions(decisions, s);
  EXPECT_EQ(c.scored, 8);
  EXPECT_EQ(c.true_matches, 1);
  EXPECT_EQ(c.false_matches, 2);
  EXPECT_EQ(c.missed_matches, 2);
  EXPECT_EQ(c.false_new, 2);
}

TEST(DecisionScore, ALandmarkTheMapRemovedIsNoLongerOneToMiss) {
  const Scenario s = scans({{5}, {}, {5}});
  const AssociationCounts kept = score_decisions({{0, {0}, {}}, {2, {1}, {}}}, s);
  EXPECT_EQ(kept.missed_matches, 1);
  EXPECT_EQ(kept.false_new, 1);
  const AssociationCounts removed = score_decisions({{0, {0}, {}}, {1, {}, {0}}, {2, {1}, {}}}, s);
  EXPECT_EQ(removed.missed_matches, 0);
  EXPECT_EQ(removed.false_new, 0);
  EXPECT_EQ(removed.scored, 2);
}

TEST(DecisionScore, TwoMeasurementsOfOneLandmarkInItsFirstScanAreJudgedAgainstTheMapBeforeIt) {
  const Scenario s = scans({{4, 4}});
  const AssociationCounts c = score_decisions({{0, {0, 1}, {}}}, s);
  EXPECT_EQ(c.missed_matches, 0);
  EXPECT_EQ(c.false_new, 0);
}

TEST(DecisionScore, MeasurementsWithoutGroundTruthAreNotScoredButStillBuildTheMap) {
  Scenario s = scans({{kTruthUnknown}, {kTruthUnknown}});
  const AssociationCounts c = score_decisions({{0, {0}, {}}, {1, {0}, {}}}, s);
  EXPECT_EQ(c.scored, 0);
  EXPECT_FALSE(c.f1().has_value());
}

TEST(DecisionScore, ARecordThatDoesNotFitTheScenarioIsAnError) {
  const Scenario s = scans({{1, 2}});
  EXPECT_DEATH(score_decisions({{0, {0}, {}}}, s), "1 decisions for 2 measurements");
  EXPECT_DEATH(score_decisions({{3, {0, 1}, {}}}, s), "names step 3");
}

}  // namespace
}  // namespace arbor
