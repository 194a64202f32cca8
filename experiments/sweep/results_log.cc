// Reading and appending sweep result rows; see results_log.h.
#include "experiments/sweep/results_log.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include <fmt/core.h>

#include "core/io/atomic_file.h"
#include "core/io/input_error.h"
#include "experiments/sweep/grid_columns.h"

namespace arbor {
namespace {

// The grid's columns (grid_columns.inc), then where the run's scenario and files are.
const std::vector<std::string>& param_columns() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> out;
    for (const GridColumn& c : kGridColumns) out.emplace_back(c.name);
    out.insert(out.end(), {"scenario", "run_dir"});
    return out;
  }();
  return names;
}

std::string csv_escape(const std::string& cell) {
  if (cell.find_first_of(",\"\n\r") == std::string::npos) return cell;
  std::string out = "\"";
  for (const char c : cell) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

}  // namespace

std::vector<std::string> result_columns(const std::vector<std::string>& metrics,
                                        const std::vector<std::string>& run_options) {
  std::vector<std::string> columns{"key", "status", "error"};
  columns.insert(columns.end(), param_columns().begin(), param_columns().end());
  // The grid's further run options, after the parameters (before scenario and run_dir).
  columns.insert(std::find(columns.begin(), columns.end(), "scenario"), run_options.begin(), run_options.end());
  for (const auto& m : metrics)
    if (std::find(columns.begin(), columns.end(), m) == columns.end()) columns.push_back(m);
  for (const char* c : {"commit", "host", "compiler", "build", "process_wall_s", "exit_code", "finished_at"})
    if (std::find(columns.begin(), columns.end(), c) == columns.end()) columns.emplace_back(c);
  return columns;
}

std::vector<std::pair<std::string, nlohmann::ordered_json>> param_cells(const RunParams& run) {
  using Json = nlohmann::ordered_json;
  const bool sim = run.dataset.empty();
  const auto sim_only = [&](Json v) { return sim ? v : Json(); };
  std::vector<std::pair<std::string, nlohmann::ordered_json>> cells{
      {"key", run.key()},
      {"dataset", sim ? Json() : Json(run.dataset)},
      {"world", sim_only(run.world)},
      {"world_landmarks", sim_only(run.world_landmarks)},
      {"world_steps", sim_only(run.world_steps)},
      {"clutter", sim_only(run.clutter)},
      {"world_seed", sim_only(run.simulation_seed())},
      {"filter", run.filter},
      {"map", run.map.empty() ? Json() : Json(run.map)},
      {"assoc", run.assoc},
      {"particles", run.particles > 0 ? Json(run.particles) : Json()},
      {"seed", run.seed},
      {"threads", run.threads},
  };
  for (const auto& [name, value] : run.run_options) cells.emplace_back(name, value);
  cells.insert(cells.end(), {
      {"scenario", sim ? "scenarios/" + run.scenario_name() + ".scn" : run.dataset},
      {"run_dir", "runs/" + run.key()},
  });
  return cells;
}

std::string cell_text(const nlohmann::ordered_json& value) {
  if (value.is_null()) return {};
  if (value.is_string()) return value.get<std::string>();
  return value.dump();
}

std::vector<ResultRow> read_result_rows(const std::string& jsonl_path, std::vector<int>* lines) {
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
    ResultRow row;
    try {
      row = ResultRow::parse(body);
    } catch (const nlohmann::json::exception& e) {  // parse errors, and numbers beyond a double (1e999)
      throw InputError(jsonl_path, line, "row", fmt::format("malformed JSON row: {}", e.what()));
    }
    if (!row.is_object() || !row.contains("key") || !row["key"].is_string())
      throw InputError(jsonl_path, line, "key", "a result row must be a JSON object with a string 'key'");
    rows.push_back(std::move(row));
    if (lines) lines->push_back(line);
  }
  return rows;
}

std::vector<ResultRow> last_row_of_each_key(std::vector<ResultRow> rows) {
  std::map<std::string, std::size_t> last_of_key;
  for (std::size_t i = 0; i < rows.size(); ++i) last_of_key[rows[i]["key"].get<std::string>()] = i;
  std::vector<ResultRow> kept;
  for (std::size_t i = 0; i < rows.size(); ++i)
    if (last_of_key[rows[i]["key"].get<std::string>()] == i) kept.push_back(std::move(rows[i]));
  return kept;
}

bool has_ok_row_of_dataset(const std::string& dir, const std::string& dataset) {
  for (const ResultRow& row : read_result_rows(dir + "/" + kResultsJsonl))
    if (row.value("status", std::string()) == "ok" && row.contains("dataset") && row["dataset"] == dataset) return true;
  return false;
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
    const auto it = row.find(columns[i]);
    out += (i ? "," : "") + csv_escape(it != row.end() ? cell_text(*it) : std::string());
  }
  return out + "\n";
}

void append_result_row(const std::string& dir, const ResultRow& row, const std::vector<std::string>& columns) {
  // JSONL first: it decides what resume skips. A kill between the two writes leaves the CSV one row short,
  // and the next start regenerates the CSV from the JSONL.
  append_line_durably(dir + "/" + kResultsJsonl, row.dump() + "\n");
  const std::string csv = dir + "/" + kResultsCsv;
  if (!std::filesystem::exists(csv)) append_line_durably(csv, csv_header(columns));
  append_line_durably(csv, csv_line(row, columns));
}

void write_result_files(const std::string& dir, const std::vector<ResultRow>& rows, const std::vector<std::string>& columns) {
  std::string jsonl, csv = csv_header(columns);
  for (const auto& row : rows) {
    jsonl += row.dump() + "\n";
    csv += csv_line(row, columns);
  }
  write_file_atomically(dir + "/" + kResultsJsonl, jsonl);
  write_file_atomically(dir + "/" + kResultsCsv, csv);
}

}  // namespace arbor
