// Sweep specs: grid expansion, shards, the spec hash, result-file reading, and validation errors that name
// the spec's line and field before anything runs.
#include "experiments/sweep/sweep_spec.h"

#include <algorithm>
#include <filesystem>
#include <set>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <toml++/toml.h>

#include "core/io/input_error.h"
#include "experiments/sweep/results_log.h"
#include "experiments/sweep/sweep_runner.h"
#include "tests/experiments/sweep_test_util.h"

namespace arbor {
namespace {

using testing_util::ScratchDir;
using testing_util::read_text;
using testing_util::write_text;

constexpr const char* kGoodSpec = R"(# a small grid
[sweep]
name = "unit"

[scenarios]
world = ["uniform", "rooms"]
landmarks = { from = 100, to = 10000, factor = 10 }
steps = 50
clutter = { from = 0.0, to = 0.3, step = 0.1 }

[grid]
filter = ["fastslam2", "fastslam1"]
map = ["naive"]  # the registry may hold only this one
assoc = "known"
particles = [10, 1]
seed = { from = 1, to = 3 }
threads = [1, 2]
)";

SweepSpec spec_from(const ScratchDir& dir, const std::string& text) {
  write_text(dir / "spec.toml", text);
  return read_sweep_spec(dir / "spec.toml");
}

// Reads a spec that must fail; returns the error.
InputError error_of(const ScratchDir& dir, const std::string& text) {
  write_text(dir / "spec.toml", text);
  try {
    read_sweep_spec(dir / "spec.toml");
  } catch (const InputError& e) {
    return e;
  }
  ADD_FAILURE() << "spec was accepted:\n" << text;
  return InputError("", 0, "", "");
}

// Every spec the project ships reads and validates, so a study the docs name does not stop at its first
// line (a grid crossing EKF-SLAM with a particle option once did). The tests run from the source tree. The
// datasets a spec names are logs that its script converts first (out/scenarios/), so each spec is read as a
// copy in a scratch tree where they exist as empty files: its grid is checked all the same.
TEST(SweepSpec, EveryShippedSpecValidates) {
  const ScratchDir dir("shipped_specs");
  int specs = 0;
  for (const auto& entry : std::filesystem::recursive_directory_iterator("experiments")) {
    if (entry.path().extension() != ".toml") continue;
    ++specs;
    const std::filesystem::path copy = std::filesystem::path(dir.str()) / entry.path();
    std::filesystem::create_directories(copy.parent_path());
    std::filesystem::copy_file(entry.path(), copy);
    try {
      const toml::table table = toml::parse_file(entry.path().string());
      const toml::node_view<const toml::node> datasets = table["scenarios"]["datasets"];
      std::vector<std::string> named;
      if (const toml::array* list = datasets.as_array())
        for (const toml::node& d : *list) named.push_back(d.value_or(std::string{}));
      else if (datasets.is_string())
        named.push_back(datasets.value_or(std::string{}));
      for (const std::string& dataset : named) {
        const std::filesystem::path placeholder = copy.parent_path() / dataset;
        std::filesystem::create_directories(placeholder.parent_path());
        write_text(placeholder.string(), "");
      }
      read_sweep_spec(copy.string());
    } catch (const std::exception& e) {
      ADD_FAILURE() << entry.path() << ": " << e.what();
    }
  }
  EXPECT_GE(specs, 30) << "the shipped specs were not found: is the working directory the source tree?";
}

TEST(SweepSpec, ExpandsTheFullCrossProductSortedAndUnique) {
  ScratchDir dir("spec");
  const SweepSpec spec = spec_from(dir, kGoodSpec);
  // worlds 2 x landmarks {100, 1000, 10000} x clutter {0, .1, .2, .3} x filters 2 x particles 2 x seeds 3 x threads 2
  EXPECT_EQ(spec.runs.size(), 2u * 3 * 4 * 2 * 2 * 3 * 2);
  std::set<std::string> keys;
  std::set<std::int64_t> landmarks;
  std::set<double> clutter;
  for (const auto& r : spec.runs) {
    keys.insert(r.key());
    landmarks.insert(r.world_landmarks);
    clutter.insert(r.clutter);
  }
  EXPECT_EQ(keys.size(), spec.runs.size());
  EXPECT_EQ(landmarks, (std::set<std::int64_t>{100, 1000, 10000}));
  EXPECT_EQ(clutter.size(), 4u);
  EXPECT_DOUBLE_EQ(*clutter.rbegin(), 0.3);  // the range end is hit exactly, not 0.30000000000000004
  EXPECT_TRUE(std::is_sorted(spec.runs.begin(), spec.runs.end()));
  EXPECT_EQ(spec.metrics, default_metrics(false));
}

TEST(SweepSpec, HashIgnoresCommentsAndListOrderButNotTheGrid) {
  ScratchDir dir("spec");
  const std::string base = spec_from(dir, kGoodSpec).hash;
  std::string reordered = kGoodSpec;
  reordered.replace(reordered.find("[\"fastslam2\", \"fastslam1\"]"), 26, "[\"fastslam1\", \"fastslam2\"]");
  EXPECT_EQ(spec_from(dir, "# another comment\n" + reordered).hash, base);
  std::string grown = kGoodSpec;
  grown.replace(grown.find("particles = [10, 1]"), 19, "particles = [10, 2]");
  EXPECT_NE(spec_from(dir, grown).hash, base);
}

TEST(SweepSpec, ShardsPartitionTheGrid) {
  ScratchDir dir("spec");
  const SweepSpec spec = spec_from(dir, kGoodSpec);
  std::multiset<std::string> seen;
  for (int i = 0; i < 3; ++i)
    for (const auto& r : shard_runs(spec.runs, i, 3)) seen.insert(r.key());
  EXPECT_EQ(seen.size(), spec.runs.size());
  EXPECT_EQ(std::set<std::string>(seen.begin(), seen.end()).size(), spec.runs.size());
  int index = -1, count = -1;
  parse_shard("2/5", &index, &count);
  EXPECT_EQ(index, 2);
  EXPECT_EQ(count, 5);
  EXPECT_THROW(parse_shard("5/5", &index, &count), InputError);
  EXPECT_THROW(parse_shard("1/", &index, &count), InputError);
}

TEST(SweepSpec, SmootherRunsOncePerScenarioAndSeed) {
  ScratchDir dir("spec");
  const SweepSpec spec = spec_from(dir, R"(
[scenarios]
world = "uniform"
landmarks = 50
steps = 20
[grid]
filter = ["smoother", "fastslam1"]
map = "naive"
assoc = "known"
particles = [5, 10]
seed = [1, 2]
)");
  int smoother = 0;
  for (const auto& r : spec.runs) smoother += r.filter == "smoother";
  EXPECT_EQ(smoother, 2);
  EXPECT_EQ(spec.runs.size(), 2u + 2 * 2);
  EXPECT_EQ(spec.metrics, default_metrics(true));
}

TEST(SweepSpec, DatasetsResolveAgainstTheSpecFolderAndKeysDoNotDependOnIt) {
  ScratchDir dir("spec");
  std::filesystem::create_directories(dir / "data");
  write_text(dir / "data/park.scn", "arbor-scenario 2\n");
  const std::string text = R"(
[scenarios]
datasets = ["data/park.scn"]
[grid]
filter = "fastslam2"
map = "naive"
assoc = "known"
particles = 10
seed = 1
)";
  const SweepSpec spec = spec_from(dir, text);
  ASSERT_EQ(spec.runs.size(), 1u);
  EXPECT_EQ(spec.runs[0].dataset, "data/park.scn");
  EXPECT_EQ(spec.runs[0].dataset_path, dir / "data/park.scn");
  EXPECT_EQ(spec.runs[0].key().rfind("park-", 0), 0u) << spec.runs[0].key();
  const auto argv = run_command(spec.runs[0], "arbor", "out");
  EXPECT_NE(std::find(argv.begin(), argv.end(), dir / "data/park.scn"), argv.end());
  // The same spec elsewhere (another machine, another checkout) gives the same key and hash.
  ScratchDir other("spec_elsewhere");
  std::filesystem::create_directories(other / "data");
  write_text(other / "data/park.scn", "arbor-scenario 2\n");
  const SweepSpec moved = spec_from(other, text);
  EXPECT_EQ(moved.runs[0].key(), spec.runs[0].key());
  EXPECT_EQ(moved.hash, spec.hash);
}

