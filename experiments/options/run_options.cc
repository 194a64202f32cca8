// The run options, defined once; see run_options.h.
#include "experiments/options/run_options.h"

#include <algorithm>

#include <CLI/CLI.hpp>
#include <fmt/core.h>
#include <fmt/ranges.h>

#include "core/io/input_error.h"
#include "experiments/options/option_checks.h"
#include "variants/registry.h"

namespace arbor::cli {

void add_run_options(CLI::App& cmd, RunConfig& config, RunChoices& choices) {
  cmd.add_option("--scenario", config.scenario_path, "Scenario file (from `arbor simulate` or `arbor convert`)")
      ->required();
  cmd.add_option("--filter", choices.filter, "fastslam1 (sample the motion model) or fastslam2 (measurement-informed proposal)")
      ->check(CLI::IsMember({"fastslam1", "fastslam2"}))
      ->capture_default_str();
  cmd.add_option("--map", config.map, fmt::format("Map back end: {}", fmt::join(map_backend_names(), ", ")))
      ->capture_default_str();
  cmd.add_option("--assoc", config.assoc,
                  fmt::format("Data association: {} (known = the scenario's ground-truth ids)",
                              fmt::join(association_names(), ", ")))
      ->capture_default_str();
  cmd.add_option("--particles", config.options.particles, "Number of particles M")->capture_default_str();
  cmd.add_option("--seed", config.options.seed, "Seed of every random draw of the filter")
      ->check(unsigned_number())
      ->capture_default_str();
  cmd.add_option("--threads", config.options.threads, "Worker threads (0 = all cores); results do not depend on it")
      ->capture_default_str();
  cmd.add_option("--resample-threshold", config.options.resample_threshold,
                  "Resample when N_eff < threshold * particles")
      ->capture_default_str();
  cmd.add_option("--chi2", config.options.association.gate_probability,
                  "Chi-square gate probability of the association tests")
      ->check(open_probability())
      ->capture_default_str();
  cmd.add_option("--new-landmark-gate", config.options.association.new_landmark_probability,
                  "A measurement outside this chi-square gate of every landmark starts a new one")
      ->check(open_probability())
      ->capture_default_str();
  cmd.add_option("--motion-sampling", choices.motion_sampling,
                  "per-scan: carry each particle's predicted mean and covariance through every control and draw once "
                  "per scan (the FastSLAM 2.0 proposal and the association see the whole prediction); per-control: "
                  "draw at every control (the proposal sees only the last control's covariance; an ablation)")
      ->check(CLI::IsMember({"per-scan", "per-control"}))
      ->capture_default_str();
  cmd.add_option("--likelihood", choices.likelihood,
                  "Measurement likelihood in the weights, the proposal and the landmark updates: gaussian or student-t "
                  "(heavy tails: an outlier pulls and weighs less)")
      ->check(CLI::IsMember({"gaussian", "student-t"}))
      ->capture_default_str();
  cmd.add_option("--student-dof", config.options.student_dof, "Degrees of freedom of the Student-t likelihood")
      ->check(within(0.1, 1e6))
      ->capture_default_str();
  cmd.add_option("--known-gate", config.options.association.known_gate_probability,
                  "With --assoc known, reject (and count) a measurement outside this chi-square gate of the landmark "
                  "its id names; 1 (the default) disables the gate: known association is the oracle")
      ->check(within(1e-6, 1.0))
      ->capture_default_str();
  cmd.add_option("--gate-covariance", choices.gate_covariance,
                  "Innovation covariance of every gate: particle (each particle's own) or set (plus the weighted "
                  "spread of the landmark's predicted measurement over the particle set: the drift of a gap)")
      ->check(CLI::IsMember({"particle", "set"}))
      ->capture_default_str();
  cmd.add_option("--roughen", config.options.roughen,
                  "Regularised resampling: after a resampling each particle's prediction gains the kernel "
                  "(roughen * h_opt)^2 times the set's pose covariance (Musso et al. 2001); 0 = off, 1 = h_opt")
      ->check(within(0.0, 10.0))
      ->capture_default_str();
  cmd.add_option("--move-window", config.options.move_window,
                  "Resample-move: after each resampling every particle revises the poses of its last N scans by "
                  "Metropolis-Hastings, pairings fixed and landmarks recomputed (Gilks & Berzuini 2001); 0 = off")
      ->check(within(0, 10000))
      ->capture_default_str();
  cmd.add_option("--move-steps", config.options.move_steps, "Resample-move: proposals per particle and resampling")
      ->check(within(1, 1000))
      ->capture_default_str();
  cmd.add_option("--move-scale", config.options.move_scale,
                  "Resample-move: the first proposal's step in prediction standard deviations (halved at each next)")
      ->check(within(1e-6, 100.0))
      ->capture_default_str();
  cmd.add_option("--max-hypotheses", config.options.association.max_hypotheses,
                  "Search budget of JCBB and the interpretation trees per particle and scan; a search that reaches it "
                  "answers with its best hypothesis so far and is counted in result.json budget_exhausted")
      ->check(at_least(1))
      ->capture_default_str();
  cmd.add_option("--max-work", config.options.association.max_work,
                  "Their work budget per particle and scan, in multiply-adds and candidate scans (a tree's "
                  "compatibility test counts 16); reaching it is counted as above")
      ->check(at_least(1))
      ->capture_default_str();
  cmd.add_option("--prune", config.options.log_odds_prune, "Drop landmarks whose existence log-odds fall below this")
      ->capture_default_str();
  cmd.add_option("--confirm", config.options.log_odds_confirm,
                  "A new landmark is provisional until its existence log-odds reach this (start 1, +1 per sighting, "
                  "-0.5 per miss); only confirmed landmarks make the reported map (1: every landmark at once)")
      ->capture_default_str();
  cmd.add_option("--provisional-scans", config.options.provisional_scans,
                  "Drop a landmark still provisional this many scans after the one that started it (0: never); not "
                  "with --assoc known")
      ->check(at_least(0))
      ->capture_default_str();
  cmd.add_flag("--pose-from-confirmed", config.options.pose_from_confirmed,
                "Only confirmed landmarks steer the pose: a measurement paired with a provisional landmark updates "
                "it, but moves the pose and weighs the particle as an unpaired measurement would (for cluttered "
                "sensors); not with --assoc known");
  cmd.add_option("--provisional-steer-min", config.options.provisional_steer_min,
                  "With --pose-from-confirmed, a scan that pairs no confirmed landmark but at least this many "
                  "provisional ones lets them steer the pose (the second sighting of an unmapped area, above all the "
                  "start; 0: never)")
      ->check(at_least(0))
      ->capture_default_str();
  cmd.add_flag("--relocalize", config.options.relocalize,
                "Relocalise a lost robot: when the best particle pairs under half a scan, search its settled map "
                "with the pose-free locality tree; a pose that pairs more, found again at the next scan, re-seeds "
                "every particle (a kidnapped robot, or a loop closure the gates miss)");
  cmd.add_option("--relocalize-min-pairings", config.options.relocalize_min_pairings,
                  "Pairings a relocalised pose must explain")
      ->check(at_least(3))
      ->capture_default_str();
  cmd.add_option("--relocalize-accept", config.options.association.accept_explained,
                  "The relocalising search stops at the first pose that explains this fraction of the scan (0: it "
                  "searches to its bound and keeps the best)")
      ->check(within(0.0, 1.0))
      ->capture_default_str();
  cmd.add_flag("--close-loops", config.options.close_loops,
                "Close loops by re-sighting: a landmark confirmed inside the gate of exactly one dormant landmark "
                "(unpaired for --dormant-scans scans), widened by --loop-drift-m, is that landmark's drifted copy, "
                "and later measurements of the copy update the original; not with --assoc known");
  cmd.add_option("--dormant-scans", config.options.dormant_scans, "Scans unpaired after which a landmark is dormant")
      ->check(at_least(1))
      ->capture_default_str();
  cmd.add_option("--loop-drift-m", config.options.loop_drift_m,
                  "Position drift (standard deviation per axis) a loop may have built up, for --close-loops")
      ->check(at_least(1e-6))
      ->capture_default_str();
  cmd.add_option("--prior-map", config.prior_map_path,
                  "Start every particle from this map (map.csv: a run's map, or `arbor simulate --survey-out`): "
                  "localisation in a known map; its landmarks count as confirmed, new ones get ids above its largest")
      ->check(CLI::ExistingFile);
  cmd.add_option("--out", config.out_dir, "Output directory (result.json, trajectory.tum, map.csv, associations.csv, steps.csv)")
      ->required();
}

void apply_run_choices(const RunChoices& choices, RunConfig& config) {
  if (!from_string(choices.filter, &config.options.version))
    throw InputError("", 0, "filter", "unknown filter " + choices.filter);
  if (!from_string(choices.motion_sampling, &config.options.motion_sampling))
    throw InputError("", 0, "motion-sampling", "unknown motion sampling " + choices.motion_sampling);
  if (!from_string(choices.likelihood, &config.options.likelihood))
    throw InputError("", 0, "likelihood", "unknown likelihood " + choices.likelihood);
  if (!from_string(choices.gate_covariance, &config.options.gate_covariance))
    throw InputError("", 0, "gate-covariance", "unknown gate covariance " + choices.gate_covariance);
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

RunConfig run_config_from_arguments(const std::vector<std::string>& arguments) {
  RunOptionParser parser;
  if (std::string error = parser.parse(arguments); !error.empty()) throw InputError("", 0, "", error);
  apply_run_choices(parser.choices, parser.config);
  if (parser.config.out_dir == "-") parser.config.out_dir.clear();
  if (parser.config.scenario_path == "-") parser.config.scenario_path.clear();
  return parser.config;
}

const std::vector<std::string>& sweepable_run_options() {
  static const std::vector<std::string> names = [] {
    RunOptionParser parser;
    const std::vector<std::string> set_by_the_sweep{"scenario", "out",       "filter", "map",
                                                    "assoc",    "particles", "seed",   "threads"};
    std::vector<std::string> out;
    for (const CLI::Option* o : parser.app.get_options()) {
      const std::string name = o->get_single_name();
      if (o->get_lnames().empty() || name == "help") continue;
      if (std::find(set_by_the_sweep.begin(), set_by_the_sweep.end(), name) == set_by_the_sweep.end())
        out.push_back(name);
    }
    std::sort(out.begin(), out.end());
    return out;
  }();
  return names;
}

std::string run_option_error(const std::string& name, const std::string& value) {
  return RunOptionParser().parse({"--" + name + "=" + value});
}

}  // namespace arbor::cli
