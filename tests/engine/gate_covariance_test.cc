// The gates of issue 41. Known association, the oracle, refuses no true measurement by default. With
// --gate-covariance set, a particle set that drifted apart over a stretch without landmarks still pairs the
// landmark it sights again, which each particle's own covariance puts outside its gate. And the new options
// (set gating, roughened resampling, tempered weights) keep runs bit-identical across map back ends and thread
// counts.
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/engine/fastslam.h"
#include "experiments/run/fastslam_run.h"
#include "experiments/sim/simulator.h"
#include "tests/engine/worlds.h"
#include "variants/association/jcbb.h"
#include "variants/maps/vector_map.h"
#include "variants/registry.h"

namespace arbor {
namespace {

TEST(GateCovariance, KnownAssociationByDefaultRefusesNoMeasurementOnAWorldWithoutOutliers) {
  for (std::uint64_t seed : {1, 2, 3}) {
    const Scenario scenario = testing::simulated_world(seed, 300);
    RunConfig c = testing::fastslam_config(FilterVersion::kFastSlam2, 30, seed, 2);
    const RunOutput out = run_fastslam(scenario, c);
    EXPECT_EQ(out.result["rejected_measurements"].get<std::int64_t>(), 0) << "seed " << seed;
  }
  // The gate is still there on request, and refuses some of the same truth.
  RunConfig gated = testing::fastslam_config(FilterVersion::kFastSlam2, 30, 1, 2);
  gated.options.association.known_gate_probability = 0.9;
  EXPECT_GT(run_fastslam(testing::simulated_world(1, 300), gated).result["rejected_measurements"].get<std::int64_t>(), 0);
}

constexpr int kGapScans = 60;  // scans without a measurement: the particles' headings drift apart

// A robot standing at the origin (testing::standing_robot) that knows one landmark 19.5 m ahead (beyond the 19 m where a miss is negative evidence, so the gap does not erase it), sees nothing
// for kGapScans scans, then sees that landmark where it truly is. Over the gap each particle draws its own
// odometry noise at every scan, so the set's headings spread by about 2 degrees times sqrt(kGapScans), while
// each particle's own prediction covariance holds one scan's worth.
Scenario drifting_gap() {
  std::vector<std::vector<Vec2>> scans(kGapScans);
  scans.push_back({Vec2(19.5, 0.0)});
  return testing::standing_robot(scans);
}

// The share of particles that pair the re-sighting with the known landmark.
double share_pairing_after_gap(GateCovariance gates) {
  const Scenario scenario = drifting_gap();
  FastSlamOptions options;
  options.particles = 200;
  options.threads = 2;
  options.seed = 4;
  options.gate_covariance = gates;
  FastSlam<VectorMap, Jcbb> engine(scenario, options);
  VectorMap prior;
  Landmark lm;
  lm.id = 0;
  lm.mean = Vec2(19.5, 0.0);
  lm.cov = 0.01 * Mat2::Identity();
  lm.log_odds = 8.0f;
  lm.confirmed = true;
  prior.insert(lm);
  engine.set_prior_map(prior);
  for (const ScenarioStep& step : scenario.steps) engine.step(step);
  int paired = 0;
  for (int i = 0; i < engine.particle_count(); ++i) {
    const std::vector<StepDecisions> decisions = engine.particle(i).decisions.to_vector();
    paired += !decisions.empty() && !decisions.back().landmarks.empty() && decisions.back().landmarks[0] == 0;
  }
  return static_cast<double>(paired) / engine.particle_count();
}

TEST(GateCovariance, ASetThatDriftedOverAGapPairsTheReSightedLandmark) {
  const double own = share_pairing_after_gap(GateCovariance::kParticle);
  const double set = share_pairing_after_gap(GateCovariance::kSet);
  EXPECT_LT(own, 0.5) << "the gap must drift the set beyond the particles' own gates, or this test shows nothing";
  EXPECT_GT(set, 0.95) << "a 0.99 gate of a consistent spread keeps about 99 %";
}

// The rooms world with clutter (as LoopClosure.RunsAreBitIdenticalAcrossBackendsAndThreads) under JCBB, with
// set gating, roughened resampling and tempered weights on.
TEST(GateCovariance, Issue41OptionsAreBitIdenticalAcrossBackendsAndThreads) {
  const Scenario scenario = testing::cluttered_rooms(3, 150, /*clutter=*/2.0, /*scans=*/200);
  testing::expect_bit_identical_across_backends_and_threads(
      scenario, "set_gates",
      [](RunConfig& c) {
        testing::small_jcbb_run(c);
        c.options.gate_covariance = GateCovariance::kSet;
        c.options.roughen = 1.0;
        c.options.weight_exponent = 0.25;
      },
      [](const RunOutput& out, const std::string& what) {
        EXPECT_GT(out.result["resamples"].get<int>(), 0) << what << ": roughening acts only after a resampling";
      });
}

}  // namespace
}  // namespace arbor
