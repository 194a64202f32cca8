// The smoother's pose marginals are consistent: with true association on simulated worlds the average
// NEES of the poses against ground truth is near 3 (the pose's dimension), and a smoother told the sensor
// is twice as precise as it is reports errors far outside its marginals. Poses along one trajectory are
// correlated, so the average is over many worlds, and its band is wider than a chi-square band would be.
#include <gtest/gtest.h>

#include "core/metrics/trajectory_metrics.h"
#include "experiments/sim/simulator.h"
#include "variants/smoothing/smoother.h"

namespace arbor {
namespace {

// Mean NEES over the poses with ground truth, over worlds 1..worlds; sensor_scale multiplies the sensor
// noise the smoother assumes (not the noise the simulator drew).
double mean_nees(int worlds, double sensor_scale) {
  double sum = 0.0;
  int n = 0;
  for (int seed = 1; seed <= worlds; ++seed) {
    SimulationOptions sim;
    sim.world.landmarks = 60;
    sim.steps = 150;
    sim.seed = seed;
    sim.world.seed = seed;
    Scenario s = simulate(sim);
    const SmootherAssociations truth = SmootherAssociations::from_truth(s);
    s.sensor.sigma_range_m *= sensor_scale;
    s.sensor.sigma_bearing_rad *= sensor_scale;
    const SmootherResult r = smooth(s, truth, SmootherOptions{});
    EXPECT_TRUE(r.summary.pose_marginals) << "seed " << seed;
    for (const SmoothedPose& p : r.poses) {
      if (p.step < 0 || !s.steps[p.step].truth_pose) continue;
      sum += pose_nees(p.pose, p.covariance, *s.steps[p.step].truth_pose);
      ++n;
    }
  }
  return sum / n;
}

TEST(SmootherConsistency, PoseNeesAveragesThreeWithTheTrueNoise) {
  const double nees = mean_nees(12, 1.0);
  EXPECT_GT(nees, 2.0);
  EXPECT_LT(nees, 4.5);
}

TEST(SmootherConsistency, AnOverconfidentSensorModelIsCaught) {
  const double nees = mean_nees(12, 0.5);
  EXPECT_GT(nees, 4.5);
}

}  // namespace
}  // namespace arbor
