// DIR/sweep.json: which sweep a results directory belongs to (spec hash, shard, columns). Resume and merge
// read it to refuse mixing rows of different grids.
#ifndef ARBOR_EXPERIMENTS_SWEEP_SWEEP_MANIFEST_H_
#define ARBOR_EXPERIMENTS_SWEEP_SWEEP_MANIFEST_H_

#include <map>
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
  // Each dataset the spec names (its path as written) -> dataset_fingerprint() of its content when the rows
  // were made. The run keys name a dataset by its path only, so without this the rows of two versions of one
  // file mixed silently on resume and in merges (hostile B6). Empty in directories of earlier builds.
  std::map<std::string, std::string> datasets;
};

// nullopt when DIR/sweep.json does not exist; InputError when it is malformed.
std::optional<SweepManifest> read_manifest(const std::string& dir);
void write_manifest(const std::string& dir, const SweepManifest& manifest);

// "SIZE:HASH" of the file's bytes (stable_hash, FNV-1a); throws InputError when it cannot be read.
std::string dataset_fingerprint(const std::string& path);

// A dataset both manifests record with different fingerprints, or nullopt.
std::optional<std::string> changed_dataset(const SweepManifest& a, const SweepManifest& b);

}  // namespace arbor

#endif  // ARBOR_EXPERIMENTS_SWEEP_SWEEP_MANIFEST_H_
