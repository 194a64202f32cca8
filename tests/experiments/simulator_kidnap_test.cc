// The kidnapped robot of `arbor simulate --kidnap T`: at the first scan at or after T the true robot is back
// where it was at T/2, and the odometer says nothing of the jump.
#include <gtest/gtest.h>

#include "experiments/sim/simulator.h"

namespace arbor {
namespace {

TEST(SimulatorKidnap, TheRobotReappearsWhereItWasAtHalfTheTimeAndTheOdometerSeesNothing) {
  SimulationOptions o;
  o.steps = 120;
  o.kidnap_time_s = 40.0;  // scan 80 (dt 0.5 s): carried back to where it was at scan 40
  const Scenario kidnapped = simulate(o);
  o.kidnap_time_s = -1.0;
  const Scenario plain = simulate(o);
  ASSERT_EQ(kidnapped.steps.size(), plain.steps.size());
  const double step_m = o.speed_mps * o.dt_s;
  for (int k = 1; k < o.steps; ++k) {
    const Vec2 moved = kidnapped.steps[k].truth_pose->position() - kidnapped.steps[k - 1].truth_pose->position();
    if (k == 80) {
      EXPECT_GT(moved.norm(), 10.0) << "the jump";
      EXPECT_LT((kidnapped.steps[k].truth_pose->position() - plain.steps[40].truth_pose->position()).norm(), 1.5 * step_m);
    } else {
      EXPECT_LT(moved.norm(), 1.01 * step_m) << "scan " << k;
    }
    // The odometer reads one step of driving every time, the jump included.
    EXPECT_NEAR(kidnapped.steps[k].control.head<2>().norm(), step_m, 0.2) << "scan " << k;
  }
  EXPECT_EQ(kidnapped.metadata.at("kidnap_time_s"), "40");
}

}  // namespace
}  // namespace arbor
