// The smoother as the accuracy reference: on small simulated worlds with true association its trajectory
// error is below FastSLAM's on the same data, and below dead reckoning's.
//
// The error is the SE(2)-aligned ATE, which compares what the estimators control: the map's frame rests on
// the start pose and its first scan, and a rigid offset of everything says little about either estimator.
#include <gtest/gtest.h>

#include "core/metrics/trajectory_metrics.h"
#include "experiments/sim/simulator.h"
#include "variants/registry.h"
#include "variants/smoothing/smoother.h"

namespace arbor {
namespace {

double aligned_ate(const std::vector<TimedPose>& trajectory, const Scenario& s) {
  const auto ate = absolute_trajectory_error(trajectory, truth_positions(s), /*align=*/true);
  EXPECT_TRUE(ate.has_value());
  return ate ? ate->rmse_m : 0.0;
}

TEST(SmootherVsFastSlam, SmootherIsMoreAccurateWithTrueAssociation) {
  for (std::uint64_t seed : {1u, 2u, 3u}) {
    SimulationOptions sim;
    sim.world.landmarks = 60;
    sim.steps = 150;
    sim.seed = seed;
    sim.world.seed = seed;
    const Scenario s = simulate(sim);

    const SmootherResult smoothed = smooth(s, SmootherAssociations::from_truth(s), SmootherOptions{});
    ASSERT_TRUE(smoothed.summary.usable) << smoothed.summary.report;
    std::vector<TimedPose> smoother_trajectory;
    for (const SmoothedPose& p : smoothed.poses) smoother_trajectory.push_back({p.time_s, p.pose});

    FastSlamOptions fs;
    fs.particles = 50;
    fs.seed = 7;
    fs.threads = 1;
    std::unique_ptr<Filter> filter = make_filter("naive", "known", s, fs);
    for (const ScenarioStep& step : s.steps) filter->step(step);

    const double smoother = aligned_ate(smoother_trajectory, s);
    const double fastslam = aligned_ate(filter->best_trajectory(), s);
    const double dr = aligned_ate(dead_reckoning(s), s);
    EXPECT_LT(smoother, fastslam) << "seed " << seed;
    EXPECT_LT(smoother, 0.5 * dr) << "seed " << seed;
    // Unaligned, the smoother still beats dead reckoning by far.
    const auto raw = absolute_trajectory_error(smoother_trajectory, truth_positions(s), false);
    const auto raw_dr = absolute_trajectory_error(dead_reckoning(s), truth_positions(s), false);
    EXPECT_LT(raw->rmse_m, raw_dr->rmse_m) << "seed " << seed;
  }
}

}  // namespace
}  // namespace arbor
