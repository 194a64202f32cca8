// One FastSLAM run from a scenario to its result files (DESIGN.md §9): DIR/result.json, DIR/trajectory.tum
// (best particle), DIR/trajectory_mean.tum (weighted mean), DIR/map.csv (best particle's map),
// DIR/associations.csv (best particle's decisions) and DIR/steps.csv (per-step time, N_eff, landmarks, NEES).
#ifndef ARBOR_EXPERIMENTS_RUN_FASTSLAM_RUN_H_
#define ARBOR_EXPERIMENTS_RUN_FASTSLAM_RUN_H_

#include <string>

#include <nlohmann/json.hpp>

#include "core/engine/fastslam_options.h"
#include "core/types/scenario.h"

namespace arbor {

struct RunConfig {
  std::string scenario_path;  // recorded in the result; the scenario itself is passed in
  std::string map = "naive";
  std::string assoc = "known";
  FastSlamOptions options;
  std::string out_dir;        // empty: compute the metrics but write no files
  bool progress = false;      // a progress line on stderr
};

struct RunOutput {
  nlohmann::json result;      // what result.json holds
  std::vector<double> nees;   // per step with a truth pose
};

// Runs the filter over every step of the scenario and computes the metrics. Throws InputError for invalid
// names or options.
RunOutput run_fastslam(const Scenario& scenario, const RunConfig& config);

}  // namespace arbor

#endif  // ARBOR_EXPERIMENTS_RUN_FASTSLAM_RUN_H_
