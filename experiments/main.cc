// arbor: the command-line front end (experiments/cli/command_line.cc; each subcommand in
// experiments/cli/<name>_command.cc).
#include "experiments/cli/command_line.h"

int main(int argc, char** argv) { return arbor::cli::run_command_line(argc, argv); }
