// The consistency horizon on hand-made NEES series (issue 41): windows of 10, band of the mean of ten
// chi-square(3) values [chi2(30; 0.025) / 10, chi2(30; 0.975) / 10] = [1.679, 4.698].
#include <vector>

#include <gtest/gtest.h>

#include "core/metrics/trajectory_metrics.h"

namespace arbor {
namespace {

TEST(ConsistencyHorizon, AConsistentRunKeepsItsWholeLength) {
  EXPECT_EQ(consistency_horizon(std::vector<double>(50, 3.0)), 50u);
}

TEST(ConsistencyHorizon, ARunThatLeavesTheBandForGoodEndsWhereItsLastWindowInsideEnds) {
  std::vector<double> nees(20, 3.0);
  nees.resize(45, 100.0);
  EXPECT_EQ(consistency_horizon(nees), 20u) << "the window of samples 10-19 is the last inside";
}

TEST(ConsistencyHorizon, AnExcursionThatComesBackDoesNotEndIt) {
  std::vector<double> nees(20, 3.0);
  nees.resize(30, 100.0);
  nees.resize(60, 3.0);
  EXPECT_EQ(consistency_horizon(nees), 60u);
}

TEST(ConsistencyHorizon, TheBandIsTheMeanOfTenAndHasTwoSides) {
  // A mean of 4.6 is inside, 4.8 is not; 1.7 inside, 1.6 not (underconfidence leaves the band too).
  EXPECT_EQ(consistency_horizon(std::vector<double>(10, 4.6)), 10u);
  EXPECT_EQ(consistency_horizon(std::vector<double>(10, 4.8)), 0u);
  EXPECT_EQ(consistency_horizon(std::vector<double>(10, 1.7)), 10u);
  EXPECT_EQ(consistency_horizon(std::vector<double>(10, 1.6)), 0u);
}

TEST(ConsistencyHorizon, FewerSamplesThanAWindowHaveNone) {
  EXPECT_FALSE(consistency_horizon(std::vector<double>(9, 3.0)).has_value());
  EXPECT_FALSE(consistency_horizon({}).has_value());
}

}  // namespace
}  // namespace arbor
