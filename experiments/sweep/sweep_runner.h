// Executes a sweep: generates the simulated scenarios it needs, runs every pending grid point of this shard
// as a child `arbor run` (up to `jobs` at once), and appends one result row per finished run.
// Resumable: rows already in DIR/results.jsonl are skipped, so the same command continues a stopped sweep.
#ifndef ARBOR_EXPERIMENTS_SWEEP_SWEEP_RUNNER_H_
#define ARBOR_EXPERIMENTS_SWEEP_SWEEP_RUNNER_H_

#include <string>
#include <vector>

#include "experiments/sweep/sweep_spec.h"

namespace arbor {

struct SweepOptions {
  std::string out_dir;
  int jobs = 0;             // 0: the spec's `jobs`, else cores / max threads
  int shard_index = 0;      // this shard, 0 <= shard_index < shard_count
  int shard_count = 1;
  bool dry_run = false;     // list the runs and their commands, run nothing
  bool retry_failed = false;  // run again the grid points whose recorded row is not "ok"
  std::string arbor_exe;    // the binary that executes runs; empty: this one
};

struct SweepSummary {
  int grid_runs = 0;      // the whole grid
  int shard_runs = 0;     // this shard's part
  int already_done = 0;   // skipped because their row existed
  int finished = 0;       // recorded by this invocation
  int failed = 0;         // of those, not "ok"
  bool interrupted = false;
};

// Parses "I/N" (0 <= I < N); throws InputError naming the option.
void parse_shard(const std::string& text, int* index, int* count);

// The runs of shard index/count: grid positions i with i % count == index.
std::vector<RunParams> shard_runs(const std::vector<RunParams>& grid, int index, int count);

// The argv that executes one run (argv[0] = arbor_exe).
std::vector<std::string> run_command(const RunParams& run, const std::string& arbor_exe, const std::string& out_dir);

// Throws InputError when out_dir holds a different sweep (spec hash or shard differ).
SweepSummary run_sweep(const SweepSpec& spec, const SweepOptions& options);

}  // namespace arbor

#endif  // ARBOR_EXPERIMENTS_SWEEP_SWEEP_RUNNER_H_
