// `arbor smooth`'s pipeline: result files with the fields of `arbor run` plus the solver's, the g2o export,
// and association decisions read from a FastSLAM result directory (with errors naming file, line and field).
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <unistd.h>

#include "core/io/input_error.h"
#include "core/io/scenario_format.h"
#include "experiments/run/fastslam_run.h"
#include "experiments/run/smooth_run.h"
#include "experiments/sim/simulator.h"

namespace arbor {
namespace {

std::string fresh_dir(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / ("arbor_smooth_run_" + std::to_string(::getpid()) + "_" + name);
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir.string();
}

Scenario small_world() {
  SimulationOptions sim;
  sim.world.landmarks = 40;
  sim.steps = 60;
  return simulate(sim);
}

// A small FastSLAM run (20 particles, one thread) with this association of the small world written to
// DIR/scenario.txt, its files in DIR/fastslam: the decisions a smoother is given. Returns the run's config.
RunConfig small_fastslam_run(const std::string& dir, const std::string& assoc) {
  write_scenario(small_world(), dir + "/scenario.txt");
  RunConfig run;
  run.assoc = assoc;
  run.options.particles = 20;
  run.options.threads = 1;
  run.options.association.known_gate_probability = 1.0;  // no gate: with known association every measurement
                                                         // with an id is paired, as the truth's
  run.out_dir = dir + "/fastslam";
  run_fastslam(read_scenario(dir + "/scenario.txt"), run);
  return run;
}

TEST(SmoothRun, WritesResultFilesWithTheRunFieldsAndTheSolverFields) {
  const std::string dir = fresh_dir("files");
  write_scenario(small_world(), dir + "/scenario.txt");
  SmoothConfig config;
  config.scenario_path = dir + "/scenario.txt";
  config.g2o_path = dir + "/problem.g2o";
  config.out_dir = dir + "/out";
  const SmoothOutput out = run_smoother(config);
  for (const char* f : {"result.json", "trajectory.tum", "map.csv"})
    EXPECT_TRUE(std::filesystem::exists(config.out_dir + "/" + f)) << f;
  EXPECT_TRUE(std::filesystem::exists(config.g2o_path));
  std::ifstream in(config.out_dir + "/result.json");
  const nlohmann::json r = nlohmann::json::parse(in);
  for (const char* key : {"config", "ate_rmse_m", "ate_aligned_rmse_m", "landmark_rmse_m", "nees_mean", "assoc_precision",
                          "assoc_recall", "assoc_f1", "landmarks", "steps", "step_time_median_s", "step_time_p95_s",
                          "wall_time_s", "peak_rss_bytes", "solve_time_s", "iterations", "initial_cost", "final_cost",
                          "termination"})
    EXPECT_TRUE(r.contains(key)) << key;
  EXPECT_EQ(r["termination"], "CONVERGENCE");
  EXPECT_LT(r["ate_rmse_m"].get<double>(), r["dead_reckoning_ate_m"].get<double>());
  EXPECT_LT(r["landmark_rmse_m"].get<double>(), 0.5);
  EXPECT_EQ(r["config"]["associations"], "known");
}

TEST(SmoothRun, ReadsAssociationDecisions) {
  const Scenario s = small_world();
  const std::string dir = fresh_dir("decisions");
  int first = -1;
  for (std::size_t k = 0; k < s.steps.size() && first < 0; ++k)
    if (!s.steps[k].measurements.empty()) first = static_cast<int>(k);
  ASSERT_GE(first, 0);
  std::ofstream(dir + "/associations.csv") << "step,measurement,landmark\n" << first << ",0,17\n";
  const SmootherAssociations a = read_association_decisions(dir, s);
  EXPECT_EQ(a.landmark_ids[first][0], 17);
  EXPECT_EQ(a.associated_count(), 1u);

  std::ofstream(dir + "/associations.csv") << "step,measurement,landmark\n" << first << ",999,17\n";
  try {
    read_association_decisions(dir, s);
    FAIL() << "no error for a measurement index out of range";
  } catch (const InputError& e) {
    EXPECT_EQ(e.line(), 2);
    EXPECT_EQ(e.field(), "measurement");
  }
  EXPECT_THROW(read_association_decisions(fresh_dir("empty"), s), InputError);
}

// A FastSLAM run with known association decides exactly what the ground truth says (clutter spurious, every
// other measurement its landmark), only under the run's own landmark ids: smoothing with its decisions must
// build the same problem, so the same cost and the same trajectory.
TEST(SmoothRun, AKnownAssociationRunsDecisionsAreTheTruthRenamed) {
  const std::string dir = fresh_dir("known_run");
  const RunConfig run = small_fastslam_run(dir, "known");

  SmoothConfig config;
  config.scenario_path = dir + "/scenario.txt";
  const SmoothOutput truth = run_smoother(config);
  config.associations = run.out_dir;
  config.init = "dead-reckoning";  // as the truth's run; by default it would start from the FastSLAM run
  const SmoothOutput decided = run_smoother(config);
  EXPECT_EQ(decided.result["associations_used"], truth.result["associations_used"]);
  EXPECT_GT(decided.result["associations_used"].get<int>(), 0);
  EXPECT_EQ(decided.smoother.summary.final_cost, truth.smoother.summary.final_cost);
  EXPECT_EQ(decided.result["ate_rmse_m"], truth.result["ate_rmse_m"]);
  EXPECT_EQ(decided.result["landmark_rmse_m"], truth.result["landmark_rmse_m"]);
}

// With a real strategy the decisions cover every measurement of every scan, name landmarks of the run's map
// or -1, and the smoother given them (starting, by default, from the run's trajectory) beats dead reckoning.
TEST(SmoothRun, NearestNeighbourDecisionsCoverEveryMeasurementAndSolve) {
  const std::string dir = fresh_dir("nn_run");
  const RunConfig run = small_fastslam_run(dir, "nn");
  const Scenario s = read_scenario(dir + "/scenario.txt");

  const SmootherAssociations decisions = read_association_decisions(run.out_dir, s);
  std::size_t measurements = 0, rows = 0;
  for (std::size_t k = 0; k < s.steps.size(); ++k) {
    measurements += s.steps[k].measurements.size();
    for (std::int64_t id : decisions.landmark_ids[k]) rows += id >= 0;
  }
  std::ifstream csv(run.out_dir + "/associations.csv");
  std::size_t lines = 0;
  for (std::string line; std::getline(csv, line);) ++lines;
  EXPECT_EQ(lines, measurements + 1);  // the header and one row per measurement
  EXPECT_EQ(decisions.associated_count(), rows);
  EXPECT_GT(rows, measurements / 2);

  SmoothConfig config;
  config.scenario_path = dir + "/scenario.txt";
  config.associations = run.out_dir;
  const SmoothOutput out = run_smoother(config);
  EXPECT_EQ(out.result["config"]["init"], run.out_dir);
  EXPECT_TRUE(out.smoother.summary.usable);
  EXPECT_LT(out.result["ate_rmse_m"].get<double>(), out.result["dead_reckoning_ate_m"].get<double>());
}

}  // namespace
}  // namespace arbor
