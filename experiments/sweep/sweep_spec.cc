// Reading, validating and expanding sweep specs (TOML, parsed by toml++); see sweep_spec.h.
#include "experiments/sweep/sweep_spec.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <set>
#include <string_view>
#include <tuple>

#include <fmt/core.h>
#include <fmt/format.h>
#include <toml++/toml.h>

#include "core/io/input_error.h"
#include "experiments/options/run_options.h"
#include "variants/filter_list.h"
#include "variants/registry.h"

namespace arbor {
namespace {

constexpr std::int64_t kMaxGridSize = 1'000'000;  // a typo like to = 1e9 must not hang the expansion

// Where a node came from, for messages; toml++ records the position of every node and key.
int line_of(const toml::node& node) { return static_cast<int>(node.source().begin.line); }

class SpecReader {
 public:
  explicit SpecReader(std::string path) : path_(std::move(path)) {}

  [[noreturn]] void fail(int line, std::string_view field, const std::string& why) const {
    throw InputError(path_, line, std::string(field), why);
  }

  // Rejects keys a table does not know: a typo ("partciles") must not silently drop a dimension.
  void only_keys(const toml::table& table, std::string_view table_name, const std::vector<std::string_view>& allowed) const {
    for (auto&& [key, node] : table) {
      if (std::find(allowed.begin(), allowed.end(), key.str()) != allowed.end()) continue;
      std::string list;
      for (const auto a : allowed) list += (list.empty() ? "" : ", ") + std::string(a);
      fail(static_cast<int>(key.source().begin.line), qualified(table_name, key.str()),
           fmt::format("unknown key (known in [{}]: {})", table_name, list));
    }
  }

  static std::string qualified(std::string_view table, std::string_view key) {
    return table.empty() ? std::string(key) : fmt::format("{}.{}", table, key);
  }

  // A list of strings: a single string or an array of strings, each one of `known`.
  std::vector<std::string> names(const toml::node& node, const std::string& field, const std::vector<std::string>& known) const {
    std::vector<std::string> out;
    const auto take = [&](const toml::node& item) {
      const auto* s = item.as_string();
      if (!s) fail(line_of(item), field, fmt::format("expected a string, got {}", type_name(item)));
      const std::string& value = s->get();
      if (!known.empty() && std::find(known.begin(), known.end(), value) == known.end())
        fail(line_of(item), field, fmt::format("unknown value '{}' (known: {})", value, join(known)));
      out.push_back(value);
    };
    for_each_item(node, field, take);
    return out;
  }

  // A list of integers in [lo, hi]: an integer, an array of integers, or a range table
  // {from, to, step} (arithmetic) or {from, to, factor} (geometric: from, from*factor, ... <= to).
  std::vector<std::int64_t> integers(const toml::node& node, const std::string& field, std::int64_t lo, std::int64_t hi) const {
    std::vector<std::int64_t> out;
    const auto check = [&](const toml::node& item, std::int64_t v) {
      if (v < lo || v > hi) fail(line_of(item), field, fmt::format("value {} out of range [{}, {}]", v, lo, hi));
      out.push_back(v);
    };
    if (const auto* range = node.as_table()) {
      only_keys(*range, field, {"from", "to", "step", "factor"});
      const std::int64_t from = integer_member(*range, field, "from", true, 0);
      const std::int64_t to = integer_member(*range, field, "to", true, 0);
      const bool has_step = range->contains("step"), has_factor = range->contains("factor");
      if (has_step && has_factor) fail(line_of(node), field, "a range has either 'step' or 'factor', not both");
      if (from > to) fail(line_of(node), field, fmt::format("bad range: from = {} is greater than to = {}", from, to));
      // Endpoints first: with both inside [lo, hi] the step arithmetic below cannot overflow.
      if (from < lo || to > hi) fail(line_of(node), field, fmt::format("bad range: [{}, {}] goes outside [{}, {}]", from, to, lo, hi));
      if (has_factor) {
        const std::int64_t factor = integer_member(*range, field, "factor", true, 0);
        if (factor < 2) fail(line_of(node), field, fmt::format("bad range: factor must be at least 2, got {}", factor));
        for (std::int64_t v = from; v <= to; v *= factor) {
          if (v <= 0) fail(line_of(node), field, "bad range: a geometric range must start above 0");
          check(node, v);
          if (out.size() > kMaxGridSize || v > to / factor) break;
        }
      } else {
        const std::int64_t step = integer_member(*range, field, "step", false, 1);
        if (step <= 0) fail(line_of(node), field, fmt::format("bad range: step must be positive, got {}", step));
        if ((to - from) / step >= kMaxGridSize) fail(line_of(node), field, "bad range: more than a million values");
        for (std::int64_t v = from; v <= to; v += step) check(node, v);
      }
      return out;
    }
    for_each_item(node, field, [&](const toml::node& item) {
      const auto* v = item.as_integer();
      if (!v) fail(line_of(item), field, fmt::format("expected an integer, got {}", type_name(item)));
      check(item, v->get());
    });
    return out;
  }

