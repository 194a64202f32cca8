// Only confirmed landmarks steer the pose (FastSlamOptions::pose_from_confirmed, issue 12): a measurement
// paired with a provisional landmark updates it, but moves the pose and weighs the particle exactly as an
// unpaired measurement would. A confirmed landmark steers as before. Both filter versions.
#include <vector>

#include <gtest/gtest.h>

#include "core/engine/fastslam.h"
#include "test_support.h"
#include "variants/association/jcbb.h"
#include "variants/maps/vector_map.h"

namespace arbor {
namespace {

struct SteeringOutcome {
  std::vector<Pose2> poses;            // every particle's, at the end
  std::vector<double> log_weights;     // likewise
  std::vector<LandmarkId> decisions;   // particle 0's decision for the measurement, scan by scan
};

SteeringOutcome run_steering(const std::vector<Vec2>& range_bearings, FilterVersion version, bool pose_from_confirmed,
                             const VectorMap* prior = nullptr) {
  std::vector<std::vector<Vec2>> scans;
  for (const Vec2& z : range_bearings) scans.push_back({z});
  const Scenario scenario = testing::standing_robot(scans);  // one measurement per scan
  FastSlamOptions options;
  options.version = version;
  options.particles = 4;
  options.threads = 1;
  options.pose_from_confirmed = pose_from_confirmed;
  FastSlam<VectorMap, Jcbb> engine(scenario, options);
  if (prior) engine.set_prior_map(*prior);
  for (const ScenarioStep& step : scenario.steps) engine.step(step);
  SteeringOutcome out;
  for (int i = 0; i < options.particles; ++i) {
    out.poses.push_back(engine.particle(i).pose);
    out.log_weights.push_back(engine.particle(i).log_weight);
  }
  for (const StepDecisions& d : engine.particle(0).decisions.to_vector())
    if (!d.landmarks.empty()) out.decisions.push_back(d.landmarks[0]);
  return out;
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
  VectorMap prior;
  Landmark lm;
  lm.id = 0;
  lm.mean = Vec2(10.0, 0.0);
  lm.cov = 0.01 * Mat2::Identity();
  lm.log_odds = 8.0f;
  lm.confirmed = true;
  prior.insert(lm);
  const std::vector<Vec2> off_range{{10.15, 0.0}};
  const SteeringOutcome with = run_steering(off_range, version, true, &prior);
  ASSERT_EQ(with.decisions, (std::vector<LandmarkId>{0}));
  EXPECT_TRUE(same_particles(with, run_steering(off_range, version, false, &prior)));
  EXPECT_FALSE(same_particles(with, run_steering({{5.0, 1.0}}, version, true, &prior)));
}

INSTANTIATE_TEST_SUITE_P(BothVersions, PoseFromConfirmed,
                         ::testing::Values(FilterVersion::kFastSlam1, FilterVersion::kFastSlam2),
                         [](const auto& info) { return std::string(to_string(info.param)); });

}  // namespace
}  // namespace arbor
