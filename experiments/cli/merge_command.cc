// `arbor merge DIR... --out DIR`: joins the results of sweep shards.
#include <fmt/core.h>

#include "experiments/cli/commands.h"
#include "experiments/sweep/sweep_merge.h"

namespace arbor::cli {

void add_merge_command(CLI::App& app, CommandAction* action) {
  struct Options {
    std::vector<std::string> inputs;
    std::string out;
  };
  auto options = std::make_shared<Options>();
  CLI::App* cmd = app.add_subcommand(
      "merge", "Join the result directories of sweep shards (same spec only; refuses others), de-duplicating rows by run key.");
  cmd->add_option("DIR", options->inputs, "Sweep result directories (each with sweep.json)")->required();
  cmd->add_option("--out", options->out, "Merged results directory")->required();
  cmd->callback([options, action] {
    *action = [options] {
      const MergeSummary s = merge_sweeps(options->inputs, options->out);
      fmt::print(stderr, "[merge] {} rows from {} directories ({} duplicates dropped); {} of {} grid runs present{}\n",
                 s.rows, s.inputs, s.duplicates, s.rows, s.grid_runs,
                 s.rows < s.grid_runs ? " — some shards are incomplete" : "");
      return 0;
    };
  });
}

}  // namespace arbor::cli
