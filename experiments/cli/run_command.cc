// `arbor run`: one FastSLAM run over a scenario; writes DIR/result.json, trajectory.tum, map.csv, associations.csv, steps.csv.
#include <fmt/core.h>
#include <fmt/ranges.h>

#include "core/io/input_error.h"
#include "core/io/scenario_format.h"
#include "core/io/atomic_file.h"
#include "experiments/cli/commands.h"
#include "experiments/cli/option_checks.h"
#include "experiments/run/fastslam_run.h"
#include "variants/registry.h"

namespace arbor::cli {

void add_run_command(CLI::App& app, CommandAction* action) {
  auto* cmd = app.add_subcommand("run", "Run FastSLAM on a scenario and write its result files");
  auto config = std::make_shared<RunConfig>();
  auto filter = std::make_shared<std::string>("fastslam2");
  auto quiet = std::make_shared<bool>(false);
  auto sampling = std::make_shared<std::string>("per-scan");
  auto likelihood = std::make_shared<std::string>("gaussian");
  cmd->add_option("--scenario", config->scenario_path, "Scenario file (from `arbor simulate` or `arbor convert`)")
      ->required();
  cmd->add_option("--filter", *filter, "fastslam1 (sample the motion model) or fastslam2 (measurement-informed proposal)")
      ->check(CLI::IsMember({"fastslam1", "fastslam2"}))
      ->capture_default_str();
  cmd->add_option("--map", config->map, fmt::format("Map back end: {}", fmt::join(map_backend_names(), ", ")))
      ->capture_default_str();
  cmd->add_option("--assoc", config->assoc,
                  fmt::format("Data association: {} (known = the scenario's ground-truth ids)",
                              fmt::join(association_names(), ", ")))
      ->capture_default_str();
  cmd->add_option("--particles", config->options.particles, "Number of particles M")->capture_default_str();
  cmd->add_option("--seed", config->options.seed, "Seed of every random draw of the filter")
      ->check(unsigned_number())
      ->capture_default_str();
  cmd->add_option("--threads", config->options.threads, "Worker threads (0 = all cores); results do not depend on it")
      ->capture_default_str();
  cmd->add_option("--resample-threshold", config->options.resample_threshold,
                  "Resample when N_eff < threshold * particles")
      ->capture_default_str();
  cmd->add_option("--chi2", config->options.association.gate_probability,
                  "Chi-square gate probability of the association tests")
      ->capture_default_str();
  cmd->add_option("--new-landmark-gate", config->options.association.new_landmark_probability,
                  "A measurement outside this chi-square gate of every landmark starts a new one")
      ->capture_default_str();
  cmd->add_option("--motion-sampling", *sampling,
                  "per-scan: carry each particle's predicted mean and covariance through every control and draw once "
                  "per scan (the FastSLAM 2.0 proposal and the association see the whole prediction); per-control: "
                  "draw at every control (the proposal sees only the last control's covariance; an ablation)")
      ->check(CLI::IsMember({"per-scan", "per-control"}))
      ->capture_default_str();
  cmd->add_option("--likelihood", *likelihood,
                  "Measurement likelihood in the weights, the proposal and the landmark updates: gaussian or student-t "
                  "(heavy tails: an outlier pulls and weighs less)")
      ->check(CLI::IsMember({"gaussian", "student-t"}))
      ->capture_default_str();
  cmd->add_option("--student-dof", config->options.student_dof, "Degrees of freedom of the Student-t likelihood")
      ->check(within(0.1, 1e6))
      ->capture_default_str();
  cmd->add_option("--known-gate", config->options.association.known_gate_probability,
                  "With --assoc known, reject (and count) a measurement outside this chi-square gate of the landmark "
                  "its id names; 1 disables the gate")
      ->check(within(1e-6, 1.0))
      ->capture_default_str();
  cmd->add_option("--max-hypotheses", config->options.association.max_hypotheses,
                  "Search budget of JCBB and the interpretation trees per particle and scan; a search that reaches it "
                  "answers with its best hypothesis so far and is counted in result.json budget_exhausted")
      ->check(at_least(1))
      ->capture_default_str();
  cmd->add_option("--max-work", config->options.association.max_work,
                  "Their work budget per particle and scan, in multiply-adds and candidate scans (a tree's "
                  "compatibility test counts 16); reaching it is counted as above")
      ->check(at_least(1))
      ->capture_default_str();
  cmd->add_option("--prune", config->options.log_odds_prune, "Drop landmarks whose existence log-odds fall below this")
      ->capture_default_str();
  cmd->add_option("--confirm", config->options.log_odds_confirm,
                  "A new landmark is provisional until its existence log-odds reach this (start 1, +1 per sighting, "
                  "-0.5 per miss); only confirmed landmarks make the reported map (1: every landmark at once)")
      ->capture_default_str();
  cmd->add_option("--provisional-scans", config->options.provisional_scans,
                  "Drop a landmark still provisional this many scans after the one that started it (0: never); not "
                  "with --assoc known")
      ->check(at_least(0))
      ->capture_default_str();
  cmd->add_flag("--relocalize", config->options.relocalize,
                "Relocalise a lost robot: when the best particle pairs under half a scan, search its settled map "
                "with the pose-free locality tree; a pose that pairs more, found again at the next scan, re-seeds "
                "every particle (a kidnapped robot, or a loop closure the gates miss)");
  cmd->add_option("--relocalize-min-pairings", config->options.relocalize_min_pairings,
                  "Pairings a relocalised pose must explain")
      ->check(at_least(3))
      ->capture_default_str();
  cmd->add_option("--out", config->out_dir, "Output directory (result.json, trajectory.tum, map.csv, associations.csv, steps.csv)")
      ->required();
  cmd->add_flag("--quiet", *quiet, "No progress line");
  cmd->callback([=] {
    *action = [=] {
      // Before anything can fail: a bad scenario or option must not leave the previous run's result.json
      // marking this directory finished (run_fastslam forgets it too, for callers of the library).
      forget_finished_run(config->out_dir);
      if (!from_string(*filter, &config->options.version)) throw InputError("", 0, "filter", "unknown filter " + *filter);
      if (!from_string(*sampling, &config->options.motion_sampling))
        throw InputError("", 0, "motion-sampling", "unknown motion sampling " + *sampling);
      if (!from_string(*likelihood, &config->options.likelihood))
        throw InputError("", 0, "likelihood", "unknown likelihood " + *likelihood);
      config->progress = !*quiet;
      const Scenario scenario = read_scenario(config->scenario_path);
      const RunOutput out = run_fastslam(scenario, *config);
      const auto& r = out.result;
      const auto show = [](const nlohmann::json& v) { return v.is_null() ? std::string("n/a") : fmt::format("{:.4g}", v.get<double>()); };
      fmt::print("{} {} map={} assoc={} particles={} seed={}\n", config->scenario_path, *filter, config->map,
                 config->assoc, config->options.particles, config->options.seed);
      fmt::print("  ATE RMSE {} m (weighted mean {} m, dead reckoning {} m{})\n", show(r["ate_rmse_m"]),
                 show(r["ate_mean_rmse_m"]), show(r["dead_reckoning_ate_m"]),
                 r["ate_aligned"].get<bool>() ? ", SE(2)-aligned to GPS" : "");
      fmt::print("  landmark RMSE {} m, landmarks {} (true {}), pose NEES median {} (in the 95 % band at {} of scans)\n",
                 show(r["landmark_rmse_m"]), r["landmarks"].get<std::size_t>(), r["true_landmarks"].get<std::size_t>(),
                 show(r["nees_median"]), show(r["nees_in_band_fraction"]));
      fmt::print("  association precision {} recall {} F1 {}, rejected measurements {}\n", show(r["assoc_precision"]),
                 show(r["assoc_recall"]), show(r["assoc_f1"]), r["rejected_measurements"].get<std::int64_t>());
      fmt::print("  step time median {:.3g} ms, p95 {:.3g} ms, wall {:.3g} s, peak RSS {:.1f} MB\n",
                 1e3 * r["step_time_median_s"].get<double>(), 1e3 * r["step_time_p95_s"].get<double>(),
                 r["wall_time_s"].get<double>(), r["peak_rss_bytes"].get<double>() / 1e6);
      fmt::print("  wrote {}/result.json, trajectory.tum, map.csv, associations.csv, steps.csv\n", config->out_dir);
      return 0;
    };
  });
}

}  // namespace arbor::cli
