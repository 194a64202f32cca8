// Whole FastSLAM runs on simulated worlds: bit-identical across thread counts, consistent on short horizons
// (NEES over 30 seeds), far more accurate than dead reckoning; the result contract, and a failed rerun
// leaves no result behind; steps.csv marks the scans, and the time per scan counts the odometry between them.
#include <algorithm>
#include <filesystem>
#include <numeric>
#include <optional>

#include <gtest/gtest.h>

#include "core/io/input_error.h"
#include "core/io/trajectory_io.h"
#include "core/metrics/run_statistics.h"
#include "experiments/run/fastslam_run.h"
#include "experiments/sim/simulator.h"
#include "tests/engine/worlds.h"

namespace arbor {
namespace {

// Runs with 1 and 2 threads and compares the output files byte for byte.
void expect_identical_across_threads(const Scenario& scenario, RunConfig c, const std::string& name) {
  std::string files[2];
  for (int t = 1; t <= 2; ++t) {
    c.options.threads = t;
    c.out_dir = testing::scratch_dir(name + "_threads" + std::to_string(t));
    const RunOutput out = run_fastslam(scenario, c);
    files[t - 1] = testing::read_file(c.out_dir + "/trajectory.tum") + testing::read_file(c.out_dir + "/map.csv") +
                   testing::read_file(c.out_dir + "/trajectory_mean.tum") + out.result["ate_rmse_m"].dump() +
                   out.result["nees_mean"].dump() + out.result["landmarks"].dump();
  }
  ASSERT_GT(files[0].size(), 1000u);
  EXPECT_TRUE(files[0] == files[1]) << name << ": outputs differ between 1 and 2 threads";
}

TEST(FastSlamRun, BitIdenticalWithOneAndTwoThreads) {
  const Scenario scenario = testing::simulated_world(3, 120);
  expect_identical_across_threads(scenario, testing::fastslam_config(FilterVersion::kFastSlam2, 50, 9, 1), "fs2");
  expect_identical_across_threads(scenario, testing::fastslam_config(FilterVersion::kFastSlam1, 50, 9, 1), "fs1");
}

TEST(FastSlamRun, DifferentSeedsGiveDifferentRuns) {
  const Scenario scenario = testing::simulated_world(3, 60);
  const auto a = run_fastslam(scenario, testing::fastslam_config(FilterVersion::kFastSlam2, 20, 1, 2));
  const auto b = run_fastslam(scenario, testing::fastslam_config(FilterVersion::kFastSlam2, 20, 2, 2));
  EXPECT_NE(a.result["ate_rmse_m"], b.result["ate_rmse_m"]);
}

// Consistency (Bar-Shalom, Li & Kirubarajan 2001, §5.4): the average of 30 NEES values of a consistent 3-dof
// estimator lies in the chi2(90)/30 quantiles [2.19, 3.93] with 95% probability. FastSLAM loses consistency as
// resampling depletes the particles' histories (Bailey, Nieto & Nebot 2006), so the claim is for a short
// horizon: steps 1-20 of the default world with 100 particles (step 0 stands still at the exactly known start,
// where the particle spread is only the noise floor). Measured at commit time: 11 of 20 steps inside the band,
// the rest above it (overconfident), the worst 4.65; the longer drift is recorded in results/consistency/.
TEST(FastSlamRun, FastSlam2IsConsistentOnAShortHorizonOver30Seeds) {
  const int steps = 21;
  const std::vector<double> nees = testing::average_nees_over_seeds(steps, [&](int s) {
    return run_fastslam(testing::simulated_world(s, steps), testing::fastslam_config(FilterVersion::kFastSlam2, 100, s, 0));
  });
  const int inside = static_cast<int>(std::count_if(nees.begin(), nees.end(), testing::in_nees_band));
  const double worst = std::ranges::max(nees);
  EXPECT_GE(inside, 10) << "steps with the 30-seed NEES inside [2.19, 3.93]";
  EXPECT_LT(worst, 5.5);
}

// Dead reckoning on the default loop drifts by metres; FastSLAM with known association stays within tens
// of centimetres (measured on the simulator of d43e3e0, seeds 1-5: FastSLAM 1.0 ATE 0.05-0.43 m, 2.0
// 0.07-0.34 m, dead reckoning 3.0-17.2 m). With its tempered weights (the default with known association,
// FastSlamOptions::effective_weight_exponent) FastSLAM 2.0's plain ATE on seeds 1-8 is lower on six and higher
// on two; the closest to the 15 % bound is seed 1 at 0.35 m for 2.95 m (with the paper's weights 0.14 m): the
// set keeps more of the rotation about the start that no scan observes, while its aligned ATE falls from 0.054
// to 0.043 m. Seeds 1-3 here keep the test short under the sanitizers.
TEST(FastSlamRun, AteIsFarBelowDeadReckoning) {
  for (int s = 1; s <= 3; ++s) {
    for (auto version : {FilterVersion::kFastSlam1, FilterVersion::kFastSlam2}) {
      const RunOutput out = run_fastslam(testing::simulated_world(s, 500), testing::fastslam_config(version, 100, s, 0));
      const double ate = out.result["ate_rmse_m"].get<double>();
      const double dr = out.result["dead_reckoning_ate_m"].get<double>();
      EXPECT_LT(ate, 0.15 * dr) << "seed " << s << " " << to_string(version);
      EXPECT_LT(ate, 0.6) << "seed " << s << " " << to_string(version);
      EXPECT_LT(out.result["landmark_rmse_m"].get<double>(), 0.6);
    }
  }
}

TEST(FastSlamRun, ResultHoldsTheContractFields) {
  RunConfig c = testing::fastslam_config(FilterVersion::kFastSlam2, 10, 1, 1);
  const RunOutput out = run_fastslam(testing::simulated_world(1, 20), c);
  for (const char* key : {"config", "ate_rmse_m", "landmark_rmse_m", "nees_mean", "assoc_precision", "assoc_recall",
                          "assoc_f1", "landmarks", "steps", "step_time_median_s", "step_time_p95_s", "wall_time_s",
                          "peak_rss_bytes"})
    EXPECT_TRUE(out.result.contains(key)) << key;
  for (const char* key : {"filter", "map", "assoc", "particles", "seed", "threads", "commit", "host", "compiler"})
    EXPECT_TRUE(out.result["config"].contains(key)) << key;
}

// The time per scan adds the odometry-only steps since the previous scan to the scan's own step, and drops
// the steps after the last scan: on a real log the time per step is mostly an odometry step's.
TEST(FastSlamRun, PerScanTimesAddTheOdometryStepsBeforeEachScan) {
  const auto step = [](double time_s, bool scan) { StepRecord r; r.step_time_s = time_s; r.scan = scan; return r; };
  const std::vector<double> times =
      per_scan_times({step(1.0, false), step(2.0, false), step(4.0, true), step(8.0, true), step(16.0, false)});
  EXPECT_EQ(times, (std::vector<double>{7.0, 8.0}));
  EXPECT_TRUE(per_scan_times({step(1.0, false)}).empty());
}

// A world with three odometry readings per scan: steps.csv marks the scans, and result.json times them.
TEST(FastSlamRun, StepsCsvMarksScansAndTheResultTimesThem) {
  RunConfig c = testing::fastslam_config(FilterVersion::kFastSlam2, 10, 1, 1);
  c.out_dir = testing::scratch_dir("per_scan_time");
  const Scenario scenario = testing::simulated_world(1, 20, 0.0, 3);
  const RunOutput out = run_fastslam(scenario, c);
  const auto scans = std::count_if(scenario.steps.begin(), scenario.steps.end(), [](const ScenarioStep& s) { return s.has_scan; });
  ASSERT_GT(scenario.steps.size(), static_cast<std::size_t>(scans));
  EXPECT_EQ(out.result["scans"].get<long>(), scans);
  const std::vector<double> times = per_scan_times(out.steps);
  EXPECT_EQ(out.result["scan_time_median_s"].get<double>(), quantile(times, 0.5));
  EXPECT_EQ(out.result["scan_time_p90_s"].get<double>(), quantile(times, 0.9));
  const std::string csv = testing::read_file(c.out_dir + "/steps.csv");
  EXPECT_TRUE(csv.starts_with("step,time_s,step_time_s,n_eff,resampled,landmarks,hypotheses,nees,relocalized,scan\n"));
  long marked = 0;
  for (std::size_t at = csv.find('\n'); (at = csv.find('\n', at + 1)) != std::string::npos;) marked += csv[at - 1] == '1';
  EXPECT_EQ(marked, scans);
}

// --record-lineage adds steps.csv's last column and changes nothing else. One particle's path always shares
// its newest pose with itself (age 0); particles that never resample (no measurements: equal weights) keep
// the paths of their own initial draws, which share nothing (empty); on a world with landmarks the set
// resamples, and an age is never more than the time since the start.
TEST(FastSlamRun, TheLineageAgeIsHowFarBackTheParticlesPathsMeet) {
  const Scenario world = testing::simulated_world(1, 200, 0.0, 1);
  Scenario empty = world;
  for (ScenarioStep& step : empty.steps) step.measurements.clear();
  const auto ages = [](const Scenario& scenario, int particles, bool record, std::string* files = nullptr) {
    RunConfig c = testing::fastslam_config(FilterVersion::kFastSlam2, particles, 1, 1);
    c.options.weight_exponent = 1.0;  // the paper's weights resample often enough for the paths to meet here
    c.record_lineage = record;
    c.out_dir = testing::scratch_dir("lineage_" + std::to_string(particles) + (record ? "_on" : "_off"));
    const RunOutput out = run_fastslam(scenario, c);
    const std::string steps = testing::read_file(c.out_dir + "/steps.csv");
    EXPECT_EQ(steps.substr(0, steps.find('\n')).ends_with(",scan,ancestor_age_s"), record);
    if (files) *files = testing::read_file(c.out_dir + "/trajectory.tum") + testing::read_file(c.out_dir + "/map.csv");
    std::vector<std::optional<double>> at_scans;
    for (const StepRecord& s : out.steps)
      if (s.scan) at_scans.push_back(s.ancestor_age_s);
    return at_scans;
  };
  for (const auto& age : ages(world, 1, true)) EXPECT_EQ(age, std::optional<double>(0.0));
  for (const auto& age : ages(empty, 20, true)) EXPECT_FALSE(age.has_value());
  std::string on, off;
  const auto shared = ages(world, 20, true, &on);
  ages(world, 20, false, &off);
  EXPECT_EQ(on, off);
  EXPECT_GT(std::count_if(shared.begin(), shared.end(), [](const auto& a) { return a.has_value(); }), 0);
  const double run_time = world.steps.back().time_s - world.start_time_s;
  for (const auto& age : shared)
    if (age) {
      EXPECT_GE(*age, 0.0);
      EXPECT_LE(*age, run_time);
    }
}

// Known association scored from its record like any strategy: it never pairs wrongly, and every measurement
// it leaves unpaired while the map holds its landmark is one its gate rejected.
TEST(FastSlamRun, KnownAssociationScoresPerfectPrecisionAndMissesOnlyWhatItsGateRejects) {
  RunConfig c = testing::fastslam_config(FilterVersion::kFastSlam2, 10, 1, 1);
  c.options.association.known_gate_probability = 0.9;  // rejects about one measurement in ten
  const RunOutput out = run_fastslam(testing::simulated_world(1, 60), c);
  const auto& counts = out.result["assoc_counts"];
  EXPECT_EQ(out.result["assoc_precision"].get<double>(), 1.0);
  EXPECT_EQ(counts["false_matches"].get<int>(), 0);
  EXPECT_EQ(counts["false_new"].get<int>(), 0);
  EXPECT_GT(out.result["rejected_measurements"].get<int>(), 0);
  EXPECT_EQ(counts["missed_matches"].get<int>(), out.result["rejected_measurements"].get<int>());
  const int started = out.result["landmarks"].get<int>() + out.result["provisional_landmarks"].get<int>();
  EXPECT_EQ(counts["true_matches"].get<int>() + counts["missed_matches"].get<int>() + started, counts["scored"].get<int>());
}

// A rerun into a directory that holds a finished run forgets that run first: were its result.json left, a
// rerun that fails (here on an unknown map back end) would leave a directory that looks finished.
TEST(FastSlamRun, ARerunThatFailsLeavesNoResultBehind) {
  RunConfig c = testing::fastslam_config(FilterVersion::kFastSlam2, 5, 1, 1);
  c.out_dir = testing::scratch_dir("rerun_fails");
  run_fastslam(testing::simulated_world(1, 10), c);
  ASSERT_TRUE(std::filesystem::exists(c.out_dir + "/result.json"));
  c.map = "no-such-map";
  EXPECT_THROW(run_fastslam(testing::simulated_world(1, 10), c), InputError);
  EXPECT_FALSE(std::filesystem::exists(c.out_dir + "/result.json"));
}

}  // namespace
}  // namespace arbor
