// The run options, one descriptor each; see run_options.h.
#include "experiments/options/run_options.h"

#include <algorithm>
#include <functional>
#include <map>
#include <utility>

#include <CLI/CLI.hpp>
#include <fmt/core.h>
#include <fmt/ranges.h>
#include <tbb/info.h>

#include "core/io/input_error.h"
#include "experiments/options/option_checks.h"
#include "variants/filter_list.h"
#include "variants/registry.h"

namespace arbor::cli {

namespace {

using Json = nlohmann::json;

// One run option. Its name is --name on the command line, the key of a sweep's [grid], the keyword of
// arbor.run and, with '_' for '-', its key in result.json's config; `add` binds and checks it, `record` is
// what result.json's config holds for it (none for --out), `apply` turns a named value into the config's enum.
struct RunOptionDescriptor {
  std::string name;
  std::function<CLI::Option*(CLI::App&, RunConfig&, RunChoices&)> add;
  std::function<Json(const RunConfig&)> record;
  std::function<void(const RunChoices&, RunConfig&)> apply;
  bool is_flag = false;  // a switch: --name alone, or --name=true|false
  std::vector<std::string> choices = {};  // the names a named value accepts; empty: any value of its type
  // The filter trait the option needs (variants/filter_list.h), or none: with a filter that lacks it the
  // option is an error when given and null in result.json (EKF-SLAM has no --particles, no --map).
  bool FilterTraits::*needs = nullptr;
};

// The config field an option binds: FIELD(options.seed) reads and writes config.options.seed.
#define FIELD(path) \
  [](auto& c) -> auto& { return c.path; }

// A value read as the field's type, its default shown in --help, recorded as it is.
template <class Field, class... Check>
RunOptionDescriptor value_option(std::string name, Field field, std::string help, Check... checks) {
  return {name,
          [=](CLI::App& cmd, RunConfig& c, RunChoices&) {
            CLI::Option* o = cmd.add_option("--" + name, field(c), help);
            (o->check(checks), ...);
            return o->capture_default_str();
          },
          [=](const RunConfig& c) { return Json(field(c)); },
          {}};
}

// A switch, off unless given.
template <class Field>
RunOptionDescriptor flag_option(std::string name, Field field, std::string help) {
  return {name,
          [=](CLI::App& cmd, RunConfig& c, RunChoices&) { return cmd.add_flag("--" + name, field(c), help); },
          [=](const RunConfig& c) { return Json(field(c)); },
          {},
          /*is_flag=*/true};
}

// One of an enum's names (core/enum_names.h), all of them unless `allowed` narrows them.
template <class Field>
RunOptionDescriptor choice_option(std::string name, Field field, std::string help,
                                  std::vector<std::string> allowed = {}) {
  using Enum = std::remove_reference_t<decltype(field(std::declval<RunConfig&>()))>;
  std::vector<std::string> names = allowed;
  if (names.empty())
    for (const auto& [value, n] : kNamesOf<Enum>) names.emplace_back(n);
  return {name,
          [=](CLI::App& cmd, RunConfig& c, RunChoices& choices) {
            std::string& chosen = choices.chosen[name] = std::string(to_string(field(c)));
            return cmd.add_option("--" + name, chosen, help)->check(CLI::IsMember(names))->capture_default_str();
          },
          [=](const RunConfig& c) { return Json(std::string(to_string(field(c)))); },
          [=](const RunChoices& choices, RunConfig& c) {
            const auto it = choices.chosen.find(name);
            if (it != choices.chosen.end() && !from_string(it->second, &field(c)))
              throw InputError("", 0, name, fmt::format("unknown {} '{}'", name, it->second));
          },
          /*is_flag=*/false,
          names};
}

// A value option whose value is one of `names`, checked where the run looks it up (the registry's lists).
RunOptionDescriptor one_of(RunOptionDescriptor option, std::vector<std::string> names) {
  option.choices = std::move(names);
  return option;
}

// The option, for the filters whose traits have `needs` only.
RunOptionDescriptor needs(bool FilterTraits::*trait, RunOptionDescriptor option) {
  option.needs = trait;
  return option;
}
RunOptionDescriptor for_particles(RunOptionDescriptor option) { return needs(&FilterTraits::has_particles, std::move(option)); }

// The option, recorded in result.json by `record` instead.
RunOptionDescriptor recorded_as(RunOptionDescriptor option, std::function<Json(const RunConfig&)> record) {
  option.record = std::move(record);
  return option;
}

std::string filters_help() {
  std::string help = "The filter:";
  for (const FilterEntry& f : kFilters)
    if (!f.traits.is_batch) help += fmt::format(" {} ({});", f.name, f.summary);
  help.back() = '.';
  return help + " A batch filter (the smoother) runs with `arbor smooth`";
}

// Every option of `arbor run`, in --help's order.
const std::vector<RunOptionDescriptor>& run_option_list() {
  static const std::vector<RunOptionDescriptor> list{
      {"scenario",
       [](CLI::App& cmd, RunConfig& c, RunChoices&) {
         return cmd
             .add_option("--scenario", c.scenario_path, "Scenario file (from `arbor simulate` or `arbor convert`)")
             ->required();
       },
       [](const RunConfig& c) { return Json(c.scenario_path); },
       {}},
      choice_option("filter", FIELD(options.version), filters_help(), online_filter_names()),
      needs(&FilterTraits::has_map_backends,
            one_of(value_option("map", FIELD(map),
                                fmt::format("Map back end: {} (naive copies a particle's whole map at each resampling; "
                                            "tree and trie share it); results do not depend on it",
                                            fmt::join(map_backend_names(), ", "))),
                   map_backend_names())),
      one_of(value_option("assoc", FIELD(assoc),
                          fmt::format("Data association: {} (known: the oracle, pairing by the scenario's true ids)",
                                      fmt::join(association_names(), ", "))),
             association_names()),
      for_particles(value_option("particles", FIELD(options.particles), "Number of particles M")),
      value_option("seed", FIELD(options.seed), "Seed of every random draw of the filter", unsigned_number()),
      recorded_as(value_option("threads", FIELD(options.threads),
                               "Worker threads (0 = all cores); results do not depend on it",
                               within(0, kMaxThreads)),
                  [](const RunConfig& c) {  // what ran, not what was asked: 0 asks for every core
                    return Json(c.options.threads > 0 ? c.options.threads : tbb::info::default_concurrency());
                  }),
      for_particles(value_option("resample-threshold", FIELD(options.resample_threshold),
                   "Resample when N_eff < threshold * particles")),
      value_option("chi2", FIELD(options.association.gate_probability),
                   "Chi-square gate probability of the association tests", open_probability()),
      value_option("new-landmark-gate", FIELD(options.association.new_landmark_probability),
                   "A measurement outside this chi-square gate of every landmark starts a new one", open_probability()),
      for_particles(choice_option("motion-sampling", FIELD(options.motion_sampling),
                    "per-scan: carry each particle's predicted mean and covariance through every control and draw once "
                    "per scan (the FastSLAM 2.0 proposal and the association see the whole prediction); per-control: "
                    "draw at every control (the proposal sees only the last control's covariance; an ablation)")),
      for_particles(choice_option(
          "likelihood", FIELD(options.likelihood),
          "Measurement likelihood in the weights, the proposal and the landmark updates: gaussian or student-t "
          "(heavy tails: an outlier pulls and weighs less)")),
      for_particles(value_option("student-dof", FIELD(options.student_dof), "Degrees of freedom of the Student-t likelihood",
                   within(0.1, 1e6))),
      value_option("known-gate", FIELD(options.association.known_gate_probability),
                   "With --assoc known, reject (and count) a measurement outside this chi-square gate of the landmark "
                   "its id names; 1 (the default) disables the gate: known association is the oracle",
                   within(1e-6, 1.0)),
      for_particles(choice_option("gate-covariance", FIELD(options.gate_covariance),
                    "Innovation covariance of every gate: particle (each particle's own) or set (plus the weighted "
                    "spread of the landmark's predicted measurement over the particle set: the drift of a gap)")),
      for_particles(value_option("roughen", FIELD(options.roughen),
                   "Regularised resampling: after a resampling each particle's prediction gains the kernel "
                   "(roughen * h_opt)^2 times the set's pose covariance (Musso et al. 2001); 0 = off, 1 = h_opt",
                   within(0.0, 10.0))),
      for_particles(recorded_as(
          value_option("weight-exponent", FIELD(options.weight_exponent),
                       "Tempered weights: raise each scan's importance weight to this power (1 = the paper's weights); "
                       "below 1 the set selects as if the measurements were noisier, resamples less and stays "
                       "consistent (the proposal and the landmark updates keep the real noise). 0 = the default: "
                       "0.1 for fastslam2 with --assoc known (chosen on held-out calibration data), else 1 (a real "
                       "strategy's wrong pairings are weeded out by the weights; fastslam1's weights are all that "
                       "corrects its poses)",
                       within(0.0, 1.0)),
          [](const RunConfig& c) {  // what ran
            return Json(c.options.effective_weight_exponent(strategy_uses_ground_truth(c.assoc)));
          })),
      for_particles(value_option("move-window", FIELD(options.move_window),
                   "Resample-move: after each resampling every particle revises the poses of its last N scans by "
                   "Metropolis-Hastings, pairings fixed and landmarks recomputed (Gilks & Berzuini 2001); 0 = off",
                   within(0, 10000))),
      for_particles(value_option("move-steps", FIELD(options.move_steps), "Resample-move: proposals per particle and resampling",
                   within(1, 1000))),
      for_particles(value_option("move-scale", FIELD(options.move_scale),
                   "Resample-move: the first proposal's step in prediction standard deviations (halved at each next)",
                   within(1e-6, 100.0))),
      value_option("max-hypotheses", FIELD(options.association.max_hypotheses),
                   "Search budget of JCBB and the interpretation trees per particle and scan; a search that reaches it "
                   "answers with its best hypothesis so far and is counted in result.json budget_exhausted",
                   at_least(1)),
      value_option("max-work", FIELD(options.association.max_work),
                   "Their work budget per particle and scan, in multiply-adds and candidate scans (a tree's "
                   "compatibility test counts 16); reaching it is counted as above",
                   at_least(1)),
      value_option("prune", FIELD(options.log_odds_prune), "Drop landmarks whose existence log-odds fall below this"),
      value_option("confirm", FIELD(options.log_odds_confirm),
                   "A new landmark is provisional until its existence log-odds reach this (start 1, +1 per sighting, "
                   "-0.5 per miss); only confirmed landmarks make the reported map (1: every landmark at once)"),
      value_option("provisional-scans", FIELD(options.provisional_scans),
                   "Drop a landmark still provisional this many scans after the one that started it (0: never); not "
                   "with --assoc known",
                   at_least(0)),
      for_particles(flag_option("pose-from-confirmed", FIELD(options.pose_from_confirmed),
                  "Only confirmed landmarks steer the pose: a measurement paired with a provisional landmark updates "
                  "it, but moves the pose and weighs the particle as an unpaired measurement would (for cluttered "
                  "sensors); not with --assoc known")),
      for_particles(value_option("provisional-steer-min", FIELD(options.provisional_steer_min),
                   "With --pose-from-confirmed, a scan that pairs no confirmed landmark but at least this many "
                   "provisional ones lets them steer the pose (the second sighting of an unmapped area, above all the "
                   "start; 0: never)",
                   at_least(0))),
      for_particles(flag_option("relocalize", FIELD(options.relocalize),
                  "Relocalise a lost robot: when the best particle pairs under half a scan, search its settled map "
                  "with the pose-free locality tree; a pose that pairs more, found again at the next scan, re-seeds "
                  "every particle (a kidnapped robot, or a loop closure the gates miss)")),
      for_particles(value_option("relocalize-min-pairings", FIELD(options.relocalize_min_pairings),
                   "Pairings a relocalised pose must explain", at_least(3))),
      for_particles(value_option("relocalize-accept", FIELD(options.association.accept_explained),
                   "The relocalising search stops at the first pose that explains this fraction of the scan (0: it "
                   "searches to its bound and keeps the best)",
                   within(0.0, 1.0))),
      for_particles(flag_option("close-loops", FIELD(options.close_loops),
                  "Close loops by re-sighting: a landmark confirmed inside the gate of exactly one dormant landmark "
                  "(unpaired for --dormant-scans scans), widened by --loop-drift-m, is that landmark's drifted copy, "
                  "and later measurements of the copy update the original; not with --assoc known")),
      for_particles(value_option("dormant-scans", FIELD(options.dormant_scans), "Scans unpaired after which a landmark is dormant",
                   at_least(1))),
      for_particles(value_option("loop-drift-m", FIELD(options.loop_drift_m),
                   "Position drift (standard deviation per axis) a loop may have built up, for --close-loops",
                   at_least(1e-6))),
      for_particles(flag_option("record-lineage", FIELD(record_lineage),
                  "Record at each scan how far back the particles' paths share one pose (steps.csv's ancestor_age_s; "
                  "empty while they share none): the set can revise nothing older. Costs M times that depth a scan, "
                  "outside the step's time")),
      {"prior-map",
       [](CLI::App& cmd, RunConfig& c, RunChoices&) {
         return cmd
             .add_option("--prior-map", c.prior_map_path,
                         "Start every particle from this map (map.csv: a run's map, or `arbor simulate "
                         "--survey-out`): localisation in a known map; its landmarks count as confirmed, new "
                         "ones get ids above its largest")
             ->check(CLI::ExistingFile);
       },
       [](const RunConfig& c) { return c.prior_map_path.empty() ? Json(nullptr) : Json(c.prior_map_path); },
       {}},
      {"out",
       [](CLI::App& cmd, RunConfig& c, RunChoices&) {
         return cmd
             .add_option("--out", c.out_dir,
                         "Output directory (result.json, trajectory.tum, map.csv, associations.csv, steps.csv; "
                         "reference.tum where the scenario has a ground truth or GPS track)")
             ->required();
       },
       {},
       {}},
  };
  return list;
}

#undef FIELD

}  // namespace

const FilterTraits& filter_traits(const RunConfig& config) { return listed_filter(to_string(config.options.version)).traits; }

namespace {

// Whether the option means something to the configured filter.
bool applies(const RunOptionDescriptor& option, const RunConfig& config) {
  return !option.needs || filter_traits(config).*option.needs;
}

}  // namespace

void add_run_options(CLI::App& cmd, RunConfig& config, RunChoices& choices) {
  for (const RunOptionDescriptor& o : run_option_list()) o.add(cmd, config, choices);
}

void apply_run_choices(const RunChoices& choices, RunConfig& config) {
  for (const RunOptionDescriptor& o : run_option_list())
    if (o.apply) o.apply(choices, config);
}

nlohmann::json run_config_json(const RunConfig& config) {
  Json out = Json::object();
  for (const RunOptionDescriptor& o : run_option_list()) {
    if (!o.record) continue;
    std::string key = o.name;
    std::replace(key.begin(), key.end(), '-', '_');
    out[key] = applies(o, config) ? o.record(config) : Json(nullptr);
  }
  return out;
}

std::vector<std::string> run_option_names() {
  std::vector<std::string> names;
  for (const RunOptionDescriptor& o : run_option_list()) names.push_back(o.name);
  return names;
}

// The type a Python caller passes: the JSON type result.json records the default config's value as (a
// path that is not set records null; --out is not recorded at all).
std::vector<RunOptionInfo> run_option_info() {
  CLI::App app;
  RunConfig config;
  RunChoices choices;
  std::vector<RunOptionInfo> out;
  for (const RunOptionDescriptor& d : run_option_list()) {
    const CLI::Option* o = d.add(app, config, choices);
    RunOptionInfo info{d.name, o->get_description(), "str", o->get_default_str(), d.choices, o->get_required()};
    const Json recorded = d.record ? d.record(config) : Json(nullptr);
    if (d.is_flag || recorded.is_boolean()) info.type = "bool";
    else if (recorded.is_number_integer()) info.type = "int";
    else if (recorded.is_number_float()) info.type = "float";
    out.push_back(std::move(info));
  }
  return out;
}

namespace {

// Every run option bound to its own config, checked as the command line checks it.
struct RunOptionParser {
  CLI::App app;
  RunConfig config;
  RunChoices choices;
  RunOptionParser() {
    add_run_options(app, config, choices);
    apply_common_option_checks(app);
  }
  // CLI11's message, or empty when every argument was accepted.
  std::string parse(std::vector<std::string> arguments) {
    // The two required options get placeholders where the caller leaves them out.
    for (const char* name : {"--scenario", "--out"}) {
      const std::string prefix = std::string(name) + "=";
      if (std::none_of(arguments.begin(), arguments.end(), [&](const std::string& a) { return a.starts_with(prefix); }))
        arguments.push_back(prefix + "-");
    }
    std::reverse(arguments.begin(), arguments.end());  // CLI11 takes a vector of arguments last first
    try {
      app.parse(arguments);
    } catch (const CLI::ParseError& e) {
      return e.what();
    }
    return {};
  }
};

}  // namespace

namespace {

// The number of single-character edits between a and b (Levenshtein), for "did you mean".
std::size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t above = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = above;
    }
  }
  return row[b.size()];
}

