// Nearest neighbour: greedy exclusion by distance, the variant without exclusion, and the shared unpaired
// rule (NEW only outside every new-landmark gate).
#include <gtest/gtest.h>

#include "tests/association/test_problems.h"
#include "variants/association/nearest_neighbor.h"

namespace arbor {
namespace {

AssociationProblem two_landmarks() {
  const Pose2 prior;
  AssociationProblem p;
  p.R = Vec2(0.1 * 0.1, 0.02 * 0.02).asDiagonal();
  const Mat2 sigma = Mat2::Identity() * 0.05 * 0.05;
  p.candidates.push_back(testing::make_candidate(3, prior, Vec2(10.0, 0.0), sigma, p.R));
  p.candidates.push_back(testing::make_candidate(8, prior, Vec2(0.0, 10.0), sigma, p.R));
  return p;
}

TEST(NearestNeighbor, ExclusionGivesTheLandmarkToTheCloserMeasurement) {
  AssociationProblem p = two_landmarks();
  p.measurements.push_back(testing::make_measurement(10.15, 0.0));  // farther from landmark 3
  p.measurements.push_back(testing::make_measurement(10.02, 0.0));  // closer
  EXPECT_EQ(testing::solve_with<NearestNeighbor>(p).pairing, (std::vector<LandmarkId>{kSpurious, 3}));
  EXPECT_EQ(testing::solve_with<NearestNeighborNoExclusion>(p).pairing, (std::vector<LandmarkId>{3, 3}));
}

TEST(NearestNeighbor, UnpairedRuleSeparatesNewFromAmbiguous) {
  AssociationProblem p = two_landmarks();
  p.measurements.push_back(testing::make_measurement(10.0, 1.5708));  // on landmark 8
  p.measurements.push_back(testing::make_measurement(10.37, 0.0));    // ~3.3 sigma from landmark 3: ambiguous
  p.measurements.push_back(testing::make_measurement(20.0, -2.0));    // far from everything: new
  EXPECT_EQ(testing::solve_with<NearestNeighbor>(p).pairing, (std::vector<LandmarkId>{8, kSpurious, kNewLandmark}));
}

TEST(NearestNeighbor, BearingDifferencesWrap) {
  const Pose2 prior;
  AssociationProblem p;
  p.R = Vec2(0.1 * 0.1, 0.02 * 0.02).asDiagonal();
  p.candidates.push_back(testing::make_candidate(1, prior, Vec2(-10.0, 0.01), Mat2::Identity() * 1e-4, p.R));
  p.measurements.push_back(testing::make_measurement(10.0, -3.14));  // the same direction across +-pi
  EXPECT_EQ(testing::solve_with<NearestNeighbor>(p).pairing, (std::vector<LandmarkId>{1}));
}

}  // namespace
}  // namespace arbor
