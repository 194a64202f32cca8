// Merging shard outputs; see sweep_merge.h.
#include "experiments/sweep/sweep_merge.h"

#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include <fmt/core.h>

#include "core/io/atomic_file.h"
#include "core/io/directory_lock.h"
#include "core/io/input_error.h"
#include "experiments/sweep/results_log.h"
#include "experiments/sweep/sweep_manifest.h"

namespace arbor {

MergeSummary merge_sweeps(const std::vector<std::string>& inputs, const std::string& out) {
  if (inputs.empty()) throw InputError("", 0, "DIR", "merge needs at least one sweep directory");
  MergeSummary summary;
  std::optional<SweepManifest> first;
  std::string first_dir;
  std::map<std::string, ResultRow> by_key;
  // Adds a directory's rows, one per run key: a finished ("ok") row wins over a failed one.
  const auto fold = [&](const std::string& dir) {
    for (auto& row : read_result_rows(dir + "/" + kResultsJsonl)) {
      const std::string key = row["key"].get<std::string>();
      const auto it = by_key.find(key);
      if (it == by_key.end()) {
        by_key.emplace(key, std::move(row));
        continue;
      }
      ++summary.duplicates;
      const auto is_ok = [](const ResultRow& r) { return r.value("status", std::string()) == "ok"; };
      if (!is_ok(it->second) && is_ok(row)) it->second = std::move(row);
    }
  };
  for (const auto& dir : inputs) {
    const auto manifest = read_manifest(dir);
    if (!manifest) throw InputError(dir + "/" + kSweepManifest, 0, "", "not a sweep directory (no sweep.json)");
    if (!first) {
      first = manifest;
      first_dir = dir;
    } else if (manifest->spec_hash != first->spec_hash || manifest->columns != first->columns) {
      throw InputError(dir + "/" + kSweepManifest, 0, "spec_hash",
                       fmt::format("comes from another spec (hash {}) than {} (hash {}); refusing to merge different grids",
                                   manifest->spec_hash, first_dir, first->spec_hash));
    }
    fold(dir);
    ++summary.inputs;
  }
  std::filesystem::create_directories(out);
  const DirectoryLock lock(out);  // no sweep or other merge writes it meanwhile
  if (const auto existing = read_manifest(out)) {
    if (existing->spec_hash != first->spec_hash)
      throw InputError(out + "/" + kSweepManifest, 0, "spec_hash", "the output directory holds another sweep");
    // Merging into an earlier merge (or a shard) of the same spec adds to its rows; they used to be dropped.
    fold(out);
  }
  std::vector<ResultRow> rows;
  for (auto& [key, row] : by_key) rows.push_back(std::move(row));
  write_result_files(out, rows, first->columns);
  SweepManifest merged = *first;
  merged.shard = "merged";
  write_manifest(out, merged);
  if (std::ifstream spec(first_dir + "/spec.toml"); spec) {
    std::stringstream text;
    text << spec.rdbuf();
    write_file_atomically(out + "/spec.toml", text.str());
  }
  summary.rows = static_cast<int>(rows.size());
  summary.grid_runs = first->grid_runs;
  return summary;
}

}  // namespace arbor