TEST(SweepSpec, AnyRunOptionIsAGridDimensionCheckedAndPassedToTheChild) {
  ScratchDir dir("spec");
  std::string text = kGoodSpec;
  text += "likelihood = [\"gaussian\", \"student-t\"]\nrelocalize = true\nchi2 = 0.95\n";
  const SweepSpec spec = spec_from(dir, text);
  EXPECT_EQ(spec.runs.size(), 2u * (2u * 3 * 4 * 2 * 2 * 3 * 2));
  EXPECT_EQ(spec.run_option_names, (std::vector<std::string>{"chi2", "likelihood", "relocalize"}));
  const RunParams& run = spec.runs.back();
  const std::vector<std::string> argv = run_command(run, "arbor", "OUT");
  EXPECT_NE(std::find(argv.begin(), argv.end(), "--chi2=0.95"), argv.end());
  EXPECT_NE(std::find(argv.begin(), argv.end(), "--relocalize=true"), argv.end());
  EXPECT_EQ(std::count_if(argv.begin(), argv.end(), [](const std::string& a) { return a.rfind("--likelihood=", 0) == 0; }), 1);
  EXPECT_NE(run.key().find("__chi2-0.95_likelihood-"), std::string::npos) << run.key();
  // The rows get a column per option, between the parameters and the scenario.
  const std::vector<std::string> columns = result_columns(spec.metrics, spec.run_option_names);
  const auto at = std::find(columns.begin(), columns.end(), "likelihood");
  ASSERT_NE(at, columns.end());
  EXPECT_EQ(*(at - 2), "threads");
  // Without run options, keys are what they were (resumed sweeps keep their rows).
  const SweepSpec plain = spec_from(dir, kGoodSpec);
  EXPECT_EQ(plain.runs.front().key().find("__", plain.runs.front().key().find("__") + 2), std::string::npos);
}

