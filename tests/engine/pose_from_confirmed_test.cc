// Only confirmed landmarks steer the pose (FastSlamOptions::pose_from_confirmed, issue 12): a measurement
// paired with a provisional landmark updates it, but moves the pose and weighs the particle exactly as an
// unpaired measurement would, unless the scan pairs no confirmed landmark and provisional_steer_min
// provisional ones. A confirmed landmark steers as before. Both filter versions.
#include <vector>

#include <gtest/gtest.h>

#include "core/engine/fastslam.h"
#include "tests/engine/worlds.h"
#include "variants/association/jcbb.h"
#include "variants/maps/vector_map.h"

namespace arbor {
namespace {

struct SteeringOutcome {
  std::vector<Pose2> poses;            // every particle's, at the end
  std::vector<double> log_weights;     // likewise
  std::vector<LandmarkId> decisions;   // particle 0's decisions, measurement by measurement, scan by scan
};

// Every scan's measurements as (range, bearing); particle 0's decisions are listed scan after scan.
SteeringOutcome run_scans(const std::vector<std::vector<Vec2>>& scans, FilterVersion version, bool pose_from_confirmed,
                          int provisional_steer_min = 0, const VectorMap* prior = nullptr) {
  const Scenario scenario = testing::standing_robot(scans);
  FastSlamOptions options;
  options.version = version;
  options.particles = 4;
  options.threads = 1;
  options.pose_from_confirmed = pose_from_confirmed;
  options.provisional_steer_min = provisional_steer_min;
  FastSlam<VectorMap, Jcbb> engine(scenario, options);
  if (prior) engine.set_prior_map(*prior);
  for (const ScenarioStep& step : scenario.steps) engine.step(step);
  SteeringOutcome out;
  for (int i = 0; i < options.particles; ++i) {
    out.poses.push_back(engine.particle(i).pose);
    out.log_weights.push_back(engine.particle(i).log_weight);
  }
  for (const StepDecisions& d : engine.particle(0).decisions.to_vector())
    out.decisions.insert(out.decisions.end(), d.landmarks.begin(), d.landmarks.end());
  return out;
}

// One measurement per scan.
SteeringOutcome run_steering(const std::vector<Vec2>& range_bearings, FilterVersion version, bool pose_from_confirmed,
                             const VectorMap* prior = nullptr) {
  std::vector<std::vector<Vec2>> scans;
  for (const Vec2& z : range_bearings) scans.push_back({z});
  return run_scans(scans, version, pose_from_confirmed, 0, prior);
}

// A prior map of one confirmed landmark, id 0.
VectorMap confirmed_landmark_at(const Vec2& position) {
  VectorMap prior;
  Landmark lm;
  lm.id = 0;
  lm.mean = position;
  lm.cov = 0.01 * Mat2::Identity();
  lm.log_odds = 8.0f;
  lm.confirmed = true;
  prior.insert(lm);
  return prior;
}

bool same_particles(const SteeringOutcome& a, const SteeringOutcome& b) {
  for (std::size_t i = 0; i < a.poses.size(); ++i)
    if (a.poses[i].vector() != b.poses[i].vector() || a.log_weights[i] != b.log_weights[i]) return false;
  return true;
}

// The first scan starts a provisional landmark 10 m ahead; the second sees it 0.15 m further (inside the
// gate, so paired), or sees something 5 m to the left instead (a new landmark).
const std::vector<Vec2> kSecondSightingOffRange{{10.0, 0.0}, {10.15, 0.0}};
const std::vector<Vec2> kSecondScanElsewhere{{10.0, 0.0}, {5.0, 1.0}};

class PoseFromConfirmed : public ::testing::TestWithParam<FilterVersion> {};

TEST_P(PoseFromConfirmed, AProvisionalLandmarkMovesNothingThatANewOneWouldNot) {
  const FilterVersion version = GetParam();
  const SteeringOutcome paired = run_steering(kSecondSightingOffRange, version, true);
  ASSERT_EQ(paired.decisions, (std::vector<LandmarkId>{0, 0})) << "the second sighting pairs the provisional landmark";
  const SteeringOutcome elsewhere = run_steering(kSecondScanElsewhere, version, true);
  ASSERT_EQ(elsewhere.decisions, (std::vector<LandmarkId>{0, 1}));
  EXPECT_TRUE(same_particles(paired, elsewhere)) << "poses and weights as if the measurement were unpaired";

  // The control: without the option the same pairing moves the poses (2.0) or the weights (1.0).
  const SteeringOutcome steered = run_steering(kSecondSightingOffRange, version, false);
  ASSERT_EQ(steered.decisions, paired.decisions);
  EXPECT_FALSE(same_particles(steered, run_steering(kSecondScanElsewhere, version, false)));
}

// A landmark of a prior map is confirmed: the option changes nothing, and the pairing still steers.
TEST_P(PoseFromConfirmed, AConfirmedLandmarkStillSteers) {
  const FilterVersion version = GetParam();
  const VectorMap prior = confirmed_landmark_at(Vec2(10.0, 0.0));
  const std::vector<Vec2> off_range{{10.15, 0.0}};
  const SteeringOutcome with = run_steering(off_range, version, true, &prior);
  ASSERT_EQ(with.decisions, (std::vector<LandmarkId>{0}));
  EXPECT_TRUE(same_particles(with, run_steering(off_range, version, false, &prior)));
  EXPECT_FALSE(same_particles(with, run_steering({{5.0, 1.0}}, version, true, &prior)));
}

INSTANTIATE_TEST_SUITE_P(BothVersions, PoseFromConfirmed,
                         ::testing::Values(FilterVersion::kFastSlam1, FilterVersion::kFastSlam2),
                         [](const auto& info) { return std::string(to_string(info.param)); });

// Three landmarks seen again together, each a little off: a scan that pairs no confirmed landmark but
// provisional_steer_min provisional ones lets them steer after all (the start of every run is such a scan);
// one that pairs fewer is held as before. FastSLAM 2.0 only: 1.0 associates at its motion draw, and the
// standing robot's 2 degrees of heading noise leave some draws with the three sightings not jointly
// compatible.
TEST(PoseFromConfirmedSteerMin, EnoughProvisionalPairingsInOneScanSteer) {
  const FilterVersion version = FilterVersion::kFastSlam2;
  const std::vector<std::vector<Vec2>> scans{{{3.0, 0.0}, {2.5, 0.5}, {3.5, -0.4}},
                                             {{3.05, 0.0}, {2.55, 0.505}, {3.55, -0.395}}};
  const SteeringOutcome held = run_scans(scans, version, true);
  ASSERT_EQ(held.decisions, (std::vector<LandmarkId>{0, 1, 2, 0, 1, 2})) << "the second scan pairs all three";
  const SteeringOutcome steered = run_scans(scans, version, false);
  EXPECT_FALSE(same_particles(held, steered));
  EXPECT_TRUE(same_particles(steered, run_scans(scans, version, true, 3))) << "three provisional pairings steer";
  EXPECT_TRUE(same_particles(held, run_scans(scans, version, true, 4))) << "fewer than four are held";
}

// A scan that pairs a confirmed landmark steers by it alone: its provisional pairings are held, however many.
TEST(PoseFromConfirmedSteerMin, ProvisionalPairingsBesideAConfirmedOneAreHeld) {
  const FilterVersion version = FilterVersion::kFastSlam2;
  const VectorMap prior = confirmed_landmark_at(Vec2(4.0, 0.0));
  const std::vector<std::vector<Vec2>> scans{{{4.0, 0.0}, {3.0, 0.3}, {2.5, 0.8}, {3.5, -0.5}},
                                             {{4.02, 0.0}, {3.05, 0.305}, {2.55, 0.805}, {3.55, -0.495}}};
  const SteeringOutcome held = run_scans(scans, version, true, 0, &prior);
  ASSERT_EQ(held.decisions, (std::vector<LandmarkId>{0, 1, 2, 3, 0, 1, 2, 3}));
  EXPECT_TRUE(same_particles(held, run_scans(scans, version, true, 3, &prior)));
  EXPECT_FALSE(same_particles(held, run_scans(scans, version, false, 0, &prior))) << "the control: they would steer";
}

}  // namespace
}  // namespace arbor
