// The run options' descriptors: every option reaches result.json's config under its own name, and only there.
#include "core/io/input_error.h"
#include "experiments/options/run_options.h"
#include "experiments/sweep/sweep_spec.h"
#include "variants/filter_list.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

namespace arbor::cli {
namespace {

std::string json_key(std::string name) {
  std::replace(name.begin(), name.end(), '-', '_');
  return name;
}

TEST(RunOptions, ResultConfigHoldsEveryOptionButOutUnderItsOwnName) {
  const nlohmann::json config = run_config_json(run_config_from_arguments({}));
  std::vector<std::string> expected;
  for (const std::string& name : run_option_names())
    if (name != "out") expected.push_back(json_key(name));
  std::vector<std::string> keys;
  for (const auto& [key, value] : config.items()) keys.push_back(key);
  std::sort(expected.begin(), expected.end());
  EXPECT_EQ(keys, expected);
  EXPECT_GE(keys.size(), 30u);  // the list is read, not empty
}

// For every option, some value `arbor run` accepts changes exactly that option's key in the config: a
// descriptor that records another field, or none, fails here. Options that one strategy refuses are tried
// beside the other: the default (jcbb) and --assoc=known.
TEST(RunOptions, EachOptionsValueReachesItsOwnKeyAndNoOther) {
  const std::vector<std::string> candidates{"0.25", "0.5", "3", "7", "-3", "true",     "x.scn",     "fastslam1",
                                            "tree", "known", "per-control", "student-t", "set"};
  for (const std::string& name : run_option_names()) {
    if (name == "out" || name == "prior-map") continue;  // --out is not recorded; --prior-map needs a file
    bool changed_alone = false;
    for (const std::vector<std::string>& base : {std::vector<std::string>{}, std::vector<std::string>{"--assoc=known"}}) {
      if (changed_alone || (name == "assoc" && !base.empty())) break;
      const nlohmann::json defaults = run_config_json(run_config_from_arguments(base));
      for (const std::string& value : candidates) {
        if (!run_option_error(name, value).empty()) continue;
        std::vector<std::string> arguments = base;
        arguments.push_back("--" + name + "=" + value);
        nlohmann::json config;
        try {
          config = run_config_json(run_config_from_arguments(arguments));
        } catch (const InputError&) {  // a combination refused (check_run_option_combinations)
          continue;
        }
        std::vector<std::string> differing;
        for (const auto& [key, v] : config.items())
          if (defaults[key] != v) differing.push_back(key);
        if (differing.empty()) continue;  // the candidate was the default
        EXPECT_EQ(differing, std::vector<std::string>{json_key(name)}) << "--" << name << "=" << value;
        changed_alone = true;
        break;
      }
    }
    EXPECT_TRUE(changed_alone) << "no candidate value of --" << name << " changed result.json's config";
  }
}

TEST(RunOptions, ThePrecisionGatesKeepTheirCommandLineNames) {
  const nlohmann::json config = run_config_json(run_config_from_arguments(
      {"--assoc=known", "--chi2=0.9", "--known-gate=0.5", "--new-landmark-gate=0.95", "--prune=-4", "--confirm=2.5"}));
  EXPECT_EQ(config["chi2"], 0.9);
  EXPECT_EQ(config["known_gate"], 0.5);
  EXPECT_EQ(config["new_landmark_gate"], 0.95);
  EXPECT_EQ(config["prune"], -4.0);
  EXPECT_EQ(config["confirm"], 2.5);
}

TEST(RunOptions, TheSweepVariesEveryOptionItDoesNotSetItself) {
  const std::vector<std::string>& sweepable = sweepable_run_options();
  for (const char* own : {"scenario", "out", "filter", "map", "assoc", "particles", "seed", "threads"})
    EXPECT_EQ(std::count(sweepable.begin(), sweepable.end(), own), 0) << own;
  EXPECT_EQ(sweepable.size() + 8, run_option_names().size());
}

// The filter list is read, not copied: every filter is a sweep's grid.filter value, and every online one is
// an `arbor run --filter` (and arbor.run filter=) value, while a batch one is refused there.
TEST(FilterList, EveryListedFilterReachesTheSweepAndTheRunCommand) {
  for (const FilterEntry& f : kFilters) {
    const std::string name(f.name);
    EXPECT_EQ(std::count(known_filters().begin(), known_filters().end(), name), 1) << name;
    EXPECT_EQ(run_option_error("filter", name).empty(), !f.traits.is_batch) << name;
    EXPECT_EQ(find_filter(name), &f);
  }
  EXPECT_EQ(known_filters().size(), kFilters.size());
  EXPECT_EQ(find_filter("ekf-before-issue-43"), nullptr);
}

}  // namespace
}  // namespace arbor::cli
