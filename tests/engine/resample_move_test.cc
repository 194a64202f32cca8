// Resample-move (issue 41, core/engine/resample_move.h). A particle set that lost its diversity over a gap
// regains it for the gap's poses; a move keeps the bookkeeping exact (the
// window replayed along the path a particle holds gives the landmarks its map holds); the option is
// bit-identical across map back ends and thread counts.
#include <cmath>
#include <set>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/engine/fastslam.h"
#include "experiments/run/fastslam_run.h"
#include "experiments/sim/simulator.h"
#include "tests/engine/worlds.h"
#include "variants/association/known_association.h"
#include "variants/maps/vector_map.h"

namespace arbor {
namespace {

// A robot standing at the origin, heading 0, with exact measurements and true ids. It maps landmarks 0 and 1
// ahead (scans 0-4), sees nothing for kGap scans while each particle's heading drifts on the odometry noise,
// maps landmark 2 on its left over kNewArea scans (every scan resamples, so the set comes to descend from one
// parent and one drifted heading), then sees all three again for kClosure scans.
constexpr int kGap = 60, kNewArea = 40, kClosure = 10;
const std::vector<Vec2> kLandmarks = {{10.0, 0.0}, {10.0, 3.0}, {3.0, 10.0}};

Scenario gap_then_closure() {
  Scenario s;
  s.sensor.max_range_m = 20.0;
  s.sensor.fov_rad = kPi;
  s.sensor.sigma_range_m = 0.1;
  s.sensor.sigma_bearing_rad = 0.01;
  const auto sight = [](int id) {
    const Vec2& p = kLandmarks[id];
    return Measurement{p.norm(), std::atan2(p.y(), p.x()), std::numeric_limits<float>::quiet_NaN(), id};
  };
  const int scans = 5 + kGap + kNewArea + kClosure;
  for (int k = 0; k < scans; ++k) {
    ScenarioStep step;
    step.time_s = 0.5 * (k + 1);
    step.has_scan = true;
    step.truth_pose = Pose2{};
    if (k < 5) step.measurements = {sight(0), sight(1)};
    else if (k >= 5 + kGap && k < 5 + kGap + kNewArea) step.measurements = {sight(2)};
    else if (k >= 5 + kGap + kNewArea) step.measurements = {sight(0), sight(1), sight(2)};
    s.steps.push_back(step);
  }
  return s;
}

FastSlamOptions gap_options(int move_window, std::uint64_t seed = 7) {
  FastSlamOptions o;
  o.particles = 50;
  o.threads = 2;
  o.seed = seed;
  o.resample_threshold = 1.0;  // resample at every scan: the depletion a long stretch of new landmarks brings
  o.weight_exponent = 1.0;     // the paper's weights: tempered ones (the default here) deplete the set less
  o.move_window = move_window;
  return o;
}

// How many distinct headings the particles hold, at the end of the run, for the last scan of the gap.
int distinct_gap_headings(int move_window, std::uint64_t seed) {
  const Scenario scenario = gap_then_closure();
  FastSlam<VectorMap, KnownAssociation> engine(scenario, gap_options(move_window, seed));
  for (const ScenarioStep& step : scenario.steps) engine.step(step);
  const double gap_end_s = scenario.steps[5 + kGap - 1].time_s;
  std::set<double> headings;
  for (int i = 0; i < engine.particle_count(); ++i)
    for (const TimedPose& p : engine.particle(i).history.to_vector())
      if (p.time_s == gap_end_s) headings.insert(p.pose.theta);
  return static_cast<int>(headings.size());
}

// Resampling at every scan of the new area leaves the set few ancestors for the gap (path depletion): the
// heading it drifted to there is then fixed for good. The move, its window reaching back into the gap,
// gives the copies their own gap headings again, drawn from the target.
TEST(ResampleMove, ADepletedSetRegainsDiverseGapHeadings) {
  for (std::uint64_t seed : {1, 2, 3}) {
    const int without = distinct_gap_headings(0, seed);
    const int with = distinct_gap_headings(kGap / 2 + kNewArea + kClosure, seed);
    EXPECT_LE(without, 5) << "seed " << seed << ": the set must be depleted over the gap, or this test shows nothing";
    EXPECT_GE(with, 25) << "seed " << seed << " (of 50 particles)";
  }
}

// After every step (moves accepted or not), each particle's window replayed along its path gives exactly the
// landmark estimates its map holds: the before-states, the pairings and the history of a move stay in step.
TEST(ResampleMove, TheWindowReplayedAlongTheHeldPathGivesTheMapsLandmarks) {
  const Scenario scenario = testing::simulated_world(5, 120, /*clutter=*/0.0);
  FastSlamOptions o = gap_options(15);
  o.resample_threshold = 0.5;
  FastSlam<VectorMap, KnownAssociation> engine(scenario, o);
  std::int64_t accepted = 0, compared = 0;
  for (const ScenarioStep& step : scenario.steps) {
    engine.step(step);
    accepted += engine.last_step_stats().moves_accepted;
    for (int i = 0; i < engine.particle_count(); ++i) {
      const Particle<VectorMap>& p = engine.particle(i);
      if (step.has_scan && !p.move.scans.empty()) {
        const TimedPose& newest = p.history.newest();
        EXPECT_EQ(newest.pose.x, p.move.scans.back()->pose.x);
        EXPECT_EQ(newest.pose.theta, p.move.scans.back()->pose.theta);
      }
      for (const LandmarkEstimate& e : engine.replay_move_window(i)) {
        const Landmark* lm = p.map.find(e.id);
        if (!lm) continue;
        ++compared;
        ASSERT_NEAR((lm->mean - e.mean).norm(), 0.0, 1e-9) << "particle " << i << " landmark " << e.id;
        ASSERT_NEAR((lm->cov - e.cov).norm(), 0.0, 1e-12) << "particle " << i << " landmark " << e.id;
      }
    }
  }
  EXPECT_GT(accepted, 0) << "no move was accepted: the replay was only checked along unmoved paths";
  EXPECT_GT(compared, 1000);
}

TEST(ResampleMove, IsBitIdenticalAcrossBackendsAndThreads) {
  const Scenario scenario = testing::simulated_world(3, 200, /*clutter=*/2.0);
  testing::expect_bit_identical_across_backends_and_threads(
      scenario, "resample_move",
      [](RunConfig& c) {
        testing::small_jcbb_run(c);
        c.options.move_window = 10;
      },
      [](const RunOutput& out, const std::string& what) {
        const double acceptance = out.result["move_acceptance"].get<double>();
        EXPECT_GT(acceptance, 0.0) << what;
        EXPECT_LT(acceptance, 1.0) << what;
      });
}

TEST(ResampleMove, RefusesWhatItDoesNotCombineWith) {
  FastSlamOptions o;
  o.move_window = 10;
  EXPECT_EQ(o.validate(), "");
  o.close_loops = true;
  EXPECT_NE(o.validate().find("resample-move"), std::string::npos);
  o.close_loops = false;
  o.motion_sampling = MotionSampling::kPerControl;
  EXPECT_NE(o.validate().find("per-scan"), std::string::npos);
}

}  // namespace
}  // namespace arbor
