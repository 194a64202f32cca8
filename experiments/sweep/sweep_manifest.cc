// Reading and writing DIR/sweep.json; see sweep_manifest.h.
#include "experiments/sweep/sweep_manifest.h"

#include <fstream>
#include <sstream>

#include <fmt/core.h>

#include "core/io/atomic_file.h"
#include "core/io/input_error.h"
#include "experiments/sweep/sweep_spec.h"
#include <nlohmann/json.hpp>

namespace arbor {

std::optional<SweepManifest> read_manifest(const std::string& dir) {
  const std::string path = dir + "/" + kSweepManifest;
  std::ifstream in(path);
  if (!in) return std::nullopt;
  nlohmann::json doc;
  try {
    doc = nlohmann::json::parse(in);
  } catch (const nlohmann::json::parse_error& e) {
    throw InputError(path, 0, "", fmt::format("malformed JSON: {}", e.what()));
  }
  const auto string_member = [&](const char* name) {
    if (!doc.contains(name) || !doc[name].is_string()) throw InputError(path, 0, name, "missing or not a string");
    return doc[name].get<std::string>();
  };
  SweepManifest m;
  m.spec_hash = string_member("spec_hash");
  m.spec_name = string_member("spec_name");
  m.shard = string_member("shard");
  if (doc.contains("grid_runs") && doc["grid_runs"].is_number_integer()) m.grid_runs = doc["grid_runs"].get<int>();
  if (!doc.contains("columns") || !doc["columns"].is_array()) throw InputError(path, 0, "columns", "missing or not an array");
  for (const auto& c : doc["columns"]) {
    if (!c.is_string()) throw InputError(path, 0, "columns", "column names must be strings");
    m.columns.push_back(c.get<std::string>());
  }
  if (doc.contains("datasets")) {
    if (!doc["datasets"].is_object()) throw InputError(path, 0, "datasets", "not an object");
    for (const auto& [dataset, fingerprint] : doc["datasets"].items()) {
      if (!fingerprint.is_string()) throw InputError(path, 0, "datasets", "fingerprints must be strings");
      m.datasets[dataset] = fingerprint.get<std::string>();
    }
  }
  return m;
}

void write_manifest(const std::string& dir, const SweepManifest& m) {
  nlohmann::ordered_json doc{{"format", "arbor-sweep 1"}, {"spec_hash", m.spec_hash}, {"spec_name", m.spec_name},
                             {"shard", m.shard},          {"grid_runs", m.grid_runs}, {"columns", m.columns}};
  if (!m.datasets.empty()) doc["datasets"] = m.datasets;  // a simulated grid's manifest stays as it was
  write_file_atomically(dir + "/" + kSweepManifest, doc.dump(2) + "\n");
}

std::string dataset_fingerprint(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, 0, "", "cannot open the dataset to fingerprint it");
  std::stringstream bytes;
  bytes << in.rdbuf();
  const std::string text = bytes.str();
  return fmt::format("{}:{}", text.size(), stable_hash(text));
}

std::optional<std::string> changed_dataset(const SweepManifest& a, const SweepManifest& b) {
  for (const auto& [dataset, fingerprint] : a.datasets)
    if (const auto it = b.datasets.find(dataset); it != b.datasets.end() && it->second != fingerprint) return dataset;
  return std::nullopt;
}

}  // namespace arbor
