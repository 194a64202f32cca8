// A sweep specification (a TOML file naming the grid) and its expansion into the sorted list of runs.
// The file format is documented in experiments/sweeps/README.md; every error names the file, line and field.
#ifndef ARBOR_EXPERIMENTS_SWEEP_SWEEP_SPEC_H_
#define ARBOR_EXPERIMENTS_SWEEP_SWEEP_SPEC_H_

#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace arbor {

// The parameters of one run: one point of the grid. Exactly one of `dataset` / `world` is set.
struct RunParams {
  std::string dataset;           // scenario file as written in the spec (empty for a simulated world)
  std::string dataset_path;      // the same, resolved against the spec's directory
  std::string world;             // uniform | clustered | rooms (empty for a dataset)
  std::int64_t world_landmarks = 0;
  std::int64_t world_steps = 0;
  double clutter = 0.0;
  std::optional<std::int64_t> world_seed;  // fixed world; unset: the run's seed also seeds the simulation
  std::string filter;            // fastslam1 | fastslam2 | smoother
  std::string map;               // empty for the smoother
  std::string assoc;
  std::int64_t particles = 0;    // 0 for the smoother
  std::int64_t seed = 0;
  std::int64_t threads = 1;
  // Further `arbor run` options the grid varies (name without "--", value as the child gets it), sorted
  // by name; any option experiments/options/run_options.cc defines and the sweep does not set itself.
  std::vector<std::pair<std::string, std::string>> run_options;

  // Stable, human-readable identity of the parameter tuple; also the run's directory name.
  std::string key() const;
  // Name of the cached simulated scenario (without directory), empty for a dataset.
  std::string scenario_name() const;
  std::int64_t simulation_seed() const { return world_seed.value_or(seed); }
};

// Total order of the grid (parameters compared field by field, numbers numerically); --shard splits by
// index in this order, so every machine computes the same split from the same spec.
bool operator<(const RunParams& a, const RunParams& b);

struct SweepSpec {
  std::string path;             // the spec file
  std::string name;
  std::string description;
  std::vector<std::string> metrics;  // result.json fields kept in each row, in column order
  std::optional<int> jobs;           // default parallel runs (--jobs overrides)
  double timeout_s = 0.0;            // per-run wall-clock limit; 0 = none
  std::vector<RunParams> runs;       // the expanded grid, sorted, without duplicates
  std::vector<std::string> run_option_names;  // the further run options the grid names, sorted
  std::string hash;                  // 16 hex digits over the grid and the metrics: equal specs, equal hash
};

// The metrics kept when the spec names none: DESIGN.md §9's result.json fields (smoother fields added
// when the grid has smoother runs).
std::vector<std::string> default_metrics(bool with_smoother);

// Reads and validates a spec, and expands the grid. Throws InputError(file, line, field, why) on any
// problem: TOML syntax, unknown table or key, unknown filter/map/assoc/world, bad range or value, a missing
// required field, a dataset or prior map that does not exist. Nothing is run; nothing is written.
// inputs_must_exist = false skips only the last check, for a reader that needs the grid's keys and never opens
// those files (merge reads the copy DIR/spec.toml, where their relative paths no longer resolve).
SweepSpec read_sweep_spec(const std::string& path, bool inputs_must_exist = true);

// The names the spec accepts: DESIGN.md §9 filters and worlds, the registry's map back ends and strategies.
const std::vector<std::string>& known_filters();
const std::vector<std::string>& known_maps();
const std::vector<std::string>& known_assocs();
const std::vector<std::string>& known_worlds();
// The scalar fields of result.json a sweep can keep as metrics: those of `arbor run`, then those only
// `arbor smooth` writes. A name outside this list is a typo (it used to give a column of nulls).
const std::vector<std::string>& known_metrics();

// 64-bit FNV-1a as 16 hex digits; stable across machines and builds.
std::string stable_hash(std::string_view text);

}  // namespace arbor

#endif  // ARBOR_EXPERIMENTS_SWEEP_SWEEP_SPEC_H_
