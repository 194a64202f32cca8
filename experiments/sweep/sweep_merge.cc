// Merging shard outputs; see sweep_merge.h.
#include "experiments/sweep/sweep_merge.h"

#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include <fmt/core.h>

#include "core/io/atomic_file.h"
#include "core/io/directory_lock.h"
#include "core/io/input_error.h"
#include "experiments/sweep/results_log.h"
#include "experiments/sweep/sweep_manifest.h"
#include "experiments/sweep/sweep_spec.h"

namespace arbor {
namespace {

// Fields that differ between two runs of one configuration: time, memory and where and when it ran.
bool is_timing_or_provenance(const std::string& field) {
  for (const char* part : {"time", "wall", "rss", "cpu", "finished_at", "host", "exit_code", "commit", "compiler", "build"})
    if (field.find(part) != std::string::npos) return true;
  return false;
}

// The first result field (neither timing nor provenance) on which two rows of one run key differ; "" if none.
std::string first_differing_result(const ResultRow& a, const ResultRow& b) {
  for (const auto& [field, value] : a.items())
    if (!is_timing_or_provenance(field) && (!b.contains(field) || b[field] != value)) return field;
  for (const auto& [field, value] : b.items())
    if (!is_timing_or_provenance(field) && !a.contains(field)) return field;
  return "";
}

}  // namespace

MergeSummary merge_sweeps(const std::vector<std::string>& inputs, const std::string& out) {
  if (inputs.empty()) throw InputError("", 0, "DIR", "merge needs at least one sweep directory");
  MergeSummary summary;
  std::optional<SweepManifest> first;
  std::string first_dir;
  std::map<std::string, std::pair<ResultRow, std::string>> by_key;  // the row, and the file:line it came from
  std::set<std::string> grid;  // the run keys of the first input's spec.toml (empty: no spec kept there)
  // Adds a directory's rows, one per run key: a finished ("ok") row wins over a failed one. Two finished rows
  // of one key must agree on every result (runs are deterministic); they may differ in timing and provenance.
  const auto fold = [&](const std::string& dir) {
    const std::string path = dir + "/" + kResultsJsonl;
    std::vector<int> lines;
    std::vector<ResultRow> rows = read_result_rows(path, &lines);
    for (std::size_t i = 0; i < rows.size(); ++i) {
      ResultRow& row = rows[i];
      const std::string key = row["key"].get<std::string>();
      const std::string where = fmt::format("{}:{}", path, lines[i]);
      // A row of another grid (an edited file, or a results file copied in) would be counted as a grid run
      // and report "13 of 12 grid runs present".
      if (!grid.empty() && !grid.count(key))
        throw InputError(path, lines[i], "key", fmt::format("run {} is not in the sweep's grid ({}/spec.toml)", key, first_dir));
      const auto it = by_key.find(key);
      if (it == by_key.end()) {
        by_key.emplace(key, std::make_pair(std::move(row), where));
        continue;
      }
      ++summary.duplicates;
      const auto is_ok = [](const ResultRow& r) { return r.value("status", std::string()) == "ok"; };
      ResultRow& kept = it->second.first;
      if (is_ok(kept) && is_ok(row)) {
        if (const std::string field = first_differing_result(kept, row); !field.empty())
          throw InputError(path, lines[i], field,
                           fmt::format("run {} has {} here and {} at {}; refusing to keep either silently", key,
                                       row.value(field, ResultRow()).dump(), kept.value(field, ResultRow()).dump(),
                                       it->second.second));
      } else if (is_ok(row)) {
        it->second = std::make_pair(std::move(row), where);
      }
    }
  };
  for (const auto& dir : inputs) {
    const auto manifest = read_manifest(dir);
    if (!manifest) throw InputError(dir + "/" + kSweepManifest, 0, "", "not a sweep directory (no sweep.json)");
    if (!first) {
      first = manifest;
      first_dir = dir;
      if (std::filesystem::exists(dir + "/spec.toml"))
        // The grid's keys only: the copy's relative dataset paths resolve from DIR, not from where the spec
        // was, and a dataset moved since must not block the merge (hostile C1).
        for (const RunParams& run : read_sweep_spec(dir + "/spec.toml", /*inputs_must_exist=*/false).runs)
          grid.insert(run.key());
    } else if (manifest->spec_hash != first->spec_hash || manifest->columns != first->columns) {
      throw InputError(dir + "/" + kSweepManifest, 0, "spec_hash",
                       fmt::format("comes from another spec (hash {}) than {} (hash {}); refusing to merge different grids",
                                   manifest->spec_hash, first_dir, first->spec_hash));
    } else if (const auto dataset = changed_dataset(*first, *manifest);
               dataset && has_ok_row_of_dataset(first_dir, *dataset) && has_ok_row_of_dataset(dir, *dataset)) {
      // One spec, but a dataset regenerated between the shards: their results share keys and differ in meaning.
      throw InputError(dir + "/" + kSweepManifest, 0, "datasets",
                       fmt::format("dataset '{}' had other content here than in {} (fingerprint {} against {}); "
                                   "refusing to merge rows of two versions of it",
                                   *dataset, first_dir, manifest->datasets.at(*dataset), first->datasets.at(*dataset)));
    } else {
      first->datasets.insert(manifest->datasets.begin(), manifest->datasets.end());  // those the first lacks
    }
    fold(dir);
    ++summary.inputs;
  }
  std::filesystem::create_directories(out);
  const DirectoryLock lock(out);  // no sweep or other merge writes it meanwhile
  if (const auto existing = read_manifest(out)) {
    if (existing->spec_hash != first->spec_hash)
      throw InputError(out + "/" + kSweepManifest, 0, "spec_hash", "the output directory holds another sweep");
    if (const auto dataset = changed_dataset(*existing, *first); dataset && has_ok_row_of_dataset(out, *dataset))
      throw InputError(out + "/" + kSweepManifest, 0, "datasets",
                       fmt::format("dataset '{}' had other content in the output directory's rows; refusing to merge "
                                   "rows of two versions of it", *dataset));
    first->datasets.insert(existing->datasets.begin(), existing->datasets.end());
    // Merging into an earlier merge (or a shard) of the same spec adds to its rows; they used to be dropped.
    fold(out);
  }
  std::vector<ResultRow> rows;
  for (auto& [key, entry] : by_key) rows.push_back(std::move(entry.first));
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
