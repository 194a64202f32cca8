// Reading and writing DIR/sweep.json; see sweep_manifest.h.
#include "experiments/sweep/sweep_manifest.h"

#include <filesystem>
#include <fstream>
#include <sstream>

#include <fmt/core.h>

#include "core/io/atomic_file.h"
#include "core/io/input_error.h"
#include "experiments/sweep/json_value.h"

namespace arbor {

std::optional<SweepManifest> read_manifest(const std::string& dir) {
  const std::string path = dir + "/" + kSweepManifest;
  std::ifstream in(path);
  if (!in) return std::nullopt;
  std::stringstream text;
  text << in.rdbuf();
  const JsonValue doc = parse_json(text.str(), path);
  const auto string_member = [&](const char* name) {
    const JsonValue* v = doc.find(name);
    if (!v || v->kind != JsonValue::Kind::kString) throw InputError(path, 0, name, "missing or not a string");
    return v->text;
  };
  SweepManifest m;
  m.spec_hash = string_member("spec_hash");
  m.spec_name = string_member("spec_name");
  m.shard = string_member("shard");
  if (const JsonValue* v = doc.find("grid_runs"); v && v->kind == JsonValue::Kind::kNumber) m.grid_runs = std::stoi(v->text);
  const JsonValue* columns = doc.find("columns");
  if (!columns || columns->kind != JsonValue::Kind::kArray) throw InputError(path, 0, "columns", "missing or not an array");
  for (const auto& c : columns->items) m.columns.push_back(c.text);
  return m;
}

void write_manifest(const std::string& dir, const SweepManifest& m) {
  std::string columns;
  for (const auto& c : m.columns) columns += (columns.empty() ? "" : ", ") + json_quote(c);
  write_file_atomically(dir + "/" + kSweepManifest,
                        fmt::format("{{\n  \"format\": \"arbor-sweep 1\",\n  \"spec_hash\": {},\n  \"spec_name\": {},\n"
                                    "  \"shard\": {},\n  \"grid_runs\": {},\n  \"columns\": [{}]\n}}\n",
                                    json_quote(m.spec_hash), json_quote(m.spec_name), json_quote(m.shard), m.grid_runs,
                                    columns));
}

}  // namespace arbor