// Values that sanitise alike (`m+1.csv` and `m 1.csv` are both m_1.csv in a file name) keep distinct keys: one
// key for two runs made the grid a run short, and the second run's row overwrote the first's.
TEST(SweepSpec, RunOptionValuesThatSanitiseAlikeKeepDistinctKeys) {
  ScratchDir dir("spec");
  write_text(dir / "m+1.csv", "");
  write_text(dir / "m 1.csv", "");
  const std::string text = kGoodSpec + std::string("prior-map = [\"") + (dir / "m+1.csv") + "\", \"" + (dir / "m 1.csv") + "\"]\n";
  const SweepSpec spec = spec_from(dir, text);
  std::set<std::string> keys;
  for (const RunParams& r : spec.runs) keys.insert(r.key());
  EXPECT_EQ(keys.size(), spec.runs.size());
  EXPECT_EQ(spec.runs.size(), 2u * spec_from(dir, kGoodSpec).runs.size());
}

// `relocalize = 1` and `chi2 = [0.9, "0.90"]` ran as `arbor run` reads them, but under keys of their own: the
// same configuration ran twice and split apart in the analysis (hostile B11). Literal repeats stay one run.
TEST(SweepSpec, TwoSpellingsOfOneRunOptionSettingAreRefused) {
  ScratchDir dir("spec");
  InputError e = error_of(dir, std::string(kGoodSpec) + "chi2 = [0.9,\n  \"0.90\"]\n");
  EXPECT_EQ(e.field(), "grid.chi2");
  EXPECT_EQ(e.line(), 19);
  EXPECT_NE(std::string(e.what()).find("'0.90' is the same setting as '0.9' at line 18"), std::string::npos) << e.what();
  e = error_of(dir, std::string(kGoodSpec) + "relocalize = 1\n");
  EXPECT_EQ(e.field(), "grid.relocalize");
  EXPECT_NE(std::string(e.what()).find("a switch takes true or false (got '1')"), std::string::npos) << e.what();
  EXPECT_EQ(spec_from(dir, std::string(kGoodSpec) + "chi2 = [0.9, 0.9, 0.95]\n").runs.size(),
            2 * spec_from(dir, kGoodSpec).runs.size());
}

TEST(SweepSpec, ABadRunOptionValueNamesItsLineAndFieldWithTheRunCommandsMessage) {
  ScratchDir dir("spec");
  std::string text = kGoodSpec;
  text += "student-dof = [4,\n  0.01]\n";  // 0.01 on line 19 (threads = ... is on 17)
  InputError e = error_of(dir, text);
  EXPECT_EQ(e.field(), "grid.student-dof");
  EXPECT_EQ(e.line(), 19);
  EXPECT_NE(std::string(e.what()).find("0.01"), std::string::npos) << e.what();
  // A probability outside (0, 1) is refused by the spec, not by a child run that fails later.
  e = error_of(dir, std::string(kGoodSpec) + "chi2 = 2.0\n");
  EXPECT_EQ(e.field(), "grid.chi2");
  text = std::string(kGoodSpec) + "likelihood = \"cauchy\"\n";
  e = error_of(dir, text);
  EXPECT_EQ(e.field(), "grid.likelihood");
  EXPECT_NE(std::string(e.what()).find("cauchy"), std::string::npos) << e.what();
  // A name `arbor run` does not define, or one the sweep sets itself, is an unknown key.
  e = error_of(dir, std::string(kGoodSpec) + "chi3 = 0.9\n");
  EXPECT_EQ(e.field(), "grid.chi3");
  e = error_of(dir, std::string(kGoodSpec) + "out = \"x\"\n");
  EXPECT_EQ(e.field(), "grid.out");
}

