// The sweep's result files: DIR/results.jsonl (one JSON object per finished run; the source of truth) and
// DIR/results.csv (the same rows as CSV, regenerated from the JSONL on resume and merge).
// A row is appended with one write() (append_line_durably), so a killed sweep leaves whole rows or none;
// a trailing line without its newline is an interrupted write and is ignored (and cut off on resume).
#ifndef ARBOR_EXPERIMENTS_SWEEP_RESULTS_LOG_H_
#define ARBOR_EXPERIMENTS_SWEEP_RESULTS_LOG_H_

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "experiments/sweep/sweep_spec.h"

namespace arbor {

inline constexpr const char* kResultsJsonl = "results.jsonl";
inline constexpr const char* kResultsCsv = "results.csv";

// The columns of every row, in order: key, status, error, the run parameters, the kept metrics, then
// provenance (commit, host, compiler, build, wall time of the child process, exit code, finish time).
std::vector<std::string> result_columns(const std::vector<std::string>& metrics,
                                        const std::vector<std::string>& run_options = {});

// A row is a JSON object whose members are exactly result_columns(), in that order.
using ResultRow = nlohmann::ordered_json;

// The parameter members of a row (key, then every RunParams field as a column).
std::vector<std::pair<std::string, nlohmann::ordered_json>> param_cells(const RunParams& run);

// A cell as CSV text: strings unquoted, null empty, numbers and booleans as JSON writes them.
std::string cell_text(const nlohmann::ordered_json& value);

// Reads DIR/results.jsonl; a missing file is an empty list. A last line without '\n' is ignored; a complete
// line that is not a JSON object with a string "key" throws InputError naming the line. lines, when given,
// receives each row's line number.
std::vector<ResultRow> read_result_rows(const std::string& jsonl_path, std::vector<int>* lines = nullptr);

// The newest row of each key (a retried run's row after its failed one), in the order of the rows kept.
std::vector<ResultRow> last_row_of_each_key(std::vector<ResultRow> rows);

// Whether DIR/results.jsonl holds a finished ("ok") row of a run on this dataset (its path as the spec writes it).
bool has_ok_row_of_dataset(const std::string& dir, const std::string& dataset);

// Cuts a trailing partial line (a write interrupted by power loss) so the next append starts a fresh line.
void drop_partial_last_line(const std::string& jsonl_path);

std::string csv_header(const std::vector<std::string>& columns);
std::string csv_line(const ResultRow& row, const std::vector<std::string>& columns);

// Appends one row to DIR/results.jsonl, then to DIR/results.csv, each with a single durable write.
void append_result_row(const std::string& dir, const ResultRow& row, const std::vector<std::string>& columns);

// Replaces both files with exactly `rows` (atomic rename each); used on resume and by merge.
void write_result_files(const std::string& dir, const std::vector<ResultRow>& rows, const std::vector<std::string>& columns);

}  // namespace arbor

#endif  // ARBOR_EXPERIMENTS_SWEEP_RESULTS_LOG_H_
