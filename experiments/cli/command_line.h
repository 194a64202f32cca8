// The `arbor` command line as a function: main.cc calls it, so the program's one translation unit does not
// compile CLI11 (experiments/CMakeLists.txt says why that matters).
#ifndef ARBOR_EXPERIMENTS_CLI_COMMAND_LINE_H_
#define ARBOR_EXPERIMENTS_CLI_COMMAND_LINE_H_

namespace arbor::cli {

// Parses argv, runs the chosen subcommand, and returns the process exit status (DESIGN.md §9: 0 success,
// 2 bad input or options, 1 any other failure).
int run_command_line(int argc, char** argv);

}  // namespace arbor::cli

#endif  // ARBOR_EXPERIMENTS_CLI_COMMAND_LINE_H_
