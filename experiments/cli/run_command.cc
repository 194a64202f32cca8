// `arbor run`: one FastSLAM run over a scenario; writes DIR/result.json, trajectory.tum, map.csv, associations.csv, steps.csv.
#include <fmt/core.h>
#include <fmt/ranges.h>

#include "core/io/input_error.h"
#include "core/io/scenario_format.h"
#include "core/io/atomic_file.h"
#include "experiments/cli/commands.h"
#include "experiments/options/run_options.h"
#include "experiments/run/fastslam_run.h"
#include "variants/registry.h"

namespace arbor::cli {

void add_run_command(CLI::App& app, CommandAction* action) {
  auto* cmd = app.add_subcommand("run", "Run an online filter (FastSLAM or EKF-SLAM) on a scenario and write its result files");
  auto config = std::make_shared<RunConfig>();
  auto choices = std::make_shared<RunChoices>();
  auto quiet = std::make_shared<bool>(false);
  add_run_options(*cmd, *config, *choices);
  cmd->add_flag("--quiet", *quiet, "No progress line");
  cmd->callback([=] {
    *action = [=] {
      // Before anything can fail: a bad scenario or option must not leave the previous run's result.json
      // marking this directory finished (run_fastslam forgets it too, for callers of the library).
      prepare_run_directory(config->out_dir);
      apply_run_choices(*choices, *config);
      check_run_option_combinations(*cmd, *config);
      config->progress = !*quiet;
      const Scenario scenario = read_scenario(config->scenario_path);
      const RunOutput out = run_fastslam(scenario, *config);
      const auto& r = out.result;
      const auto show = [](const nlohmann::json& v) { return v.is_null() ? std::string("n/a") : fmt::format("{:.4g}", v.get<double>()); };
      const FilterTraits& traits = filter_traits(*config);
      fmt::print("{} {}{} assoc={}{}\n", config->scenario_path, to_string(config->options.version),
                 traits.has_map_backends ? " map=" + config->map : "", config->assoc,
                 traits.has_particles ? fmt::format(" particles={} seed={}", config->options.particles, config->options.seed) : "");
      fmt::print("  ATE RMSE {} m (mean path; best particle {} m, causal mean {} m, dead reckoning {} m{})\n",
                 show(r["ate_rmse_m"]), show(r["ate_best_rmse_m"]), show(r["ate_mean_rmse_m"]), show(r["dead_reckoning_ate_m"]),
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
