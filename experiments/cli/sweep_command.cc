// `arbor sweep SPEC --out DIR`: runs a declarative grid of experiments, resumably and in parallel.
#include <fmt/core.h>

#include "experiments/cli/commands.h"
#include "experiments/options/option_checks.h"
#include "experiments/sweep/sweep_runner.h"
#include "experiments/sweep/sweep_spec.h"

namespace arbor::cli {

void add_sweep_command(CLI::App& app, CommandAction* action) {
  struct Options {
    std::string spec;
    std::string shard = "0/1";
    SweepOptions sweep;
  };
  auto options = std::make_shared<Options>();
  CLI::App* cmd = app.add_subcommand(
      "sweep",
      "Run every point of the grid named in a sweep spec (TOML; see experiments/sweeps/README.md). Each run is a "
      "child `arbor run` writing DIR/runs/<key>/; each finished run appends one row to DIR/results.csv and "
      "DIR/results.jsonl. Stopped sweeps resume with the same command; failed runs are recorded and skipped.");
  cmd->add_option("SPEC", options->spec, "The sweep spec (.toml)")->required();
  cmd->add_option("--out", options->sweep.out_dir, "Results directory (created; reused to resume)")->required();
  cmd->add_option("--jobs,-j", options->sweep.jobs,
                  "Runs in parallel (default: the spec's 'jobs', else cores / the largest thread count)")
      ->check(within(1, 1024));
  cmd->add_option("--shard", options->shard,
                  "Run only shard I of N (0 <= I < N): grid positions i with i mod N == I, in the sorted grid. "
                  "Give each shard its own --out and join them with `arbor merge`")
      ->capture_default_str();
  cmd->add_flag("--dry-run", options->sweep.dry_run, "Validate the spec and list the runs and their commands; run nothing");
  cmd->add_flag("--retry-failed", options->sweep.retry_failed, "Run again the grid points whose recorded row is not 'ok'");
  cmd->add_option("--arbor", options->sweep.arbor_exe, "The arbor binary that executes the runs (default: this one)");
  cmd->callback([options, action] {
    *action = [options] {
      parse_shard(options->shard, &options->sweep.shard_index, &options->sweep.shard_count);
      const SweepSpec spec = read_sweep_spec(options->spec);  // validates everything before any run starts
      const SweepSummary s = run_sweep(spec, options->sweep);
      if (options->sweep.dry_run) return 0;
      if (s.interrupted) {
        fmt::print(stderr, "[sweep] interrupted: {} runs recorded this session; run the same command to resume\n", s.finished);
        return 130;
      }
      fmt::print(stderr, "[sweep] done: {} of {} runs recorded ({} this session, {} not ok); results in {}/results.csv\n",
                 s.already_done + s.finished, s.shard_runs, s.finished, s.failed, options->sweep.out_dir);
      return 0;
    };
  });
}

}  // namespace arbor::cli
