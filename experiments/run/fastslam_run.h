// One FastSLAM run from a scenario to its result files (DESIGN.md §9): DIR/result.json, DIR/trajectory.tum
// (best particle), DIR/trajectory_mean.tum (weighted mean), DIR/map.csv (best particle's map),
// DIR/associations.csv (best particle's decisions), DIR/steps.csv (per-step time, N_eff, landmarks, NEES,
// whether it held a scan) and, where the scenario has a ground truth or GPS track, DIR/reference.tum
// (experiments/run/reference_trajectory.h).
#ifndef ARBOR_EXPERIMENTS_RUN_FASTSLAM_RUN_H_
#define ARBOR_EXPERIMENTS_RUN_FASTSLAM_RUN_H_

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/engine/fastslam_options.h"
#include "core/engine/filter.h"
#include "core/types/landmark.h"
#include "core/types/scenario.h"
#include "core/types/step_decisions.h"
#include "core/types/timed_pose.h"
#include "experiments/options/run_config.h"

namespace arbor {

// One row of steps.csv: the step's time, the wall time it took, the filter's own account of it, its NEES.
struct StepRecord {
  double time_s = 0.0;
  double step_time_s = 0.0;
  StepStats stats;             // Filter::last_step_stats
  std::optional<double> nees;  // at steps with a truth pose
  bool scan = false;           // the step carried a scan (real logs have many odometry-only steps)
  // RunConfig::record_lineage: seconds back to the newest pose every particle's path shares (empty: none yet).
  std::optional<double> ancestor_age_s;
};

// Everything a run leaves: write_run_files turns it into the files of DESIGN.md §9.
struct RunOutput {
  nlohmann::json result;                 // what result.json holds
  std::vector<double> nees;              // per scan with a truth pose (and some pose uncertainty)
  std::vector<TimedPose> trajectory;       // the reported path: the particles' paths' weighted mean
  std::vector<TimedPose> best_trajectory;  // the best particle's path (its map and decisions go with it)
  std::vector<TimedPose> mean_trajectory;  // the weighted mean, at the start and at every scan or truth pose
  std::vector<TimedPose> reference;        // what the ATE is measured against; empty without truth or GPS
  std::vector<Landmark> map;             // the best particle's confirmed landmarks, ascending id
  std::vector<StepDecisions> decisions;  // the best particle's
  std::vector<StepRecord> steps;         // one per scenario step
  bool lineage_recorded = false;         // RunConfig::record_lineage: steps.csv gains ancestor_age_s
};

// The filter's time per scan: for each step that carried a scan, the summed step time of the odometry-only
// steps since the previous scan and of the scan's own step. On a real log a scan follows many odometry steps,
// so the time per step understates what keeping up with the sensor costs; steps after the last scan are no
// scan's work and are left out.
std::vector<double> per_scan_times(const std::vector<StepRecord>& steps);

// The filter a run uses: the config's variants and options, started from its prior map when it names one
// (arbor.Filter steps the same filter by hand).
std::unique_ptr<Filter> make_run_filter(const Scenario& scenario, const RunConfig& config);

// Runs the filter over every step of the scenario and computes the metrics; writes the result files when
// config.out_dir is set. Throws InputError for invalid names or options.
RunOutput run_fastslam(const Scenario& scenario, const RunConfig& config);

// Writes DIR/trajectory.tum, trajectory_mean.tum, reference.tum, map.csv, steps.csv, associations.csv, and
// result.json last.
void write_run_files(const RunOutput& output, const std::string& dir);

}  // namespace arbor

#endif  // ARBOR_EXPERIMENTS_RUN_FASTSLAM_RUN_H_