  // A run option's values as `arbor run` reads them, each with its line: a string, number or boolean, or an
  // array of them.
  std::vector<std::pair<int, std::string>> option_values(const toml::node& node, const std::string& field) const {
    std::vector<std::pair<int, std::string>> out;
    for_each_item(node, field, [&](const toml::node& item) {
      std::string text;
      if (const auto* s = item.as_string()) text = s->get();
      else if (const auto* i = item.as_integer()) text = fmt::format("{}", i->get());
      else if (const auto* f = item.as_floating_point()) text = fmt::format("{}", f->get());
      else if (const auto* b = item.as_boolean()) text = b->get() ? "true" : "false";
      else fail(line_of(item), field, fmt::format("expected a string, number or boolean, got {}", type_name(item)));
      out.emplace_back(line_of(item), std::move(text));
    });
    return out;
  }

  // A list of reals in [lo, hi]: a number, an array of numbers, or a range table {from, to, step}.
  std::vector<double> reals(const toml::node& node, const std::string& field, double lo, double hi) const {
    std::vector<double> out;
    const auto check = [&](const toml::node& item, double v) {
      if (!std::isfinite(v) || v < lo || v > hi) fail(line_of(item), field, fmt::format("value {} out of range [{}, {}]", v, lo, hi));
      out.push_back(v);
    };
    if (const auto* range = node.as_table()) {
      only_keys(*range, field, {"from", "to", "step"});
      const double from = real_member(*range, field, "from");
      const double to = real_member(*range, field, "to");
      const double step = real_member(*range, field, "step");
      if (from > to) fail(line_of(node), field, fmt::format("bad range: from = {} is greater than to = {}", from, to));
      if (!(step > 0.0)) fail(line_of(node), field, fmt::format("bad range: step must be positive, got {}", step));
      if (from < lo || to > hi) fail(line_of(node), field, fmt::format("bad range: [{}, {}] goes outside [{}, {}]", from, to, lo, hi));
      if ((to - from) / step >= kMaxGridSize) fail(line_of(node), field, "bad range: more than a million values");
      // Values are from + i*step (never accumulated), so 0.1-steps do not drift; 'to' is kept within 1e-9 steps.
      for (std::int64_t i = 0;; ++i) {
        const double v = from + static_cast<double>(i) * step;
        if (v > to + 1e-9 * step) break;
        check(node, std::min(v, to));
      }
      return out;
    }
    for_each_item(node, field, [&](const toml::node& item) {
      double v = 0.0;
      if (const auto* i = item.as_integer()) v = static_cast<double>(i->get());
      else if (const auto* f = item.as_floating_point()) v = f->get();
      else fail(line_of(item), field, fmt::format("expected a number, got {}", type_name(item)));
      check(item, v);
    });
    return out;
  }

  const std::string& path() const { return path_; }

  static std::string join(const std::vector<std::string>& names) {
    std::string out;
    for (const auto& n : names) out += (out.empty() ? "" : ", ") + n;
    return out;
  }

 private:
  template <class F>
  void for_each_item(const toml::node& node, const std::string& field, F&& f) const {
    if (const auto* array = node.as_array()) {
      if (array->empty()) fail(line_of(node), field, "empty list: a grid dimension needs at least one value");
      for (const auto& item : *array) f(item);
    } else if (node.is_table()) {
      fail(line_of(node), field, "a range table is not allowed here");
    } else {
      f(node);
    }
  }

