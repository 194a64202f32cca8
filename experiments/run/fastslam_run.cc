// The FastSLAM run pipeline: filter over the scenario, metrics, result files.
#include "experiments/run/fastslam_run.h"

#include <chrono>
#include <filesystem>

#include <fmt/core.h>

#include "core/engine/numerical_breakdown.h"
#include "core/io/atomic_file.h"
#include "core/io/input_error.h"
#include "core/io/memory_budget.h"
#include "core/io/trajectory_io.h"
#include "core/metrics/decision_score.h"
#include "core/metrics/run_statistics.h"
#include "core/metrics/trajectory_metrics.h"
#include "experiments/options/run_options.h"
#include "experiments/run/progress.h"
#include "experiments/run/reference_trajectory.h"
#include "experiments/run/result_fields.h"
#include "variants/registry.h"

namespace arbor {
namespace {

using Json = nlohmann::json;

// The format `arbor smooth --associations DIR` reads (experiments/run/smooth_run.h).
std::string associations_csv(const std::vector<StepDecisions>& decisions) {
  std::string out = "step,measurement,landmark\n";
  for (const StepDecisions& d : decisions)
    for (std::size_t j = 0; j < d.landmarks.size(); ++j) fmt::format_to(std::back_inserter(out), "{},{},{}\n", d.step, j, d.landmarks[j]);
  return out;
}

// ancestor_age_s, with --record-lineage only, is the last column: every other run's file stays as it was.
std::string steps_csv(const std::vector<StepRecord>& steps, bool with_lineage) {
  std::string out = "step,time_s,step_time_s,n_eff,resampled,landmarks,hypotheses,nees,relocalized,scan";
  out += with_lineage ? ",ancestor_age_s\n" : "\n";
  for (std::size_t k = 0; k < steps.size(); ++k) {
    const StepRecord& s = steps[k];
    fmt::format_to(std::back_inserter(out), "{},{},{:.9f},{},{},{},{},{},{},{}", k, s.time_s, s.step_time_s,
                   s.stats.n_eff, s.stats.resampled ? 1 : 0, s.stats.best_landmarks, s.stats.hypotheses,
                   s.nees ? fmt::format("{}", *s.nees) : "", s.stats.relocalized ? 1 : 0, s.scan ? 1 : 0);
    if (with_lineage) {
      out += ',';
      if (s.ancestor_age_s) fmt::format_to(std::back_inserter(out), "{}", *s.ancestor_age_s);
    }
    out += "\n";
  }
  return out;
}

// A map a run starts from: every landmark confirmed (the filter reports only confirmed ones, and a known map
// is not on probation), started at scan 0.
std::vector<Landmark> read_prior_map(const std::string& path) {
  std::vector<Landmark> map = read_map_csv(path);
  for (Landmark& lm : map) {
    lm.confirmed = true;
    lm.born_scan = 0;
  }
  return map;
}

}  // namespace

std::vector<double> per_scan_times(const std::vector<StepRecord>& steps) {
  std::vector<double> times;
  double since_last_scan = 0.0;
  for (const StepRecord& s : steps) {
    since_last_scan += s.step_time_s;
    if (!s.scan) continue;
    times.push_back(since_last_scan);
    since_last_scan = 0.0;
  }
  return times;
}

std::unique_ptr<Filter> make_run_filter(const Scenario& scenario, const RunConfig& config) {
  // 3.3 KB a particle before any landmark (peak RSS 344 MB at 10^5 particles on a 5-step world, tree map):
  // 10^6 particles on a small machine ended in std::bad_alloc.
  if (cli::filter_traits(config).has_particles)
    require_memory(config.options.particles, 3000.0, "particles", "particles");
  std::unique_ptr<Filter> filter = make_filter(config.map, config.assoc, scenario, config.options);
  if (!config.prior_map_path.empty()) filter->set_prior_map(read_prior_map(config.prior_map_path));
  return filter;
}

RunOutput run_fastslam(const Scenario& scenario, const RunConfig& config) {
  const auto wall_start = std::chrono::steady_clock::now();
  prepare_run_directory(config.out_dir);
  std::unique_ptr<Filter> filter = make_run_filter(scenario, config);

  RunOutput out;
  std::vector<double> step_times;
  step_times.reserve(scenario.steps.size());
  out.steps.reserve(scenario.steps.size());
  out.lineage_recorded = config.record_lineage;
  std::vector<TimedPose>& mean_trajectory = out.mean_trajectory;
  mean_trajectory.push_back({scenario.start_time_s, filter->estimate().mean});
  double n_eff_sum = 0.0;
  std::int64_t resamples = 0, hypotheses = 0, tests = 0, budget_exhausted = 0, moves_proposed = 0, moves_accepted = 0;
  Progress progress(fmt::format("run {}/{}", cli::filter_traits(config).has_map_backends ? fmt::format("{}/{}", to_string(config.options.version), config.map)
                                                                     : std::string(to_string(config.options.version)),
                                config.assoc),
                    static_cast<std::int64_t>(scenario.steps.size()), config.progress);

  for (std::size_t k = 0; k < scenario.steps.size(); ++k) {
    const ScenarioStep& step = scenario.steps[k];
    const auto t0 = std::chrono::steady_clock::now();
    try {
      filter->step(step);
    } catch (const NumericalBreakdown& e) {
      // Motion noise or controls inside the format's limits can still be too large for the filter's double
      // precision (hostile A1, A2); the scenario's figures are the cause, so they are named, not the engine.
      throw InputError(config.scenario_path, step.source_line, "step",
                       fmt::format("the {} filter's arithmetic broke down at step {} (t = {} s): {}; the scenario's "
                                   "motion noise or controls are too large for it",
                                   to_string(config.options.version), k, step.time_s, e.what()));
    }
    const double dt = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    step_times.push_back(dt);
    const StepStats& stats = filter->last_step_stats();
    n_eff_sum += stats.n_eff;
    resamples += stats.resampled;
    hypotheses += stats.hypotheses;
    tests += stats.tests;
    budget_exhausted += stats.budget_exhausted;
    moves_proposed += stats.moves_proposed;
    moves_accepted += stats.moves_accepted;
    StepRecord& record = out.steps.emplace_back(StepRecord{step.time_s, dt, stats, std::nullopt, step.has_scan, std::nullopt});
    if (config.record_lineage && step.has_scan)
      if (const auto shared = filter->common_ancestor_time_s()) record.ancestor_age_s = step.time_s - *shared;
    if (step.has_scan || step.truth_pose) {
      const PoseEstimate estimate = filter->estimate();
      mean_trajectory.push_back({step.time_s, estimate.mean});
      if (step.truth_pose) {
        const double nees = pose_nees(estimate.mean, estimate.covariance, *step.truth_pose);
        // At an exactly known pose (the start, with no initial uncertainty) the NEES is 0/0, not a figure.
        if (step.has_scan && estimate.covariance.trace() > 1e-9) out.nees.push_back(nees);
        record.nees = nees;
      }
    }
    progress.update(static_cast<std::int64_t>(k + 1), [&] { return fmt::format("{} landmarks", stats.best_landmarks); });
    if (config.after_step) config.after_step();
  }
  progress.finish();

  // The reported path is the posterior mean over the particles' whole paths (Filter::path_mean_trajectory);
  // the best particle's, which its map and decisions belong to, is scored beside it.
  const std::vector<TimedPose>& trajectory = out.trajectory = filter->path_mean_trajectory();
  out.best_trajectory = filter->best_trajectory();
  out.reference = reference_trajectory(scenario);
  // The filter's map is its confirmed landmarks; provisional ones are counted apart.
  std::vector<Landmark>& map = out.map = filter->best_map();
  const std::size_t provisional_landmarks = std::erase_if(map, [](const Landmark& lm) { return !lm.confirmed; });
  const std::vector<StepDecisions>& decisions = out.decisions = filter->best_decisions();
  const AssociationCounts counts = score_decisions(decisions, scenario);
  const MapMemoryStats memory = filter->memory_stats();

  const EvaluationTruth truth = evaluation_truth(scenario);
  const auto ate_mean = absolute_trajectory_error(mean_trajectory, truth.positions, truth.align);
  // A filter without particles (EKF-SLAM) is one estimate: its "per particle" figures are its own.
  const std::size_t particles = cli::filter_traits(config).has_particles ? static_cast<std::size_t>(config.options.particles) : 1;

  Json& r = out.result;
  r["config"] = cli::run_config_json(config);  // every run option, under the name the command line gives it
  r["config"].update(provenance());
  r["scenario"] = scenario.metadata;
  r.update(accuracy_fields(scenario, truth, trajectory, map));
  r["ate_mean_rmse_m"] = ate_mean ? Json(ate_mean->rmse_m) : Json(nullptr);
  const TrajectoryErrors best = trajectory_errors(truth, out.best_trajectory);
  r["ate_best_rmse_m"] = best.rmse_m;
  r["ate_best_aligned_rmse_m"] = best.aligned_rmse_m;
  // The pose NEES at scan steps: the mean is kept for comparison but a few collapse episodes dominate it;
  // the median and the share of scans inside the two-sided 95 % chi-square(3) band say more.
  r["nees_mean"] = mean_or_null(out.nees);
  r["nees_median"] = out.nees.empty() ? Json(nullptr) : Json(quantile(out.nees, 0.5));
  r["nees_in_band_fraction"] = out.nees.empty() ? Json(nullptr) : Json(fraction_in_band(out.nees, kNeesBand3Dof95));
  const auto horizon = consistency_horizon(out.nees);
  r["consistency_horizon_scan"] = horizon ? Json(*horizon) : Json(nullptr);
  r["consistency_horizon_fraction"] = horizon ? Json(double(*horizon) / out.nees.size()) : Json(nullptr);
  r["rejected_measurements"] = filter->best_rejected_measurements();
  r["loop_closures"] = filter->best_loop_closures();
  r["assoc_precision"] = optional_number(counts.precision());
  r["assoc_recall"] = optional_number(counts.recall());
  r["assoc_f1"] = optional_number(counts.f1());
  r["assoc_counts"] = {{"true_matches", counts.true_matches}, {"false_matches", counts.false_matches},
                       {"missed_matches", counts.missed_matches}, {"false_new", counts.false_new},
                       {"scored", counts.scored}};
  r["landmarks"] = map.size();
  r["provisional_landmarks"] = provisional_landmarks;
  r["spurious_landmarks"] = counts.scored > 0 ? Json(spurious_landmarks(map)) : Json(nullptr);
  r["true_landmarks"] = scenario.truth_landmarks.size();
  r["observed_true_landmarks"] = counts.scored > 0 ? Json(observed_true_landmarks(scenario)) : Json(nullptr);
  r["steps"] = scenario.steps.size();
  r["scenario_duration_s"] = scenario.steps.empty() ? 0.0 : scenario.steps.back().time_s - scenario.start_time_s;
  r["step_time_median_s"] = quantile(step_times, 0.5);
  r["step_time_p95_s"] = quantile(step_times, 0.95);
  // What keeping up with the sensor costs: on a real log a step is mostly an odometry reading, not a scan.
  const std::vector<double> scan_times = per_scan_times(out.steps);
  r["scans"] = scan_times.size();
  r["scan_time_median_s"] = scan_times.empty() ? Json(nullptr) : Json(quantile(scan_times, 0.5));
  r["scan_time_p90_s"] = scan_times.empty() ? Json(nullptr) : Json(quantile(scan_times, 0.9));
  r["n_eff_mean"] = scenario.steps.empty() ? 0.0 : n_eff_sum / scenario.steps.size();
  r["resamples"] = resamples;
  r["hypotheses"] = hypotheses;
  r["compatibility_tests"] = tests;
  r["budget_exhausted"] = budget_exhausted;
  r["relocalizations"] = filter->relocalizations();
  // Resample-move's acceptance rate (null when off): near 0 its proposals are too bold, near 1 too timid.
  r["move_acceptance"] = moves_proposed > 0 ? Json(double(moves_accepted) / moves_proposed) : Json(nullptr);
  r["map_bytes_per_particle"] = memory.bytes / particles;
  r["map_shared_fraction"] = memory.bytes ? double(memory.shared_bytes) / memory.bytes : 0.0;
  r["wall_time_s"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  r["peak_rss_bytes"] = peak_rss_bytes();

  if (!config.out_dir.empty()) write_run_files(out, config.out_dir);
  return out;
}

void write_run_files(const RunOutput& output, const std::string& out_dir) {
  forget_finished_run(out_dir);
  std::filesystem::create_directories(out_dir);
  const std::string dir = out_dir + "/";
  write_tum(dir + "trajectory.tum", output.trajectory);
  write_tum(dir + "trajectory_best.tum", output.best_trajectory);
  write_tum(dir + "trajectory_mean.tum", output.mean_trajectory);
  write_reference_tum(output.reference, out_dir);
  write_map_csv(dir + "map.csv", output.map);
  write_file_atomically(dir + "steps.csv", steps_csv(output.steps, output.lineage_recorded));
  write_file_atomically(dir + "associations.csv", associations_csv(output.decisions));
  // result.json last: its presence means the run finished and every other file is complete.
  write_file_atomically(dir + "result.json", output.result.dump(2) + "\n");
}

}  // namespace arbor
