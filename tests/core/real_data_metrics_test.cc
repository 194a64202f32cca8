// Metrics needed on real data: GPS jump rejection and landmark RMSE by distance matching (no truth ids).
#include <gtest/gtest.h>

#include "core/metrics/gps_jumps.h"
#include "core/metrics/landmark_matching.h"

namespace arbor {
namespace {

TEST(GpsJumps, DropsFixesThatImplyAnImpossibleSpeedUntilTheVehicleCouldBeThere) {
  std::vector<TimedPosition> track;
  for (int k = 0; k <= 10; ++k) track.push_back({0.2 * k, {1.0 * 0.2 * k, 0.0}});  // 1 m/s along x
  track[5].position.y() = 30.0;                                                  // one wild fix
  track[6].position.y() = 30.0;                                                  // and it stays there once
  int dropped = -1;
  const auto kept = drop_gps_jumps(track, 8.0, 1.0, &dropped);
  EXPECT_EQ(dropped, 2);
  ASSERT_EQ(kept.size(), 9u);
  EXPECT_DOUBLE_EQ(kept[5].time_s, 0.2 * 7);
  // A long gap is not a jump: the allowed distance grows with the time since the last kept fix.
  const std::vector<TimedPosition> gap = {{0.0, {0, 0}}, {60.0, {200, 0}}};
  EXPECT_EQ(drop_gps_jumps(gap, 8.0, 1.0).size(), 2u);
}

TEST(LandmarkMatching, PairsOneToOneWithinTheGateAfterAlignment) {
  std::vector<TruthLandmark> truth = {{0, {0, 0}}, {1, {10, 0}}, {2, {0, 10}}};
  std::vector<Landmark> map(4);
  map[0].mean = {0.1, 0.0};
  map[1].mean = {10.0, 0.2};
  map[2].mean = {0.0, 0.3};  // a duplicate of landmark 0, further away: left unmatched
  map[3].mean = {50.0, 50.0};
  const auto e = matched_landmark_rmse(map, truth, 2.0);
  ASSERT_TRUE(e.has_value());
  EXPECT_EQ(e->matched, 2);
  EXPECT_EQ(e->unmatched, 2);
  EXPECT_EQ(e->missed, 1);
  EXPECT_NEAR(e->rmse_m, std::sqrt((0.01 + 0.04) / 2), 1e-12);
  // The same map shifted by (5, 0): matched only after the alignment that undoes the shift.
  for (auto& l : map) l.mean.x() += 5.0;
  EXPECT_FALSE(matched_landmark_rmse(map, truth, 2.0).has_value());
  const auto aligned = matched_landmark_rmse(map, truth, 2.0, Pose2{-5.0, 0.0, 0.0});
  ASSERT_TRUE(aligned.has_value());
  EXPECT_EQ(aligned->matched, 2);
  EXPECT_NEAR(aligned->rmse_m, e->rmse_m, 1e-12);
}

}  // namespace
}  // namespace arbor