// A grid that crosses known association with an option it ignores would fail those runs one by one after the
// sweep started; the spec is refused, naming a run and both options.
TEST(SweepSpec, OptionsThatDoNotCombineAreRefusedBeforeAnyRun) {
  ScratchDir dir("spec");
  const InputError e = error_of(dir, std::string(kGoodSpec) + "close-loops = [false, true]\n");
  EXPECT_EQ(e.field(), "grid");
  EXPECT_NE(std::string(e.what()).find("--close-loops does not apply with --assoc known"), std::string::npos) << e.what();
  // The same option beside a strategy it serves is a grid like any other.
  std::string text = kGoodSpec;
  text.replace(text.find("assoc = \"known\""), 15, "assoc = \"nn\"");
  EXPECT_EQ(spec_from(dir, text + "close-loops = [false, true]\n").runs.size(), 2 * spec_from(dir, text).runs.size());
}

TEST(SweepSpec, UnknownBackEndNamesItsLineAndField) {
  ScratchDir dir("spec");
  std::string text = kGoodSpec;
  text.replace(text.find("map = [\"naive\"]"), 15, "map = [\"naive\",\n  \"octree\"]");
  const InputError e = error_of(dir, text);
  EXPECT_EQ(e.line(), 14);  // the line of "octree" (map = ... is on 13)
  EXPECT_EQ(e.field(), "grid.map");
  EXPECT_NE(std::string(e.what()).find("octree"), std::string::npos);
  EXPECT_NE(std::string(e.what()).find("spec.toml:14"), std::string::npos) << e.what();
}

TEST(SweepSpec, UnknownStrategyFilterAndWorldAreRejected) {
  ScratchDir dir("spec");
  for (const auto& [from, to, field] : std::vector<std::tuple<std::string, std::string, std::string>>{
           {"assoc = \"known\"", "assoc = \"icp\"", "grid.assoc"},
           {"filter = [\"fastslam2\", \"fastslam1\"]", "filter = [\"fastslam3\"]", "grid.filter"},
           {"world = [\"uniform\", \"rooms\"]", "world = [\"uniform\", \"maze\"]", "scenarios.world"}}) {
    std::string text = kGoodSpec;
    text.replace(text.find(from), from.size(), to);
    const InputError e = error_of(dir, text);
    EXPECT_EQ(e.field(), field);
    EXPECT_GT(e.line(), 0);
  }
}

TEST(SweepSpec, BadRangesNameTheirLine) {
  ScratchDir dir("spec");
  for (const auto& bad : {"particles = { from = 10, to = 1 }", "particles = { from = 1, to = 10, step = 0 }",
                          "particles = { from = 1, to = 10, factor = 1 }", "particles = [0, 5]",
                          "particles = { from = 1 }", "particles = []", "particles = [1.5]",
                          "particles = { from = -9223372036854775807, to = 9223372036854775807 }"}) {
    std::string text = kGoodSpec;
    text.replace(text.find("particles = [10, 1]"), 19, bad);
    const InputError e = error_of(dir, text);
    EXPECT_EQ(e.line(), 15) << bad << ": " << e.what();
    EXPECT_EQ(e.field().rfind("grid.particles", 0), 0u) << bad << ": " << e.what();
  }
  std::string text = kGoodSpec;
  text.replace(text.find("clutter = { from = 0.0, to = 0.3, step = 0.1 }"), 46, "clutter = -1.0");
  EXPECT_EQ(error_of(dir, text).line(), 9);
}

