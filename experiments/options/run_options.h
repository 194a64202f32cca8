// The options of `arbor run` that shape a run, one descriptor each (run_options.cc). `arbor run` puts them on
// its command line; a sweep spec may name any of them as a [grid] dimension, which the sweep checks against
// these same definitions and hands to each child run as --name=value; arbor.run takes them as keywords; and
// result.json's config records each under the same name. A new run option is one descriptor in
// run_options.cc: --help, the sweep spec, the child's argv, the Python keyword and result.json follow from it.
#ifndef ARBOR_EXPERIMENTS_OPTIONS_RUN_OPTIONS_H_
#define ARBOR_EXPERIMENTS_OPTIONS_RUN_OPTIONS_H_

#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "experiments/options/run_config.h"
#include "variants/filter_list.h"

// Declared, not included: CLI11 is a large header, and the sweep spec reader (and its fuzz target) needs only
// the two functions at the end, not the command line.
namespace CLI {
class App;
}  // namespace CLI

namespace arbor::cli {

// The named values (--filter, --likelihood, ...) as read, by option name, before apply_run_choices turns
// them into the engine's enums.
struct RunChoices {
  std::map<std::string, std::string> chosen;
};

// Adds every run option to cmd, bound to config and choices (--scenario and --out included, required).
void add_run_options(CLI::App& cmd, RunConfig& config, RunChoices& choices);

// Turns the named choices into config's enums; throws InputError naming the option.
void apply_run_choices(const RunChoices& choices, RunConfig& config);

// Refuses, naming both, options given together that do not combine (an option known association ignores,
// --known-gate without it, resample-move with relocalisation, loop closing or per-control sampling); app is
// the command line the config was parsed from, to tell a given option from a default. Throws InputError.
void check_run_option_combinations(const CLI::App& app, const RunConfig& config);

// result.json's "config": every run option but --out under its own name ('_' for '-'), as the run used it.
nlohmann::json run_config_json(const RunConfig& config);

// The traits of the filter config.options.version names (variants/filter_list.h).
const FilterTraits& filter_traits(const RunConfig& config);

// Every run option's name (without "--"), in --help's order.
std::vector<std::string> run_option_names();

// One run option as a user of the Python API sees it: arbor.run's and arbor.Filter's keyword signature, their
// per-option docs and the typed stub (scripts/generate_python_stub.py) are made from these, so they cannot
// drift from the command line.
struct RunOptionInfo {
  std::string name;                  // as on the command line, without "--"
  std::string help;                  // --help's text
  std::string type;                  // the value's type: "bool" (a switch), "int", "float" or "str"
  std::string default_text;          // --help's default; empty where there is none
  std::vector<std::string> choices;  // the names a named value accepts (--filter, --map, ...); empty: any
  bool required = false;             // on the command line (--scenario, --out)
};
std::vector<RunOptionInfo> run_option_info();

// Parses `--name=value` arguments as `arbor run` parses its command line (the same names, defaults and
// checks; --scenario and --out may be left out) and applies the choices. The Python API's arbor.run and
// arbor.Filter take their keyword arguments this way. Throws InputError with CLI11's message.
RunConfig run_config_from_arguments(const std::vector<std::string>& arguments);

// The run options a sweep grid may vary: all but those the sweep sets itself, from its scenario and its own
// grid dimensions (scenario, out, filter, map, assoc, particles, seed, threads). Names without "--".
const std::vector<std::string>& sweepable_run_options();

// Checks one run option value as `arbor run` would parse `--name=value`; returns CLI11's message, or an
// empty string when the value is accepted.
std::string run_option_error(const std::string& name, const std::string& value);

}  // namespace arbor::cli

#endif  // ARBOR_EXPERIMENTS_OPTIONS_RUN_OPTIONS_H_
