// Prediction between scans (Probabilistic Robotics Table 13.2): on a world whose odometry is read K times per
// scan, each particle carries its predicted mean and covariance through every control and draws once per scan.
// The tests: the accumulated covariance is exactly the chain of EKF predictions; runs stay bit-identical across
// thread counts; per-scan sampling is as accurate as per-control sampling and keeps the NEES in its band; and
// an outlier under known association is rejected, counted, and treated exactly as clutter.
#include <algorithm>
#include <vector>

#include <gtest/gtest.h>

#include "core/engine/fastslam.h"
#include "core/metrics/run_statistics.h"
#include "experiments/run/fastslam_run.h"
#include "experiments/sim/simulator.h"
#include "tests/engine/worlds.h"
#include "variants/association/known_association.h"
#include "variants/maps/vector_map.h"
#include "variants/registry.h"

namespace arbor {
namespace {

RunConfig known(FilterVersion version, int particles, std::uint64_t seed, MotionSampling sampling) {
  RunConfig c = testing::fastslam_config(version, particles, seed, 2);
  c.options.motion_sampling = sampling;
  c.options.weight_exponent = 1.0;  // the sampling modes compared under the paper's weights, as measured
  return c;
}

// As a real log reads its odometer: no ground-truth pose between scans, so the engine composes the controls
// between two scans once for the whole set (core/models/composed_motion.h) instead of once per particle.
Scenario without_truth_between_scans(Scenario s) {
  for (ScenarioStep& step : s.steps)
    if (!step.has_scan) step.truth_pose.reset();
  return s;
}

TEST(MultiRate, SimulatorReadsTheOdometerKTimesPerScan) {
  const Scenario s = testing::simulated_world(1, 21, 0.0, 10);
  ASSERT_EQ(s.steps.size(), 1u + 20u * 10u);
  int scans = 0;
  for (const ScenarioStep& step : s.steps) scans += step.has_scan;
  EXPECT_EQ(scans, 21);
  EXPECT_TRUE(s.steps[10].has_scan);
  EXPECT_FALSE(s.steps[9].has_scan);
  EXPECT_DOUBLE_EQ(s.steps[10].time_s, 0.5);
}

TEST(MultiRate, AccumulatedCovarianceIsTheChainOfPredictions) {
  const Scenario s = without_truth_between_scans(testing::simulated_world(2, 5, 0.0, 10));
  FastSlamOptions options;
  options.particles = 8;
  options.threads = 1;
  FastSlam<VectorMap, KnownAssociation> engine(s, options);
  engine.step(s.steps[0]);  // the first scan: every particle has just drawn
  std::vector<Pose2> start;
  for (int i = 0; i < engine.particle_count(); ++i) {
    ASSERT_TRUE(engine.particle(i).pose_covariance.isZero()) << "a draw resets the prediction";
    start.push_back(engine.particle(i).pose);
  }
  for (int k = 1; k <= 9; ++k) engine.step(s.steps[k]);  // controls only: no draw
  for (int i = 0; i < engine.particle_count(); ++i) {
    Pose2 x = start[i];
    Mat3 P = Mat3::Zero();
    for (int k = 1; k <= 9; ++k) {
      const Mat3 Q = s.motion.process_noise(x, s.steps[k].control, s.steps[k].time_s - s.steps[k - 1].time_s);
      Mat3 G = Mat3::Zero();  // apply() fills it; zeroed so that gcc 12 sees no read before a write
      x = s.motion.apply(x, s.steps[k].control, &G);
      P = G * P * G.transpose() + Q;
    }
    // The engine composes the nine controls once for the set (core/models/composed_motion.h): the same
    // chain up to rounding.
    const PosePrediction p = engine.predicted_pose(i);
    EXPECT_NE(engine.particle(i).pose.x, p.pose.x) << "the controls are composed for the set, not yet applied";
    EXPECT_NEAR(p.pose.x, x.x, 1e-12);
    EXPECT_NEAR(p.pose.y, x.y, 1e-12);
    EXPECT_NEAR(p.pose.theta, x.theta, 1e-12);
    EXPECT_LT((p.pose_covariance - P).cwiseAbs().maxCoeff(), 1e-12 * P.cwiseAbs().maxCoeff()) << "particle " << i;
    EXPECT_GT(P.determinant(), 0.0);
  }
  // The estimate's covariance holds the particles' predictions, not only their spread.
  EXPECT_GT(engine.estimate().covariance.trace(), engine.predicted_pose(0).pose_covariance.trace() * 0.5);
}

TEST(MultiRate, BitIdenticalAcrossMapBackends) {
  const Scenario s = without_truth_between_scans(testing::simulated_world(6, 40, 1.0, 10));
  std::string reference;
  for (const std::string& map : map_backend_names()) {
    RunConfig c = known(FilterVersion::kFastSlam2, 20, 3, MotionSampling::kPerScan);
    c.map = map;
    c.assoc = "nn";  // ids from the filter's own decisions: creation and pruning differ per particle
    c.out_dir = testing::scratch_dir("multi_rate_map_" + map);
    run_fastslam(s, c);
    const std::string files = testing::read_file(c.out_dir + "/trajectory.tum") + testing::read_file(c.out_dir + "/map.csv");
    if (reference.empty()) reference = files;
    EXPECT_TRUE(files == reference) << map << " differs from " << map_backend_names().front();
  }
  EXPECT_GT(reference.size(), 1000u);
}

TEST(MultiRate, BitIdenticalWithOneAndTwoThreads) {
  const Scenario world = testing::simulated_world(3, 40, 0.0, 10);
  for (const Scenario& s : {world, without_truth_between_scans(world)}) {
    for (auto version : {FilterVersion::kFastSlam1, FilterVersion::kFastSlam2}) {
      std::string files[2];
      for (int t = 1; t <= 2; ++t) {
        RunConfig c = known(version, 30, 4, MotionSampling::kPerScan);
        c.options.threads = t;
        c.out_dir = testing::scratch_dir("multi_rate_threads" + std::to_string(t));
        run_fastslam(s, c);
        files[t - 1] = testing::read_file(c.out_dir + "/trajectory.tum") + testing::read_file(c.out_dir + "/map.csv");
      }
      ASSERT_GT(files[0].size(), 1000u);
      EXPECT_TRUE(files[0] == files[1]) << to_string(version);
    }
  }
}

// Per-scan sampling draws each particle once from the whole prediction and lets the FastSLAM 2.0 proposal
// correct it; per-control sampling random-walks every particle and proposes with one control's covariance.
// What per-scan sampling surely buys is consistency (the next test) and speed (deferred steps,
// composed_motion.h). Its accuracy gain is small: the motion-sampling study finds per-scan ahead at K = 10-50
// (results/engine/fc7eacd_vm_gcc-12.2.0), while on these short worlds, over seeds 1-10 at d2485e1 (150 scans,
// K = 10), per-scan wins 5 of 10 with 10 particles (median ATE 0.140 against 0.137 m) and 4 of 10 with 100
// (0.131 against 0.130 m). Until stop 54 this test asserted a win on each of seeds 1-3 (measured at d43e3e0
// on seeds 1-5), which one change in how particles draw undid; it now asserts that per-scan sampling costs
// no accuracy: its median within 1.25x of per-control's.
TEST(MultiRate, PerScanSamplingIsAsAccurateAsPerControl) {
  std::vector<double> scan_ate, control_ate;
  for (std::uint64_t seed = 1; seed <= 10; ++seed) {
    const Scenario s = testing::simulated_world(seed, 150, 0.0, 10);
    const RunOutput scan = run_fastslam(s, known(FilterVersion::kFastSlam2, 10, seed, MotionSampling::kPerScan));
    const RunOutput control = run_fastslam(s, known(FilterVersion::kFastSlam2, 10, seed, MotionSampling::kPerControl));
    scan_ate.push_back(scan.result["ate_rmse_m"].get<double>());
    control_ate.push_back(control.result["ate_rmse_m"].get<double>());
  }
  EXPECT_LE(median(scan_ate), 1.25 * median(control_ate));
  EXPECT_LT(std::ranges::max(scan_ate), 1.0) << "every per-scan run stays on the map";
}

// Consistency on a short horizon over 30 seeds (Bar-Shalom et al. 2001, §5.4: the average of 30 NEES of a
// consistent 3-dof estimator lies in [2.19, 3.93] with 95 % probability), with the odometry read 10 times
// per scan. Measured at commit time, scans 1-20, 100 particles: per-scan 1.9-3.7 (18 of 20 inside the band);
// per-control 2.4-3377 (5 inside), because its proposal sees a tenth of the prediction's covariance.
TEST(MultiRate, PerScanSamplingIsConsistentOnAShortHorizonOver30Seeds) {
  const int scans = 21;
  for (auto sampling : {MotionSampling::kPerScan, MotionSampling::kPerControl}) {
    const std::vector<double> nees = testing::average_nees_over_seeds(scans, [&](int seed) {
      return run_fastslam(testing::simulated_world(seed, scans, 0.0, 10), known(FilterVersion::kFastSlam2, 100, seed, sampling));
    });
    const int inside = static_cast<int>(std::count_if(nees.begin(), nees.end(), testing::in_nees_band));
    if (sampling == MotionSampling::kPerScan) EXPECT_GE(inside, 16) << "per-scan: steps inside the band";
    else EXPECT_LE(inside, 12) << "per-control: the test must tell the two apart";
  }
}

// An outlier 20 sigma off in range, under known association with a gate: the gate rejects it and counts it, and
// the run is bit-identical to one where that measurement is labelled clutter (which known association never
// fuses). The gate is set at 1 - 1e-9 (d^2 = 41.4), far below the outlier's d^2 of about 400: at 0.999 a true
// measurement's own chance of refusal (and the particles' overconfidence) made the count depend on the draw.
TEST(KnownGate, AnOutlierIsRejectedCountedAndTreatedAsClutter) {
  Scenario outlier = testing::simulated_world(5, 40, 0.0, 1);
  ScenarioStep& step = outlier.steps[30];
  ASSERT_FALSE(step.measurements.empty());
  Measurement& m = step.measurements.front();
  ASSERT_GE(m.truth_id, 0);
  m.range_m += 20.0 * outlier.sensor.sigma_range_m;
  Scenario clutter = outlier;
  clutter.steps[30].measurements.front().truth_id = kTruthClutter;

  RunConfig c = known(FilterVersion::kFastSlam2, 20, 1, MotionSampling::kPerScan);
  c.options.association.known_gate_probability = 1.0 - 1e-9;  // the gate is off by default (issue 41): ask for it
  c.out_dir = testing::scratch_dir("gate_outlier");
  const RunOutput a = run_fastslam(outlier, c);
  const std::string files_a = testing::read_file(c.out_dir + "/trajectory.tum") + testing::read_file(c.out_dir + "/map.csv");
  c.out_dir = testing::scratch_dir("gate_clutter");
  const RunOutput b = run_fastslam(clutter, c);
  const std::string map_b = testing::read_file(c.out_dir + "/map.csv");
  const std::string files_b = testing::read_file(c.out_dir + "/trajectory.tum") + map_b;
  EXPECT_EQ(a.result["rejected_measurements"].get<int>(), 1);
  EXPECT_EQ(b.result["rejected_measurements"].get<int>(), 0);
  EXPECT_TRUE(files_a == files_b) << "the rejected outlier changed the estimate";

  c.options.association.known_gate_probability = 1.0;  // no gate: the outlier is fused and moves the estimate
  c.out_dir = testing::scratch_dir("gate_off");
  run_fastslam(outlier, c);
  EXPECT_FALSE(testing::read_file(c.out_dir + "/map.csv") == map_b);
}

}  // namespace
}  // namespace arbor