TEST(SweepSpec, MissingFieldsAndTyposAreRejected) {
  ScratchDir dir("spec");
  std::string text = kGoodSpec;
  text.erase(text.find("seed = { from = 1, to = 3 }\n"), 28);
  InputError e = error_of(dir, text);
  EXPECT_EQ(e.field(), "grid.seed");
  EXPECT_EQ(e.line(), 11);  // the [grid] header
  EXPECT_NE(std::string(e.what()).find("missing"), std::string::npos);

  text = kGoodSpec;
  text.erase(text.find("landmarks = "), text.find("steps = ") - text.find("landmarks = "));
  EXPECT_EQ(error_of(dir, text).field(), "scenarios.landmarks");

  text = kGoodSpec;
  text.replace(text.find("particles ="), 11, "partciles =");
  e = error_of(dir, text);
  EXPECT_EQ(e.field(), "grid.partciles");
  EXPECT_EQ(e.line(), 15);

  e = error_of(dir, "[grid\nfilter = 1\n");
  EXPECT_EQ(e.line(), 1);
  EXPECT_NE(std::string(e.what()).find("TOML"), std::string::npos);

  e = error_of(dir, "[scenarios]\ndatasets = [\"no/such/file.scn\"]\n[grid]\nfilter = \"fastslam1\"\n");
  EXPECT_EQ(e.line(), 2);
  EXPECT_EQ(e.field(), "scenarios.datasets");
}

// A metric name outside result.json used to give a column of nulls; the list the spec checks against is
// exactly the scalar fields a run and a solve write, so it cannot drift from them.
TEST(SweepSpec, MetricsAreTheScalarFieldsOfResultJson) {
  ScratchDir dir("metrics");
  std::string typo = kGoodSpec;
  typo.replace(typo.find("name = \"unit\""), 13, "name = \"unit\"\nmetrics = [\"ate_rmse\"]");
  EXPECT_EQ(error_of(dir, typo).field(), "sweep.metrics");

  const std::string exe = testing_util::arbor_binary();
  if (exe.empty()) GTEST_SKIP() << "ARBOR_BINARY_DIR/bin/arbor not found";
  ASSERT_EQ(testing_util::run_to_end({exe, "simulate", "--landmarks", "30", "--steps", "20", "--out", dir / "w.scn"},
                                     dir / "sim.log"), 0);
  std::set<std::string> written;
  const auto scalar_keys = [&](const std::string& result) {
    const nlohmann::json json = nlohmann::json::parse(read_text(result));
    for (const auto& [key, value] : json.items())
      if (!value.is_object() && !value.is_array()) written.insert(key);
  };
  ASSERT_EQ(testing_util::run_to_end({exe, "run", "--scenario", dir / "w.scn", "--particles", "5", "--quiet", "--out",
                                      dir / "run"}, dir / "run.log"), 0);
  scalar_keys(dir / "run/result.json");
  std::set<std::string> known(known_metrics().begin(), known_metrics().end());
#ifdef ARBOR_HAVE_SMOOTHER
  ASSERT_EQ(testing_util::run_to_end({exe, "smooth", "--scenario", dir / "w.scn", "--quiet", "--out", dir / "smooth"},
                                     dir / "smooth.log"), 0);
  scalar_keys(dir / "smooth/result.json");
  EXPECT_EQ(known, written);
#else
  for (const auto& key : written) EXPECT_TRUE(known.count(key)) << key;
#endif
}

TEST(ResultRows, ATrailingPartialLineIsNotARowAndIsCutOnResume) {
  ScratchDir dir("rows");
  const std::string path = dir / "results.jsonl";
  write_text(path, "{\"key\":\"a\",\"status\":\"ok\",\"x\":1.5e-3}\n{\"key\":\"b\",\"status\":\"ok\"}\n{\"key\":\"c\",\"sta");
  auto rows = read_result_rows(path);
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_DOUBLE_EQ(rows[0]["x"].get<double>(), 1.5e-3);
  EXPECT_EQ(rows[1]["key"], "b");
  drop_partial_last_line(path);
  EXPECT_EQ(testing_util::read_text(path), "{\"key\":\"a\",\"status\":\"ok\",\"x\":1.5e-3}\n{\"key\":\"b\",\"status\":\"ok\"}\n");
  write_text(path, "{\"key\":\"a\"}\nnot json\n");
  EXPECT_THROW(read_result_rows(path), InputError);
}

TEST(ResultRows, CsvCellsQuoteSeparatorsAndLeaveNullEmpty) {
  const ResultRow row = ResultRow::parse(R"({"key":"k","error":"bad, \"quoted\"\nline","x":0.25,"n":null})");
  EXPECT_EQ(csv_line(row, {"key", "error", "x", "n", "absent"}), "k,\"bad, \"\"quoted\"\"\nline\",0.25,,\n");
}

}  // namespace
}  // namespace arbor