// Checks one --name[=value] argument on its own, so that a bad one is reported with its option as the field
// (arbor.run's keyword, a sweep grid's key) rather than as CLI11's message about the whole command line.
void check_run_argument(const std::string& argument) {
  const std::size_t equals = argument.find('=');
  const std::string name = argument.substr(2, equals == std::string::npos ? std::string::npos : equals - 2);
  const auto& list = run_option_list();
  const auto it = std::find_if(list.begin(), list.end(), [&](const RunOptionDescriptor& o) { return o.name == name; });
  if (it == list.end()) {
    std::string message = fmt::format("'{}' is not an option of `arbor run`", name);
    const auto closest = std::min_element(list.begin(), list.end(), [&](const auto& a, const auto& b) {
      return edit_distance(name, a.name) < edit_distance(name, b.name);
    });
    if (edit_distance(name, closest->name) <= 2) message += fmt::format(" (did you mean '{}'?)", closest->name);
    throw InputError("", 0, name, message + "; `arbor run --help` lists them");
  }
  if (equals == std::string::npos && !it->is_flag)
    throw InputError("", 0, name, fmt::format("needs a value (--{0}=VALUE, or {0}=VALUE in Python); only switches "
                                              "such as --relocalize stand alone",
                                              name));
  if (std::string error = RunOptionParser().parse({argument}); !error.empty()) throw InputError("", 0, name, error);
}

}  // namespace

