// The `arbor` subcommands. Each lives in its own file and registers itself on the CLI11 app through one
// add_*_command function that main.cc calls; a command returns the process exit status.
#ifndef ARBOR_EXPERIMENTS_CLI_COMMANDS_H_
#define ARBOR_EXPERIMENTS_CLI_COMMANDS_H_

#include <functional>

#include <CLI/CLI.hpp>

namespace arbor::cli {

// The action to run once parsing succeeded; set by whichever subcommand was chosen.
using CommandAction = std::function<int()>;

void add_simulate_command(CLI::App& app, CommandAction* action);
void add_run_command(CLI::App& app, CommandAction* action);
void add_associate_command(CLI::App& app, CommandAction* action);
void add_relocalize_command(CLI::App& app, CommandAction* action);
void add_convert_command(CLI::App& app, CommandAction* action);
void add_smooth_command(CLI::App& app, CommandAction* action);  // only with ARBOR_HAVE_SMOOTHER
void add_sweep_command(CLI::App& app, CommandAction* action);
void add_merge_command(CLI::App& app, CommandAction* action);

}  // namespace arbor::cli

#endif  // ARBOR_EXPERIMENTS_CLI_COMMANDS_H_
