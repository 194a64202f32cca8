// `arbor smooth`: the Ceres full-SLAM smoother over a scenario (or a pre-associated iSAM file); writes
// DIR/result.json, trajectory.tum, map.csv, and optionally the problem as g2o.
#include "core/io/atomic_file.h"
#include "experiments/cli/commands.h"

#ifdef ARBOR_HAVE_SMOOTHER
#include <fmt/core.h>

#include "core/io/input_error.h"
#include "experiments/options/option_checks.h"
#include "experiments/run/smooth_run.h"

namespace arbor::cli {

void add_smooth_command(CLI::App& app, CommandAction* action) {
  auto* cmd = app.add_subcommand(
      "smooth",
      "Full SLAM as nonlinear least squares (Ceres): every scan pose and landmark a variable, the controls between "
      "scans chained into one relative-motion factor, range-bearing factors, a prior on the first pose. The "
      "accuracy reference for FastSLAM on the same data.");
  auto config = std::make_shared<SmoothConfig>();
  auto solver = std::make_shared<std::string>(std::string(to_string(config->options.linear_solver)));
  auto quiet = std::make_shared<bool>(false);
  auto* scenario = cmd->add_option("--scenario", config->scenario_path, "Scenario file (from `arbor simulate` or `arbor convert`)");
  auto* isam = cmd->add_option("--isam", config->isam_path,
                               "Instead of a scenario: a pre-associated iSAM/GTSAM 2-D file (ODOMETRY/LANDMARK lines, "
                               "e.g. GTSAM's victoria_park.txt)");
  scenario->excludes(isam);
  cmd->add_option("--associations", config->associations,
                  "known (the scenario's ground-truth ids) or a FastSLAM result directory (its best particle's "
                  "decisions, DIR/associations.csv)")
      ->capture_default_str();
  cmd->add_option("--init", config->init,
                  "Initial values: auto (the FastSLAM run the associations come from, else dead reckoning), "
                  "dead-reckoning, or a FastSLAM result directory (trajectory.tum; map.csv too when it is also the "
                  "association source). Starting from a run turns the warm start off")
      ->capture_default_str();
  cmd->add_option("--loss", config->loss,
                  "Robust loss on landmark observations: auto (cauchy on real data, none on simulated), none, huber, "
                  "cauchy")
      ->check(CLI::IsMember({"auto", "none", "huber", "cauchy"}))
      ->capture_default_str();
  cmd->add_option("--loss-scale", config->options.loss_scale,
                  "Where the robust loss leaves the quadratic, in standard deviations of the whitened residual")
      ->capture_default_str();
  cmd->add_option("--solver", *solver, "Sparse linear solver: sparse-normal-cholesky or sparse-schur")
      ->check(CLI::IsMember({"sparse-schur", "sparse-normal-cholesky"}))
      ->capture_default_str();
  cmd->add_flag("--pose-at-truth-steps", config->options.pose_at_truth_steps,
                "Also keep a pose at every step with ground truth (default: one pose per scan, the steps between "
                "filled in from the controls for the evaluation)");
  cmd->add_flag("--schur-landmarks-first", config->options.schur_landmarks_first,
                "With sparse-schur: eliminate exactly the landmarks (else Ceres chooses the eliminated set)");
  cmd->add_option("--warm-start", config->options.warm_start_poses,
                  "Grow the problem this many poses at a time before the full solve (0 = one batch solve from dead "
                  "reckoning, which can stall in a poor minimum on long runs)")
      ->capture_default_str();
  cmd->add_option("--warm-start-iterations", config->options.warm_start_iterations,
                  "Iteration cap of each intermediate warm-start solve")
      ->capture_default_str();
  cmd->add_option("--max-iterations", config->options.max_iterations, "Iteration cap of the final solve")
      ->capture_default_str();
  cmd->add_option("--threads", config->options.threads, "Ceres threads (Jacobians and linear algebra)")
      ->check(within(1, kMaxThreads))
      ->capture_default_str();
  cmd->add_option("--marginals-max-poses", config->options.pose_marginals_max_poses,
                  "Compute the poses' marginal covariances (for the NEES against ground-truth poses) only up to this "
                  "many poses; 0: never")
      ->capture_default_str();
  cmd->add_option("--g2o", config->g2o_path, "Also write the problem (initial values, factors) as a g2o file");
  cmd->add_option("--out", config->out_dir, "Output directory (result.json, trajectory.tum, map.csv; reference.tum where the "
                  "scenario has a ground truth or GPS track)")->required();
  cmd->add_flag("--verbose", config->options.verbose, "Ceres's per-iteration log");
  cmd->add_flag("--quiet", *quiet, "No summary on stdout");
  cmd->callback([=] {
    *action = [=] {
      prepare_run_directory(config->out_dir);  // before anything can fail (see run_command.cc)
      if (config->scenario_path.empty() && config->isam_path.empty())
        throw InputError("", 0, "scenario", "give --scenario FILE or --isam FILE");
      if (!from_string(*solver, &config->options.linear_solver))
        throw InputError("", 0, "solver", "unknown solver " + *solver);
      const SmoothOutput out = run_smoother(*config);
      // A solve that ended unusable is a failure (exit 1) with or without the summary on stdout.
      if (!out.smoother.summary.usable)
        fmt::print(stderr, "arbor: failed: the solve ended unusable ({})\n", out.smoother.summary.termination);
      if (*quiet) return out.smoother.summary.usable ? 0 : 1;
      const auto& r = out.result;
      const auto show = [](const nlohmann::json& v) {
        return v.is_null() ? std::string("n/a") : fmt::format("{:.4g}", v.get<double>());
      };
      const SmootherSummary& s = out.smoother.summary;
      fmt::print("{} smooth associations={} solver={} loss={}\n",
                 config->isam_path.empty() ? config->scenario_path : config->isam_path, config->associations, *solver,
                 r["config"]["loss"].get<std::string>());
      fmt::print("  {} poses, {} landmarks, {} factors; {} iterations, cost {:.6g} -> {:.6g}, {}\n", s.poses,
                 s.landmarks, s.factors, s.iterations, s.initial_cost, s.final_cost, s.termination);
      fmt::print("  solve {:.3f} s wall, {:.3f} s CPU (build {:.3f} s), gradient max norm {:.3g}\n", s.solve_time_s,
                 s.solve_cpu_s, s.build_time_s, s.gradient_max_norm);
      fmt::print("  ATE RMSE {} m (SE(2)-aligned {} m; dead reckoning {} m{}), landmark RMSE {} m, NEES mean {}{}\n",
                 show(r["ate_rmse_m"]), show(r["ate_aligned_rmse_m"]), show(r["dead_reckoning_ate_m"]),
                 r["ate_aligned"].get<bool>() ? ", aligned to GPS" : "", show(r["landmark_rmse_m"]),
                 show(r["nees_mean"]),
                 s.pose_marginals ? fmt::format(" (marginals {:.3f} s)", s.marginals_time_s) : std::string());
      if (s.usable)
        fmt::print("  wrote {}/result.json, trajectory.tum, map.csv{}\n", config->out_dir,
                   config->g2o_path.empty() ? "" : ", " + config->g2o_path);
      return s.usable ? 0 : 1;
    };
  });
}

}  // namespace arbor::cli
#endif  // ARBOR_HAVE_SMOOTHER