void check_run_option_combinations(const CLI::App& app, const RunConfig& config) {
  const auto given = [&](const char* name) { return app.get_option(fmt::format("--{}", name))->count() > 0; };
  // With known association the ids decide what is paired and what exists; these options, which the engine
  // then ignores, ran silently (issue 44).
  if (config.assoc == "known")
    for (const char* name : {"pose-from-confirmed", "close-loops", "provisional-scans"})
      if (given(name))
        throw InputError("", 0, name,
                         fmt::format("--{} does not apply with --assoc known (the ids decide what is paired and what "
                                     "exists); leave out one of the two",
                                     name));
  // A filter without particles (or map back ends) has nothing these options could set.
  for (const RunOptionDescriptor& o : run_option_list())
    if (!applies(o, config) && given(o.name.c_str()))
      throw InputError("", 0, o.name,
                       fmt::format("--{} does not apply to --filter {} ({})", o.name, to_string(config.options.version),
                                   o.needs == &FilterTraits::has_map_backends ? "it has no map back end" : "it has no particles"));
  if (config.assoc != "known" && given("known-gate"))
    throw InputError("", 0, "known-gate",
                     fmt::format("--known-gate applies only to --assoc known (--assoc {} gates with --chi2)", config.assoc));
  if (config.options.move_window > 0) {
    for (const char* name : {"relocalize", "close-loops"})
      if (given(name))
        throw InputError("", 0, "move-window",
                         fmt::format("--move-window and --{} do not combine: both rewrite the particles' paths", name));
    if (config.options.motion_sampling != MotionSampling::kPerScan)
      throw InputError("", 0, "move-window", "--move-window needs --motion-sampling per-scan");
  }
}