  static std::string type_name(const toml::node& node) {
    switch (node.type()) {
      case toml::node_type::string: return "a string";
      case toml::node_type::integer: return "an integer";
      case toml::node_type::floating_point: return "a real number";
      case toml::node_type::boolean: return "a boolean";
      case toml::node_type::array: return "an array";
      case toml::node_type::table: return "a table";
      default: return "a date or time";
    }
  }

  std::int64_t integer_member(const toml::table& t, const std::string& field, std::string_view key, bool required,
                              std::int64_t fallback) const {
    const toml::node* n = t.get(key);
    if (!n) {
      if (required) fail(line_of(t), field, fmt::format("range needs '{}'", key));
      return fallback;
    }
    const auto* v = n->as_integer();
    if (!v) fail(line_of(*n), qualified(field, key), "expected an integer");
    return v->get();
  }

  double real_member(const toml::table& t, const std::string& field, std::string_view key) const {
    const toml::node* n = t.get(key);
    if (!n) fail(line_of(t), field, fmt::format("range needs '{}'", key));
    if (const auto* i = n->as_integer()) return static_cast<double>(i->get());
    // TOML has nan and inf: a range ending at nan never ends (every comparison with it is false).
    if (const auto* f = n->as_floating_point(); f && std::isfinite(f->get())) return f->get();
    fail(line_of(*n), qualified(field, key), "expected a finite number");
  }

