// DIR/sweep.json: which sweep a results directory belongs to (spec hash, shard, columns). Resume and merge
// read it to refuse mixing rows of different grids.
#ifndef ARBOR_EXPERIMENTS_SWEEP_SWEEP_MANIFEST_H_
#define ARBOR_EXPERIMENTS_SWEEP_SWEEP_MANIFEST_H_

#include <optional>
#include <string>
#include <vector>

namespace arbor {

inline constexpr const char* kSweepManifest = "sweep.json";

struct SweepManifest {
  std::string spec_hash;
  std::string spec_name;
  std::string shard = "0/1";  // "I/N", or "merged"
  int grid_runs = 0;
  std::vector<std::string> columns;
};

// nullopt when DIR/sweep.json does not exist; InputError when it is malformed.
std::optional<SweepManifest> read_manifest(const std::string& dir);
void write_manifest(const std::string& dir, const SweepManifest& manifest);

}  // namespace arbor

#endif  // ARBOR_EXPERIMENTS_SWEEP_SWEEP_MANIFEST_H_
