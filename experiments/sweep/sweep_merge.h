// `arbor merge`: joins the result files of sweep shards (or of the same sweep run twice) into one directory.
#ifndef ARBOR_EXPERIMENTS_SWEEP_SWEEP_MERGE_H_
#define ARBOR_EXPERIMENTS_SWEEP_SWEEP_MERGE_H_

#include <string>
#include <vector>

namespace arbor {

struct MergeSummary {
  int inputs = 0;
  int rows = 0;        // rows written
  int duplicates = 0;  // rows dropped because their key was already taken
  int grid_runs = 0;   // size of the whole grid, so the caller can say what is missing
};

// Every input must be a sweep directory (DIR/sweep.json) of the same spec (same hash and columns), else
// InputError names the odd one out. Rows are de-duplicated by key, an "ok" row winning over a failed one,
// and written sorted by key to out/results.{jsonl,csv} with a manifest whose shard is "merged".
// The run directories (trajectories, maps) stay where they are.
MergeSummary merge_sweeps(const std::vector<std::string>& inputs, const std::string& out);

}  // namespace arbor

#endif  // ARBOR_EXPERIMENTS_SWEEP_SWEEP_MERGE_H_
