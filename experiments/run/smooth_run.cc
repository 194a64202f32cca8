// The smoother run pipeline: associations and initial values in, Ceres solve, metrics and result files out.
#ifdef ARBOR_HAVE_SMOOTHER
#include "experiments/run/smooth_run.h"

#include <chrono>
#include <filesystem>
#include <limits>
#include <unordered_map>

#include <fmt/core.h>

#include "core/io/atomic_file.h"
#include "core/io/input_error.h"
#include "core/io/scenario_format.h"
#include "core/io/text_reader.h"
#include "core/io/trajectory_io.h"
#include "core/metrics/run_statistics.h"
#include "core/metrics/trajectory_metrics.h"
#include "experiments/run/reference_trajectory.h"
#include "experiments/run/result_fields.h"
#include "variants/smoothing/g2o_writer.h"
#include "experiments/loaders/isam_factor_graph.h"

namespace arbor {
namespace {

using Json = nlohmann::json;

// The run's trajectory, and its map (run_map: the associations' run's map.csv, already read) where the
// associations come from the same run: landmark ids are the run's own, so only then do they match. With its
// map, the path is the best particle's (trajectory_best.tum), the one that map was built along.
SmootherInitialGuess read_initial_guess(const std::string& dir, const std::vector<Landmark>* run_map) {
  SmootherInitialGuess guess;
  const std::string best = dir + "/trajectory_best.tum";
  const std::string path = run_map && std::filesystem::exists(best) ? best : dir + "/trajectory.tum";
  for (const TimedPose& p : read_tum(path)) guess.trajectory.push_back({p.time_s, p.pose});
  std::stable_sort(guess.trajectory.begin(), guess.trajectory.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  if (run_map)
    for (const Landmark& l : *run_map) guess.landmarks[l.id] = l.mean;
  return guess;
}

Json summary_json(const SmootherSummary& s) {
  return {{"solve_time_s", s.solve_time_s},     {"solve_cpu_s", s.solve_cpu_s},
          {"build_time_s", s.build_time_s},
          {"iterations", s.iterations},         {"initial_cost", s.initial_cost},
          {"final_cost", s.final_cost},         {"termination", s.termination},
          {"solution_usable", s.usable},        {"gradient_max_norm", s.gradient_max_norm},
          {"linear_solver_used", s.linear_solver}, {"poses", s.poses},
          {"landmarks", s.landmarks},           {"factors", s.factors},
          {"residuals", s.residuals},           {"parameters", s.parameters},
          {"pose_marginals", s.pose_marginals}, {"marginals_time_s", s.marginals_time_s}};
}

// The smoothed poses (one per scan) with the steps between them filled in: the controls composed forward from
// the earlier pose, and the mismatch at the later one spread linearly in time, so the evaluation at Vicon or
// GPS times follows the path the controls describe rather than a straight line between scans.
std::vector<TimedPose> densify_trajectory(const Scenario& scenario, const std::vector<SmoothedPose>& poses) {
  std::vector<TimedPose> out;
  for (std::size_t i = 0; i < poses.size(); ++i) {
    const SmoothedPose& b = poses[i];
    const bool chained = i > 0 && b.step >= 0 && b.step < static_cast<int>(scenario.steps.size()) && poses[i - 1].step < b.step;
    if (chained) {
      const SmoothedPose& a = poses[i - 1];
      std::vector<TimedPose> between;
      Pose2 x = a.pose;
      for (int k = a.step + 1; k <= b.step; ++k) {
        x = scenario.motion.apply(x, scenario.steps[k].control);
        if (k < b.step) between.push_back({scenario.steps[k].time_s, x});
      }
      const Vec3 mismatch = pose_error(b.pose, x);
      const double span = b.time_s - a.time_s;
      for (TimedPose& p : between) {
        const double f = span > 0.0 ? (p.time_s - a.time_s) / span : 1.0;
        p.pose = Pose2::from_vector(p.pose.vector() + f * mismatch);
        out.push_back(p);
      }
    }
    out.push_back({b.time_s, b.pose});
  }
  return out;
}

}  // namespace

SmootherAssociations read_association_decisions(const std::string& dir, const Scenario& scenario) {
  const std::string path = dir + "/associations.csv";
  if (!std::filesystem::exists(path))
    throw InputError(path, 0, "", "no association decisions here (expected a FastSLAM result directory written by "
                                  "`arbor run` with associations.csv)");
  SmootherAssociations a;
  a.source = path;
  a.landmark_ids.resize(scenario.steps.size());
  for (std::size_t k = 0; k < scenario.steps.size(); ++k)
    a.landmark_ids[k].assign(scenario.steps[k].measurements.size(), kUnassociated);
  // The line that decided each measurement (0: none yet): a second row for one measurement silently replaced
  // the first (hostile B5); `arbor run` writes exactly one.
  std::vector<std::vector<int>> decided_at(scenario.steps.size());
  for (std::size_t k = 0; k < scenario.steps.size(); ++k) decided_at[k].assign(scenario.steps[k].measurements.size(), 0);
  TextReader in(path, ",");
  if (!in.next() || in.field_count() < 3 || in.field(0) != "step")
    throw InputError(path, in.line_number(), "header", "expected the header step,measurement,landmark");
  while (in.next()) {
    in.expect_fields(3, 3, "associations.csv");
    const std::int64_t step = in.integer(0, "step"), j = in.integer(1, "measurement"), id = in.integer(2, "landmark");
    if (step < 0 || step >= static_cast<std::int64_t>(scenario.steps.size()))
      in.fail("step", fmt::format("step {} is outside the scenario's {} steps", step, scenario.steps.size()));
    if (j < 0 || j >= static_cast<std::int64_t>(a.landmark_ids[step].size()))
      in.fail("measurement", fmt::format("step {} has {} measurements, not {}", step, a.landmark_ids[step].size(), j + 1));
    // A run's ids are 32-bit (LandmarkId): the map's writer cast 2^32 to 0 and 2^31 to -2^31 (hostile B4).
    // Not the readers' 2^30 - 1: a run started from a prior map numbers its new landmarks above that.
    constexpr std::int64_t kMaxId = std::numeric_limits<LandmarkId>::max();
    if (id < -1 || id > kMaxId)
      in.fail("landmark", fmt::format("landmark id {} is outside [0, {}] (or -1 for none)", id, kMaxId));
    int& decided = decided_at[step][j];
    if (decided > 0)
      in.fail("measurement", fmt::format("step {} measurement {} already decided at line {}", step, j, decided));
    decided = in.line_number();
    a.landmark_ids[step][j] = id;
  }
  return a;
}

namespace {
// Chosen on the calibration robots (MRCLAM Dataset 6 robots 1-2; results/heldout/ gives the figures).
constexpr SmootherLoss kRealDataLoss = SmootherLoss::kCauchy;
}  // namespace

SmoothOutput run_smoother(const SmoothConfig& config) {
  const auto wall_start = std::chrono::steady_clock::now();
  std::string why;
  if (!config.options.validate(&why)) throw InputError("", 0, "options", why);
  prepare_run_directory(config.out_dir);
  SmoothOutput out;
  Json& r = out.result;
  FactorGraph graph;
  Scenario scenario;
  std::unordered_map<std::int64_t, std::int32_t> truth_label;  // landmark id -> ground-truth id, where known
  SmootherOptions options = config.options;
  std::string init_dir;
  if (!config.isam_path.empty()) {
    graph = read_isam_factor_graph(config.isam_path, options.prior_floor_sigma);
  } else {
    scenario = read_scenario(config.scenario_path);
    SmootherAssociations associations;
    std::vector<Landmark> run_map;  // of the run the associations come from
    if (config.associations == "known") {
      associations = SmootherAssociations::from_truth(scenario);
      for (const TruthLandmark& t : scenario.truth_landmarks) truth_label[t.id] = t.id;
    } else {
      associations = read_association_decisions(config.associations, scenario);
      run_map = read_map_csv(config.associations + "/map.csv");
      for (const Landmark& l : run_map) truth_label[l.id] = l.truth_label;
    }
    // A run's own trajectory is where its associations make sense: on Victoria Park, LM from dead reckoning
    // (93 m off) with a run's decisions stalls at 96 m ATE even with the warm start, and from the run's
    // trajectory it converges in 20 iterations.
    init_dir = config.init == "auto" ? (config.associations == "known" ? "" : config.associations)
               : config.init == "dead-reckoning" ? "" : config.init;
    SmootherInitialGuess guess;
    if (!init_dir.empty()) {
      guess = read_initial_guess(init_dir, init_dir == config.associations ? &run_map : nullptr);
      options.warm_start_poses = 0;  // the guess is the starting point
    }
    graph = build_factor_graph(scenario, associations, options, init_dir.empty() ? nullptr : &guess);
    r["associations_used"] = associations.associated_count();
  }
  const bool simulated = config.isam_path.empty() && scenario.metadata.count("source") &&
                         scenario.metadata.at("source") == "simulation";
  if (config.loss == "auto") options.loss = simulated ? SmootherLoss::kNone : kRealDataLoss;
  else if (!from_string(config.loss, &options.loss)) throw InputError("", 0, "loss", "unknown loss " + config.loss);
  // Pose marginals serve only the NEES, which needs ground-truth poses.
  if (!scenario.has_truth_poses()) options.pose_marginals_max_poses = 0;
  if (!config.g2o_path.empty()) write_g2o(graph, config.g2o_path);
  out.smoother = solve_factor_graph(graph, options);
  const SmootherResult& sm = out.smoother;

  std::vector<TimedPose> trajectory;
  if (config.isam_path.empty()) trajectory = densify_trajectory(scenario, sm.poses);
  else
    for (const SmoothedPose& p : sm.poses) trajectory.push_back({p.time_s, p.pose});
  std::vector<Landmark> map;
  for (const SmoothedLandmark& l : sm.landmarks) {
    Landmark lm;
    lm.id = static_cast<LandmarkId>(l.id);
    lm.mean = l.position;
    lm.cov = l.covariance;
    const auto label = truth_label.find(l.id);
    lm.truth_label = label == truth_label.end() ? -1 : label->second;
    map.push_back(lm);
  }

  const SmootherSummary& s = sm.summary;

  r["config"] = {{"scenario", config.scenario_path},
                 {"isam", config.isam_path},
                 {"smoother", "ceres"},
                 {"associations", config.associations},
                 {"init", init_dir.empty() ? "dead-reckoning" : init_dir},
                 {"loss", std::string(to_string(options.loss))},
                 {"loss_scale", options.loss_scale},
                 {"solver", std::string(to_string(options.linear_solver))},
                 {"schur_landmarks_first", options.schur_landmarks_first},
                 {"warm_start_poses", options.warm_start_poses},
                 {"warm_start_iterations", options.warm_start_iterations},
                 {"max_iterations", options.max_iterations},
                 {"threads", options.threads}};
  r["config"].update(provenance());
  r["scenario"] = scenario.metadata;
  // As `arbor run`. The iSAM file has no truth, so these are null for it.
  r.update(accuracy_fields(scenario, evaluation_truth(scenario), trajectory, map));
  // NEES of the marginal pose covariances at the poses with ground truth (simulation, UTIAS): a consistent
  // smoother averages 3, the pose's dimension.
  // steps.csv holds them per pose, as `arbor run` writes its per-scan NEES, so the consistency figure draws
  // the smoother over time beside the filters.
  std::vector<double> nees;
  std::string steps_csv = "step,time_s,nees\n";
  if (s.pose_marginals)
    for (const SmoothedPose& p : sm.poses)
      if (p.step >= 0 && scenario.steps[p.step].truth_pose) {
        nees.push_back(pose_nees(p.pose, p.covariance, *scenario.steps[p.step].truth_pose));
        fmt::format_to(std::back_inserter(steps_csv), "{},{},{}\n", p.step, p.time_s, nees.back());
      }
  r["nees_mean"] = mean_or_null(nees);
  r["nees_median"] = nees.empty() ? Json(nullptr) : Json(quantile(nees, 0.5));
  r["nees_in_band_fraction"] = nees.empty() ? Json(nullptr) : Json(fraction_in_band(nees, kNeesBand3Dof95));
  // The smoother takes its associations as given; their quality is scored in the run they came from.
  r["assoc_precision"] = nullptr;
  r["assoc_recall"] = nullptr;
  r["assoc_f1"] = nullptr;
  r["landmarks"] = map.size();
  r["true_landmarks"] = scenario.truth_landmarks.size();
  r["steps"] = config.isam_path.empty() ? scenario.steps.size() : sm.poses.size() - 1;
  r["step_time_median_s"] = nullptr;  // a batch solve has no per-step time
  r["step_time_p95_s"] = nullptr;
  r.update(summary_json(s));
  r["wall_time_s"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  r["peak_rss_bytes"] = peak_rss_bytes();

  // An unusable solve (Ceres FAILURE, a non-finite cost) is no result: nothing is written, so no result.json
  // marks it finished, and `arbor smooth` exits 1.
  if (!config.out_dir.empty() && s.usable) {
    std::filesystem::create_directories(config.out_dir);
    const std::string dir = config.out_dir + "/";
    write_tum(dir + "trajectory.tum", trajectory);
    write_reference_tum(reference_trajectory(scenario), config.out_dir);
    write_map_csv(dir + "map.csv", map);
    if (!nees.empty()) write_file_atomically(dir + "steps.csv", steps_csv);
    else std::filesystem::remove(dir + "steps.csv");  // a reused directory keeps no other run's curve
    write_file_atomically(dir + "result.json", r.dump(2) + "\n");  // last: its presence means complete
  }
  return out;
}

}  // namespace arbor
#endif  // ARBOR_HAVE_SMOOTHER