  std::string path_;
};

std::string sanitize(std::string_view text) {
  std::string out;
  for (const char c : text) out.push_back(std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '-' ? c : '_');
  return out;
}

auto tie(const RunParams& p) {
  return std::tie(p.dataset, p.world, p.world_landmarks, p.world_steps, p.clutter, p.world_seed, p.filter, p.map,
                  p.assoc, p.particles, p.seed, p.threads, p.run_options);
}

// The traits of a filter the spec reader has already checked against the list.
const FilterTraits& traits_of(std::string_view filter) { return listed_filter(filter).traits; }

}  // namespace

const std::vector<std::string>& known_filters() {
  static const std::vector<std::string> names = filter_names();
  return names;
}
// Map back ends and strategies come from the registry, so a spec is checked against what this build can run.
const std::vector<std::string>& known_maps() {
  static const std::vector<std::string> names = map_backend_names();
  return names;
}
const std::vector<std::string>& known_assocs() {
  static const std::vector<std::string> names = association_names();
  return names;
}
const std::vector<std::string>& known_worlds() {
  static const std::vector<std::string> names{"uniform", "clustered", "rooms"};
  return names;
}

const std::vector<std::string>& known_metrics() {
  // tests/experiments/sweep_spec_test.cc checks this list against the result.json of a real run and solve.
  static const std::vector<std::string> names{
      // arbor run
      "assoc_f1", "assoc_precision", "assoc_recall", "ate_aligned", "ate_aligned_rmse_m", "ate_mean_rmse_m",
      "ate_best_aligned_rmse_m", "ate_best_rmse_m",
      "ate_rmse_m", "budget_exhausted", "compatibility_tests", "consistency_horizon_fraction",
      "consistency_horizon_scan", "dead_reckoning_ate_m", "hypotheses",
      "landmark_rmse_m", "landmarks", "loop_closures", "map_bytes_per_particle", "map_shared_fraction", "n_eff_mean",
      "nees_in_band_fraction", "nees_mean", "nees_median", "observed_true_landmarks", "peak_rss_bytes",
      "move_acceptance", "provisional_landmarks", "rejected_measurements", "relocalizations", "resamples",
      "scan_time_median_s", "scan_time_p90_s", "scans", "scenario_duration_s",
      "spurious_landmarks", "step_time_median_s", "step_time_p95_s", "steps", "true_landmarks", "wall_time_s",
      // arbor smooth only
      "associations_used", "build_time_s", "factors", "final_cost", "gradient_max_norm", "initial_cost",
      "iterations", "linear_solver_used", "marginals_time_s", "parameters", "pose_marginals", "poses", "residuals",
      "solution_usable", "solve_cpu_s", "solve_time_s", "termination"};
  return names;
}

std::vector<std::string> default_metrics(bool with_smoother) {
  // DESIGN.md §9's fields, then the engine statistics `arbor run` adds (absent ones are recorded as null).
  std::vector<std::string> m{"ate_rmse_m",         "landmark_rmse_m", "nees_mean",      "assoc_precision",
                             "assoc_recall",       "assoc_f1",        "landmarks",      "steps",
                             "step_time_median_s", "step_time_p95_s", "wall_time_s",    "peak_rss_bytes",
                             "ate_mean_rmse_m",    "true_landmarks",  "n_eff_mean",     "hypotheses",
                             "compatibility_tests", "map_bytes_per_particle", "nees_median",
                             "nees_in_band_fraction", "rejected_measurements",
                             // issue 41: the failure rate needs the aligned ATE beside the smoother's and dead
                             // reckoning's; the consistency horizon says from when a run is overconfident
                             "ate_aligned_rmse_m", "dead_reckoning_ate_m", "consistency_horizon_scan",
                             // issue 44: on real logs most steps are odometry only; the report times scans
                             "scan_time_median_s", "scan_time_p90_s", "scans"};
  if (with_smoother) m.insert(m.end(), {"solve_time_s", "iterations", "initial_cost", "final_cost", "termination"});
  return m;
}

std::string stable_hash(std::string_view text) {
  std::uint64_t h = 0xcbf29ce484222325ULL;
  for (const char c : text) {
    h ^= static_cast<unsigned char>(c);
    h *= 0x100000001b3ULL;
  }
  return fmt::format("{:016x}", h);
}

std::string RunParams::scenario_name() const {
  if (world.empty()) return {};
  return fmt::format("{}-n{}-t{}-c{}-s{}", world, world_landmarks, world_steps, sanitize(fmt::format("{}", clutter)),
                     simulation_seed());
}

std::string RunParams::key() const {
  // The scenario part names a dataset by its file stem plus a hash of the path as written, so two files
  // called data.scn in different folders get different keys, and the key does not depend on where the
  // sweep runs (shards on other machines resolve the path differently).
  std::string scenario;
  if (!dataset.empty()) {
    scenario = fmt::format("{}-{}", sanitize(std::filesystem::path(dataset).stem().string()), stable_hash(dataset).substr(0, 8));
  } else {
    scenario = fmt::format("{}-n{}-t{}-c{}", world, world_landmarks, world_steps, sanitize(fmt::format("{}", clutter)));
    if (world_seed) scenario += fmt::format("-w{}", *world_seed);
  }
  // Further run options, where the grid names any, follow as __name-value_name-value.
  std::string options;
  // A value that sanitising changes gets a hash of itself: `m+1.csv` and `m 1.csv` both sanitise to m_1.csv,
  // and one key for two runs made the grid one run short.
  const auto option_text = [](const std::string& value) {
    const std::string safe = sanitize(value);
    return safe == value ? safe : fmt::format("{}-{}", safe, stable_hash(value).substr(0, 8));
  };
  for (const auto& [name, value] : run_options) options += fmt::format("{}{}-{}", options.empty() ? "__" : "_", name, option_text(value));
  // The key names only the dimensions the filter has (fastslam2-tree-jcbb-m100, smoother).
  const FilterTraits traits = traits_of(filter);
  std::string method = filter;
  if (traits.has_map_backends) method += "-" + map;
  if (traits.chooses_association) method += "-" + assoc;
  if (traits.has_particles) method += fmt::format("-m{}", particles);
  return fmt::format("{}__{}-s{}-t{}{}", scenario, method, seed, threads, options);
}

bool operator<(const RunParams& a, const RunParams& b) { return tie(a) < tie(b); }

namespace {

// A run option's value as `arbor run` reads it: a number by its value, a switch as true or false (empty for
// any other spelling), a name as written.
std::string setting_of(const std::string& option, const std::string& value) {
  static const std::vector<cli::RunOptionInfo> infos = cli::run_option_info();
  const auto info = std::find_if(infos.begin(), infos.end(), [&](const auto& i) { return i.name == option; });
  const std::string type = info == infos.end() ? "str" : info->type;
  if (type == "bool") return value == "true" || value == "false" ? value : std::string();
  if (type == "int" || type == "float") return fmt::format("{}", std::strtod(value.c_str(), nullptr));
  return value;
}

}  // namespace

SweepSpec read_sweep_spec(const std::string& path, bool inputs_must_exist) {
  SpecReader in(path);
  if (!std::filesystem::exists(path)) throw InputError(path, 0, "", "sweep spec not found");
  toml::table root;
  try {
    root = toml::parse_file(path);
  } catch (const toml::parse_error& e) {
    throw InputError(path, static_cast<int>(e.source().begin.line), "", fmt::format("TOML syntax: {}", e.description()));
  }
  in.only_keys(root, "", {"sweep", "scenarios", "grid"});
  const auto table = [&](std::string_view name, bool required) -> const toml::table* {
    const toml::node* n = root.get(name);
    if (!n) {
      if (required) in.fail(1, name, fmt::format("missing table [{}]", name));
      return nullptr;
    }
    if (!n->is_table()) in.fail(line_of(*n), name, "expected a table");
    return n->as_table();
  };

  SweepSpec spec;
  spec.path = path;
  spec.name = std::filesystem::path(path).stem().string();

  // [sweep]: name, description, metrics, jobs, timeout_s. All optional.
  bool explicit_metrics = false;
  if (const toml::table* sweep = table("sweep", false)) {
    in.only_keys(*sweep, "sweep", {"name", "description", "metrics", "jobs", "timeout_s"});
    if (const auto* n = sweep->get("name")) spec.name = in.names(*n, "sweep.name", {}).front();
    if (const auto* n = sweep->get("description")) spec.description = in.names(*n, "sweep.description", {}).front();
    if (const auto* n = sweep->get("metrics")) {
      for (const auto& m : in.names(*n, "sweep.metrics", {})) {
        if (m.empty() || !std::all_of(m.begin(), m.end(), [](char c) { return std::islower(static_cast<unsigned char>(c)) || std::isdigit(static_cast<unsigned char>(c)) || c == '_'; }))
          in.fail(line_of(*n), "sweep.metrics", fmt::format("'{}' is not a result.json field name", m));
        if (std::find(known_metrics().begin(), known_metrics().end(), m) == known_metrics().end())
          in.fail(line_of(*n), "sweep.metrics",
                  fmt::format("'{}' is not a field of result.json (known: {})", m, fmt::join(known_metrics(), ", ")));
        if (std::find(spec.metrics.begin(), spec.metrics.end(), m) == spec.metrics.end()) spec.metrics.push_back(m);
      }
      explicit_metrics = true;
    }
    if (const auto* n = sweep->get("jobs")) spec.jobs = static_cast<int>(in.integers(*n, "sweep.jobs", 1, 1024).front());
    if (const auto* n = sweep->get("timeout_s")) spec.timeout_s = in.reals(*n, "sweep.timeout_s", 0.0, 1e7).front();
  }

  // [scenarios]: datasets and/or simulated worlds.
  const toml::table* scenarios = table("scenarios", true);
  in.only_keys(*scenarios, "scenarios", {"datasets", "world", "landmarks", "steps", "clutter", "world_seed"});
  std::vector<RunParams> bases;
  if (const auto* n = scenarios->get("datasets")) {
    const std::filesystem::path spec_dir = std::filesystem::path(path).parent_path();
    const auto check_one = [&](const toml::node& item) {
      RunParams p;
      p.dataset = in.names(item, "scenarios.datasets", {}).front();
      const std::filesystem::path resolved = std::filesystem::path(p.dataset).is_absolute() ? std::filesystem::path(p.dataset) : spec_dir / p.dataset;
      if (inputs_must_exist && !std::filesystem::is_regular_file(resolved))
        in.fail(line_of(item), "scenarios.datasets", fmt::format("dataset '{}' not found (looked for {})", p.dataset, resolved.string()));
      p.dataset_path = resolved.lexically_normal().string();
      bases.push_back(p);
    };
    if (const auto* array = n->as_array()) {
      if (array->empty()) in.fail(line_of(*n), "scenarios.datasets", "empty list");
      for (const auto& item : *array) check_one(item);
    } else {
      check_one(*n);
    }
  }
  if (const auto* n = scenarios->get("world")) {
    const auto worlds = in.names(*n, "scenarios.world", known_worlds());
    const auto need = [&](std::string_view key) -> const toml::node& {
      const toml::node* m = scenarios->get(key);
      if (!m) in.fail(line_of(*scenarios), fmt::format("scenarios.{}", key), "missing field (a simulated world needs landmarks and steps)");
      return *m;
    };
    const auto landmarks = in.integers(need("landmarks"), "scenarios.landmarks", 1, 100'000'000);
    const auto steps = in.integers(need("steps"), "scenarios.steps", 1, 100'000'000);
    std::vector<double> clutter{0.0};
    if (const auto* c = scenarios->get("clutter")) clutter = in.reals(*c, "scenarios.clutter", 0.0, 10'000.0);
    std::optional<std::int64_t> world_seed;
    if (const auto* s = scenarios->get("world_seed")) world_seed = in.integers(*s, "scenarios.world_seed", 0, INT64_C(1) << 53).front();
    for (const auto& w : worlds)
      for (const auto n_lm : landmarks)
        for (const auto t : steps)
          for (const auto c : clutter) {
            RunParams p;
            p.world = w;
            p.world_landmarks = n_lm;
            p.world_steps = t;
            p.clutter = c;
            p.world_seed = world_seed;
            bases.push_back(p);
          }
  } else {
    for (const std::string_view key : {"landmarks", "steps", "clutter", "world_seed"})
      if (const auto* m = scenarios->get(key)) in.fail(line_of(*m), fmt::format("scenarios.{}", key), "only meaningful with 'world'");
  }
  if (bases.empty()) in.fail(line_of(*scenarios), "scenarios", "missing field: name 'datasets' or a simulated 'world'");

  // [grid]: the method dimensions.
  const toml::table* grid = table("grid", true);
  std::vector<std::string_view> grid_keys{"filter", "map", "assoc", "particles", "seed", "threads"};
  for (const std::string& name : cli::sweepable_run_options()) grid_keys.push_back(name);
  in.only_keys(*grid, "grid", grid_keys);
  const auto need = [&](std::string_view key) -> const toml::node& {
    const toml::node* m = grid->get(key);
    if (!m) in.fail(line_of(*grid), fmt::format("grid.{}", key), "missing field");
    return *m;
  };
  const auto filters = in.names(need("filter"), "grid.filter", known_filters());
  // A dimension is asked for when some filter of the grid has it; a filter without it runs once per scenario
  // and seed whatever its values (the smoother: no map, no choice of association, no particles).
  const auto any = [&](bool FilterTraits::*trait) {
    return std::any_of(filters.begin(), filters.end(), [&](const auto& f) { return traits_of(f).*trait; });
  };
  std::vector<std::string> maps, assocs;
  std::vector<std::int64_t> particles;
  if (any(&FilterTraits::has_map_backends)) maps = in.names(need("map"), "grid.map", known_maps());
  if (any(&FilterTraits::chooses_association)) assocs = in.names(need("assoc"), "grid.assoc", known_assocs());
  if (any(&FilterTraits::has_particles)) particles = in.integers(need("particles"), "grid.particles", 1, 10'000'000);
  const auto seeds = in.integers(need("seed"), "grid.seed", 0, INT64_C(1) << 53);
  std::vector<std::int64_t> threads{1};
  if (const auto* n = grid->get("threads")) threads = in.integers(*n, "grid.threads", 1, 1024);

  // Every further run option named in the grid, each value checked as `arbor run` itself would parse it.
  std::vector<std::vector<std::pair<std::string, std::string>>> option_sets{{}};
  for (const std::string& name : cli::sweepable_run_options()) {
    const toml::node* node = grid->get(name);
    if (!node) continue;
    spec.run_option_names.push_back(name);
    const std::string field = "grid." + name;
    std::vector<std::pair<std::string, std::string>> values;
    std::map<std::string, std::pair<std::string, int>> spelling_of;  // what a value means -> its text and line
    for (const auto& [line, value] : in.option_values(*node, field)) {
      // --prior-map's check is that the file exists (from the working directory): skipped with the datasets'.
      const bool file_check_only = name == "prior-map" && !inputs_must_exist;
      if (const std::string error = file_check_only ? std::string() : cli::run_option_error(name, value); !error.empty())
        in.fail(line, field, error);
      // Two spellings of one setting ("0.9" and "0.90", true and 1) made two grid points of one configuration,
      // split apart in the analysis (hostile B11). The run key keeps the text as written, so a switch takes
      // true or false only, and a second spelling of a value already listed is refused.
      const std::string meaning = setting_of(name, value);
      if (meaning.empty())
        in.fail(line, field, fmt::format("a switch takes true or false (got '{}'), so that one setting has one run key", value));
      const auto [first, inserted] = spelling_of.emplace(meaning, std::make_pair(value, line));
      if (!inserted && first->second.first != value)
        in.fail(line, field, fmt::format("'{}' is the same setting as '{}' at line {}: it would run every grid point "
                                         "twice under two keys",
                                         value, first->second.first, first->second.second));
      values.emplace_back(name, value);
    }
    std::vector<std::vector<std::pair<std::string, std::string>>> grown;
    for (const auto& set : option_sets)
      for (const auto& v : values) {
        grown.push_back(set);
        grown.back().push_back(v);
        if (static_cast<std::int64_t>(grown.size()) > kMaxGridSize) in.fail(line_of(*node), field, "more than a million runs");
      }
    option_sets = std::move(grown);
  }

  std::set<std::string> seen;
  // Options that do not combine (`--assoc known` with `--close-loops`, ...) would fail each such run with exit 2
  // once the sweep is under way; the grid is refused instead, checked once per distinct combination.
  std::set<std::string> combinations_checked;
  const auto check_combination = [&](const RunParams& p) {
    std::vector<std::string> arguments{"--filter=" + p.filter, "--assoc=" + p.assoc};
    for (const auto& [name, value] : p.run_options) arguments.push_back("--" + name + "=" + value);
    std::string combination;
    for (const std::string& a : arguments) combination += a + "\n";
    if (!combinations_checked.insert(combination).second) return;
    try {
      cli::run_config_from_arguments(arguments);
    } catch (const InputError& e) {
      in.fail(line_of(*grid), "grid", fmt::format("run {} combines options that do not combine: {}", p.key(), e.what()));
    }
  };
  const auto add = [&](RunParams p) {
    // A batch filter takes none of `arbor run`'s options: one run, whatever they are.
    const bool batch = traits_of(p.filter).is_batch;
    const std::size_t sets = batch ? 1 : option_sets.size();
    for (std::size_t i = 0; i < sets; ++i) {
      if (static_cast<std::int64_t>(spec.runs.size()) >= kMaxGridSize) in.fail(line_of(*grid), "grid", "more than a million runs");
      p.run_options = batch ? std::vector<std::pair<std::string, std::string>>{} : option_sets[i];
      if (!batch) check_combination(p);
      if (seen.insert(p.key()).second) spec.runs.push_back(p);
    }
  };
  for (const auto& base : bases)
    for (const auto& f : filters)
      for (const auto seed : seeds)
        for (const auto t : threads) {
          RunParams p = base;
          p.filter = f;
          p.seed = seed;
          p.threads = t;
          const FilterTraits& traits = traits_of(f);
          for (const auto& m : traits.has_map_backends ? maps : std::vector<std::string>{""})
            for (const auto& a : traits.chooses_association ? assocs : std::vector<std::string>{"known"})
              for (const auto n : traits.has_particles ? particles : std::vector<std::int64_t>{0}) {
                p.map = m;
                p.assoc = a;
                p.particles = n;
                add(p);
              }
        }
  std::sort(spec.runs.begin(), spec.runs.end());

  if (!explicit_metrics) spec.metrics = default_metrics(any(&FilterTraits::is_batch));
  // The hash covers what makes rows comparable: the grid and the columns. Comments, spacing and the order
  // of list entries do not change it.
  std::string canonical = "arbor-sweep 1\n";
  for (const auto& m : spec.metrics) canonical += "metric " + m + "\n";
  for (const auto& r : spec.runs) canonical += r.key() + "\n";
  spec.hash = stable_hash(canonical);
  return spec;
}

}  // namespace arbor
