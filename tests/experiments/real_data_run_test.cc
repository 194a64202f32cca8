// End to end on real data: the converted UTIAS MRCLAM robot 1 run through FastSLAM 2.0 with known association.
#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "core/metrics/decision_score.h"
#include "experiments/loaders/utias_mrclam.h"
#include "variants/registry.h"

namespace arbor {
namespace {

// Position RMSE of the filter's weighted-mean pose and of dead reckoning against the interpolated Vicon poses.
// No alignment: the scenario starts at the Vicon pose, so both live in the Vicon frame.
struct RunErrors {
  double filter_rmse_m = 0.0;
  double dead_reckoning_rmse_m = 0.0;
  std::size_t landmarks = 0;
};

RunErrors run_known_association(const Scenario& s, int particles, std::uint64_t seed) {
  FastSlamOptions options;
  options.version = FilterVersion::kFastSlam2;
  options.particles = particles;
  options.seed = seed;
  options.threads = 2;
  auto filter = make_filter("naive", "known", s, options);
  Pose2 dead_reckoning = s.initial_pose;
  double sum_filter = 0.0, sum_dr = 0.0;
  std::size_t n = 0;
  for (const auto& step : s.steps) {
    filter->step(step);
    dead_reckoning = s.motion.apply(dead_reckoning, step.control);
    if (!step.truth_pose) continue;
    sum_filter += (filter->estimate().mean.position() - step.truth_pose->position()).squaredNorm();
    sum_dr += (dead_reckoning.position() - step.truth_pose->position()).squaredNorm();
    ++n;
  }
  return {std::sqrt(sum_filter / n), std::sqrt(sum_dr / n), filter->best_map().size()};
}

TEST(RealData, UtiasRobot1WithKnownAssociationAteFarBelowDeadReckoning) {
  LoadReport report;
  const Scenario s = load_utias_mrclam(std::string(ARBOR_SOURCE_DIR) + "/data/utias_mrclam/MRCLAM_Dataset6", {}, &report);
  // Measured (Release, 100 particles, the whole 760 s, the weighted mean at every Vicon time): seed 1
  // 0.44 m, seeds 1-3 0.44-0.69 m; dead reckoning 2.62 m. Before prediction between scans and the calibrated
  // noise the same run gave 1.13 m (seeds 1-3: 0.78-1.13 m), so the floor of 0.6 m fails for that engine.
  // Since the loader scales the logged commands (issue 41: 0.94 speed, 0.93 turn rate, fitted on robots 1-2),
  // dead reckoning itself is 1.60 m, not 2.62 m.
  const RunErrors e = run_known_association(s, 100, 1);
  EXPECT_GT(e.dead_reckoning_rmse_m, 1.2);
  EXPECT_LT(e.filter_rmse_m, 0.6);
  EXPECT_EQ(e.landmarks, 15u);
}

TEST(RealData, UtiasRobot1WithJcbbAssociatesAboveAMeasuredF1Floor) {
  LoadReport report;
  const Scenario s = load_utias_mrclam(std::string(ARBOR_SOURCE_DIR) + "/data/utias_mrclam/MRCLAM_Dataset6", {}, &report);
  FastSlamOptions options;
  options.version = FilterVersion::kFastSlam2;
  options.particles = 10;
  options.seed = 1;
  options.threads = 2;
  auto filter = make_filter("naive", "jcbb", s, options);
  for (const auto& step : s.steps) filter->step(step);
  // Measured (Release, 10 particles, seeds 1-3, the whole run, the noise calibrated with its tails):
  // F1 0.60-0.69 (precision 0.45-0.56, recall 0.87-0.91); seed 1 gives 0.642. The wider, honest gates pair
  // more measurements with a neighbour than the MAD-based noise did (F1 0.70-0.78), which is the association
  // issue's to fix. A floor of 0.55 still fails for an association that pairs at random.
  const auto f1 = score_decisions(filter->best_decisions(), s).f1();
  ASSERT_TRUE(f1.has_value());
  EXPECT_GT(*f1, 0.55);
}

}  // namespace
}  // namespace arbor
