// The `arbor` command line: every subcommand registers itself (experiments/cli/<name>_command.cc).
#include "experiments/cli/command_line.h"

#include <cstdio>
#include <exception>
#include <new>

#include <CLI/CLI.hpp>
#include <fmt/core.h>

#include "core/io/input_error.h"
#include "experiments/cli/commands.h"
#include "experiments/options/option_checks.h"

namespace arbor::cli {

int run_command_line(int argc, char** argv) {
  CLI::App app{"Arbor: a benchmark and research framework for landmark-based SLAM (FastSLAM 1.0/2.0)."};
  app.require_subcommand(1);
  app.set_help_all_flag("--help-all", "Print help for every subcommand");
  CommandAction action;
  add_simulate_command(app, &action);
  add_run_command(app, &action);
  add_associate_command(app, &action);
  add_relocalize_command(app, &action);
  add_convert_command(app, &action);
#ifdef ARBOR_HAVE_SMOOTHER
  add_smooth_command(app, &action);
#endif
  add_sweep_command(app, &action);
  add_merge_command(app, &action);
  apply_common_option_checks(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : 2;  // DESIGN.md §9: bad options exit with status 2
  }
  try {
    return action ? action() : 0;
  } catch (const InputError& e) {
    fmt::print(stderr, "arbor: error: {}\n", e.what());
    return 2;
  } catch (const std::bad_alloc&) {
    // What the memory checks (core/io/memory_budget.h) did not foresee: the map grows with the run. The hint
    // names the options of the command that ran (`relocalize` has no --particles or --map: hostile C6).
    const std::vector<CLI::App*> used = app.get_subcommands();
    const std::string command = used.empty() ? std::string() : used.front()->get_name();
    if (command == "run")
      fmt::print(stderr, "arbor: failed: out of memory; a run needs more with --particles, a larger map (--landmarks) "
                         "or the naive back end (--map naive copies every particle's map)\n");
    else
      fmt::print(stderr, "arbor: failed: out of memory; `arbor {}` needs more than this machine has with these "
                         "options: make the sizes they ask for smaller\n", command);
    return 1;
  } catch (const std::exception& e) {
    fmt::print(stderr, "arbor: failed: {}\n", e.what());
    return 1;
  }
}

}  // namespace arbor::cli
