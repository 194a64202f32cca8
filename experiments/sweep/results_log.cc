// Reading and appending sweep result rows; see results_log.h.
#include "experiments/sweep/results_log.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <fmt/core.h>

#include "core/io/atomic_file.h"
#include "core/io/input_error.h"

namespace arbor {
namespace {

const std::vector<std::string>& param_columns() {
  static const std::vector<std::string> names{"dataset", "world", "world_landmarks", "world_steps", "clutter",
                                              "world_seed", "filter", "map", "assoc", "particles", "seed", "threads",
                                              "scenario", "run_dir"};
  return names;
}

std::string csv_escape(const std::string& cell) {
  if (cell.find_first_of(",\"\n\r") == std::string::npos) return cell;
  std::string out = "\"";
  for (const char c : cell) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

std::string number_text(std::int64_t v) { return fmt::format("{}", v); }

}  // namespace

std::vector<std::string> result_columns(const std::vector<std::string>& metrics) {
  std::vector<std::string> columns{"key", "status", "error"};
  columns.insert(columns.end(), param_columns().begin(), param_columns().end());
  for (const auto& m : metrics)
    if (std::find(columns.begin(), columns.end(), m) == columns.end()) columns.push_back(m);
  for (const char* c : {"commit", "host", "compiler", "build", "process_wall_s", "exit_code", "finished_at"})
    if (std::find(columns.begin(), columns.end(), c) == columns.end()) columns.emplace_back(c);
  return columns;
}

std::vector<std::pair<std::string, JsonValue>> param_cells(const RunParams& run) {
  const bool sim = run.dataset.empty();
  const auto num = [](std::int64_t v) { return JsonValue::number(number_text(v)); };
  std::vector<std::pair<std::string, JsonValue>> cells{
      {"key", JsonValue::string(run.key())},
      {"dataset", sim ? JsonValue::null() : JsonValue::string(run.dataset)},
      {"world", sim ? JsonValue::string(run.world) : JsonValue::null()},
      {"world_landmarks", sim ? num(run.world_landmarks) : JsonValue::null()},
      {"world_steps", sim ? num(run.world_steps) : JsonValue::null()},
      {"clutter", sim ? JsonValue::number(fmt::format("{}", run.clutter)) : JsonValue::null()},
      {"world_seed", sim ? num(run.simulation_seed()) : JsonValue::null()},
      {"filter", JsonValue::string(run.filter)},
      {"map", run.map.empty() ? JsonValue::null() : JsonValue::string(run.map)},
      {"assoc", JsonValue::string(run.assoc)},
      {"particles", run.particles > 0 ? num(run.particles) : JsonValue::null()},
      {"seed", num(run.seed)},
      {"threads", num(run.threads)},
      {"scenario", JsonValue::string(sim ? "scenarios/" + run.scenario_name() + ".scn" : run.dataset)},
      {"run_dir", JsonValue::string("runs/" + run.key())},
  };
  return cells;
}

std::vector<ResultRow> read_result_rows(const std::string& jsonl_path) {
  std::vector<ResultRow> rows;
  std::ifstream in(jsonl_path, std::ios::binary);
  if (!in) return rows;
  std::stringstream buffer;
  buffer << in.rdbuf();
  const std::string text = buffer.str();
  std::size_t start = 0;
  int line = 0;
  while (start < text.size()) {
    const std::size_t end = text.find('\n', start);
    if (end == std::string::npos) break;  // an interrupted append: not a row
    ++line;
    const std::string_view body(text.data() + start, end - start);
    start = end + 1;
    if (body.find_first_not_of(" \t\r") == std::string_view::npos) continue;
    ResultRow row = parse_json(body, jsonl_path, line);
    const JsonValue* key = row.find("key");
    if (row.kind != JsonValue::Kind::kObject || !key || key->kind != JsonValue::Kind::kString)
      throw InputError(jsonl_path, line, "key", "a result row must be a JSON object with a string 'key'");
    rows.push_back(std::move(row));
  }
  return rows;
}

void drop_partial_last_line(const std::string& jsonl_path) {
  std::error_code ec;
  const auto size = std::filesystem::file_size(jsonl_path, ec);
  if (ec || size == 0) return;
  std::ifstream in(jsonl_path, std::ios::binary);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (text.empty() || text.back() == '\n') return;
  const std::size_t keep = text.rfind('\n') == std::string::npos ? 0 : text.rfind('\n') + 1;
  std::filesystem::resize_file(jsonl_path, keep);
}

std::string csv_header(const std::vector<std::string>& columns) {
  std::string out;
  for (std::size_t i = 0; i < columns.size(); ++i) out += (i ? "," : "") + csv_escape(columns[i]);
  return out + "\n";
}

std::string csv_line(const ResultRow& row, const std::vector<std::string>& columns) {
  std::string out;
  for (std::size_t i = 0; i < columns.size(); ++i) {
    const JsonValue* v = row.find(columns[i]);
    out += (i ? "," : "") + csv_escape(v ? v->cell() : std::string());
  }
  return out + "\n";
}

void append_result_row(const std::string& dir, const ResultRow& row, const std::vector<std::string>& columns) {
  // JSONL first: it decides what resume skips. A kill between the two writes leaves the CSV one row short,
  // and the next start regenerates the CSV from the JSONL.
  append_line_durably(dir + "/" + kResultsJsonl, row.encode() + "\n");
  const std::string csv = dir + "/" + kResultsCsv;
  if (!std::filesystem::exists(csv)) append_line_durably(csv, csv_header(columns));
  append_line_durably(csv, csv_line(row, columns));
}

void write_result_files(const std::string& dir, const std::vector<ResultRow>& rows, const std::vector<std::string>& columns) {
  std::string jsonl, csv = csv_header(columns);
  for (const auto& row : rows) {
    jsonl += row.encode() + "\n";
    csv += csv_line(row, columns);
  }
  write_file_atomically(dir + "/" + kResultsJsonl, jsonl);
  write_file_atomically(dir + "/" + kResultsCsv, csv);
}

}  // namespace arbor