RunConfig run_config_from_arguments(const std::vector<std::string>& arguments) {
  for (const std::string& a : arguments)
    if (a.starts_with("--")) check_run_argument(a);
  RunOptionParser parser;
  if (std::string error = parser.parse(arguments); !error.empty()) throw InputError("", 0, "", error);
  apply_run_choices(parser.choices, parser.config);
  check_run_option_combinations(parser.app, parser.config);
  if (parser.config.out_dir == "-") parser.config.out_dir.clear();
  if (parser.config.scenario_path == "-") parser.config.scenario_path.clear();
  return parser.config;
}

const std::vector<std::string>& sweepable_run_options() {
  static const std::vector<std::string> names = [] {
    const std::vector<std::string> set_by_the_sweep{"scenario", "out",       "filter", "map",
                                                    "assoc",    "particles", "seed",   "threads"};
    std::vector<std::string> out;
    for (const std::string& name : run_option_names())
      if (std::find(set_by_the_sweep.begin(), set_by_the_sweep.end(), name) == set_by_the_sweep.end())
        out.push_back(name);
    std::sort(out.begin(), out.end());
    return out;
  }();
  return names;
}

std::string run_option_error(const std::string& name, const std::string& value) {
  return RunOptionParser().parse({"--" + name + "=" + value});
}

}  // namespace arbor::cli
