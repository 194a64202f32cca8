// The analysis scripts run with the system Python on the committed results fixture and produce their files.
// Skipped (with the reason) where /usr/bin/python3 lacks numpy, pandas or matplotlib.
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "tests/experiments/sweep_test_util.h"

namespace arbor {
namespace {

using testing_util::read_text;
using testing_util::run_to_end;
using testing_util::ScratchDir;

constexpr const char* kPython = "/usr/bin/python3";
const std::string kSource = ARBOR_SOURCE_DIR;
// The package analysis/arbor_analysis importable: a report section runs on its own as a module of it, and the
// snippets below import it.
const std::string kPythonPath = "PYTHONPATH=" + kSource + "/analysis";

class AnalysisScripts : public ::testing::Test {
 protected:
  void SetUp() override {
    ScratchDir probe("python_probe");
    if (!std::filesystem::exists(kPython) ||
        run_to_end({kPython, "-c", "import numpy, pandas, matplotlib"}, probe / "probe.log") != 0)
      GTEST_SKIP() << kPython << " cannot import numpy, pandas and matplotlib (Debian: apt install python3-pandas "
                   << "python3-matplotlib): " << read_text(probe / "probe.log");
  }
  std::string fixture() const { return kSource + "/tests/data/results_fixture"; }
  // Runs a Python snippet with the package analysis/arbor_analysis importable, `ar` its results module and
  // `df` the results under out (ar.load_results); *log is what it printed. A fatal failure if it fails: call
  // it inside ASSERT_NO_FATAL_FAILURE.
  static void run_on_results(const ScratchDir& out, const std::string& snippet, std::string* log) {
    const std::string script = "from arbor_analysis import results as ar\n"
                               "df = ar.load_results('" + out.str() + "')\n" + snippet;
    const int status = run_to_end({"/usr/bin/env", kPythonPath, kPython, "-c", script}, out / "log.txt");
    *log = read_text(out / "log.txt");
    ASSERT_EQ(status, 0) << *log;
  }
  // One clutter_study.sh run: OUT/runs/NAME/result.json with the fields analysis/studies/clutter.py reads.
  static void write_clutter_run(const ScratchDir& out, const std::string& name, double ate_aligned, int landmarks = 100,
                                int spurious = 0, double wall_s = 1.0) {
    const std::filesystem::path dir = std::filesystem::path(out.str()) / "runs" / name;
    std::filesystem::create_directories(dir);
    std::ofstream(dir / "result.json")
        << "{\"assoc_f1\": 0.98, \"ate_rmse_m\": 1.0, \"ate_aligned_rmse_m\": " << ate_aligned << ", \"landmarks\": "
        << landmarks << ", \"observed_true_landmarks\": 100, \"spurious_landmarks\": " << spurious
        << ", \"wall_time_s\": " << wall_s << "}";
  }
};

TEST_F(AnalysisScripts, ReportBuildsEveryFigureAndTableFromTheFixture) {
  ScratchDir out("report");
  ASSERT_EQ(run_to_end({kPython, kSource + "/analysis/report", fixture(), "--out", out.str()}, out / "log.txt"), 0)
      << read_text(out / "log.txt");
  const std::string report = read_text(out / "report.md");
  for (const char* figure : {"complexity_step_time.png", "accuracy_vs_particles.png", "association_vs_clutter.png",
                             "hypotheses_vs_map_size.png", "thread_scaling.png", "trajectory_best.png"}) {
    EXPECT_GT(std::filesystem::file_size(out / figure), 1000u) << figure;
    EXPECT_NE(report.find(std::string("(") + figure + ")"), std::string::npos) << figure << " not linked";
  }
  for (const char* section : {"## FastSLAM vs smoother", "## Paired comparisons", "## Runs that did not finish",
                              "synthetic failure"})
    EXPECT_NE(report.find(section), std::string::npos) << section;
  // The fixture's slopes are known by construction: naive ~1, tree ~0 (see make_fixture.py).
  EXPECT_NE(read_text(out / "log.txt").find("naive: log-log slope 0.9"), std::string::npos) << read_text(out / "log.txt");
  // The half-written last row of the fixture is not a row.
  EXPECT_EQ(report.find("half-written"), std::string::npos);
  EXPECT_EQ(report.find("|  |"), std::string::npos) << "an empty table cell";
  // The same report as one self-contained page: every figure embedded, nothing fetched, no empty table.
  const std::string page = read_text(out / "report.html");
  std::size_t embedded = 0;
  for (std::size_t at = page.find("<img "); at != std::string::npos; at = page.find("<img ", at + 1)) {
    EXPECT_EQ(page.compare(page.find("src=", at), 27, "src=\"data:image/png;base64,"), 0) << page.substr(at, 80);
    ++embedded;
  }
  EXPECT_EQ(embedded, 6u);
  EXPECT_EQ(page.find("<tbody>\n</tbody>"), std::string::npos) << "an empty table";
  EXPECT_EQ(page.find("http"), std::string::npos) << "a network reference";
  EXPECT_NE(page.find("<strong>What this shows</strong>"), std::string::npos);
}

// The report imports every section module; a section's own command line (python3 -m arbor_analysis.NAME) is one
// shared wrapper (main_for in arbor_analysis/results.py), so one section and the run-directory plot stand for the
// rest (Python start-up with matplotlib costs seconds per process on the 2-core CI machine).
TEST_F(AnalysisScripts, FigureScriptsRunOnTheirOwn) {
  ScratchDir out("figures");
  ASSERT_EQ(run_to_end({"/usr/bin/env", kPythonPath, kPython, "-m", "arbor_analysis.accuracy", fixture(), "--out",
                        out.str()},
                       out / "log.txt"),
            0)
      << read_text(out / "log.txt");
  EXPECT_GT(std::filesystem::file_size(out / "accuracy_vs_particles.png"), 1000u);
  const std::string run = fixture() + "/runs/uniform-n100-t300-c0__smoother-s1-t1";
  ASSERT_EQ(run_to_end({"/usr/bin/env", kPythonPath, kPython, "-m", "arbor_analysis.trajectory", run, "--out",
                        out / "run.png"},
                       out / "log.txt"),
            0)
      << read_text(out / "log.txt");
  EXPECT_GT(std::filesystem::file_size(out / "run.png"), 1000u);
}

// A sweep that varies a run option writes it between threads and scenario; the analysis keeps its text
// (not NaN), tells configurations apart by it, and every label part names its dimension.
TEST_F(AnalysisScripts, RunOptionsSeparateConfigurationsAndLabelsNameTheirDimensions) {
  ScratchDir out("options");
  std::ofstream(out / "results.jsonl")
      << R"({"key":"a","status":"ok","filter":"fastslam2","map":"tree","assoc":"nn","particles":10,"seed":1,)"
      << R"("threads":1,"likelihood":"gaussian","scenario":"s","run_dir":"runs/a","clutter":2})" << "\n"
      << R"({"key":"b","status":"ok","filter":"fastslam2","map":"tree","assoc":"nn","particles":10,"seed":1,)"
      << R"("threads":1,"likelihood":"student-t","scenario":"s","run_dir":"runs/b","clutter":2})" << "\n";
  std::string log;
  ASSERT_NO_FATAL_FAILURE(run_on_results(
      out,
      "print(ar.run_option_columns(df), sorted(df['likelihood']))\n"
      "for name, g in ar.lines_for(df.assign(x=[1, 2]), 'x', min_points=1): print(name)\n"
      "print(ar.label(df.iloc[0], ['filter', 'assoc', 'clutter', 'particles']))\n",
      &log));
  EXPECT_NE(log.find("['likelihood'] ['gaussian', 'student-t']"), std::string::npos) << log;
  EXPECT_NE(log.find("\nlikelihood = gaussian\n"), std::string::npos) << log;
  EXPECT_NE(log.find("\nlikelihood = student-t\n"), std::string::npos) << log;
  EXPECT_NE(log.find("fastslam2/nn, clutter = 2 /scan, particles = 10"), std::string::npos) << log;
}

// The clutter study's table: known association is the reference of each world and clutter rate (its ratio
// is 1), and the ratio of another strategy is the ratio of the mean aligned ATEs.
TEST_F(AnalysisScripts, ClutterTableComparesWithKnownAssociation) {
  ScratchDir out("clutter");
  const auto write_run = [&](const std::string& name, double ate_aligned, int landmarks) {
    write_clutter_run(out, name, ate_aligned, landmarks, /*spurious=*/2, /*wall_s=*/1.5);
  };
  write_run("rooms-c2-s1-known", 0.2, 100);
  write_run("rooms-c2-s2-known", 0.4, 100);
  write_run("rooms-c2-s1-jcbb", 0.3, 104);
  write_run("rooms-c2-s2-jcbb", 0.6, 106);
  write_run("rooms-c2-s1-nn", 0.5, 100);
  write_run("rooms-c2-s2-nn", 0.5, 100);
  write_run("not-a-run", 9.0, 1);
  ASSERT_EQ(run_to_end({kPython, kSource + "/analysis/studies/clutter.py", out.str()}, out / "log.txt"), 0)
      << read_text(out / "log.txt");
  const std::string table = read_text(out / "clutter.md");
  EXPECT_NE(table.find("| rooms | 2 | known | 2 | 0.98 | 1 | 0.3 | 1 | 1 |"), std::string::npos) << table;
  EXPECT_NE(table.find("| rooms | 2 | jcbb | 2 | 0.98 | 1 | 0.45 | 1.5 | 1.05 |"), std::string::npos) << table;
  // JCBB against NN paired by seed: -0.2 m on seed 1, +0.1 m on seed 2; two pairs list their values.
  EXPECT_NE(table.find("| rooms | 2 | 2 | 0 / 0 | 0 of 2 | -0.2 / 0.1 | 1 of 2 |"), std::string::npos) << table;
  EXPECT_GT(std::filesystem::file_size(out / "clutter.png"), 1000u);
}

// The ATE ratio to known association comes with a bootstrap interval over the seeds: where every seed has the
// same ratio (1.5 here) the interval is that ratio; below three seeds there is none. A committed study (no
// runs/, only its clutter.csv) renders the same tables.
TEST_F(AnalysisScripts, ClutterRatioToKnownCarriesItsSeedInterval) {
  ScratchDir out("clutter_interval");
  const auto write_run = [&](const std::string& name, double ate_aligned) { write_clutter_run(out, name, ate_aligned); };
  for (int seed = 1; seed <= 3; ++seed) {
    write_run("rooms-c2-s" + std::to_string(seed) + "-known", 0.1 * seed);
    write_run("rooms-c2-s" + std::to_string(seed) + "-jcbb", 0.15 * seed);
    if (seed <= 2) write_run("rooms-c2-s" + std::to_string(seed) + "-nn", 0.2 * seed);
  }
  ASSERT_EQ(run_to_end({kPython, kSource + "/analysis/studies/clutter.py", out.str()}, out / "log.txt"), 0)
      << read_text(out / "log.txt");
  const std::string table = read_text(out / "clutter.md");
  EXPECT_NE(table.find("| rooms | 2 | jcbb | 3 | 1.5 | 1.5 – 1.5 |"), std::string::npos) << table;
  EXPECT_NE(table.find("| rooms | 2 | nn | 2 | 2 | – |"), std::string::npos) << table;
  std::filesystem::remove_all(out / "runs");
  std::filesystem::remove(out / "clutter.md");
  ASSERT_EQ(run_to_end({kPython, kSource + "/analysis/studies/clutter.py", out.str()}, out / "log.txt"), 0)
      << read_text(out / "log.txt");
  EXPECT_EQ(read_text(out / "clutter.md"), table);
}

// On simulated data the reference is known association without its gate (the gate refuses loop closures a
// drifted particle set cannot hold): where those runs exist, a second table gives every other strategy's
// ratio to them. Here known association's gated runs are 2x its ungated ones and JCBB's 3x, so JCBB is 1.5x
// the gated reference and 3x the ungated one.
TEST_F(AnalysisScripts, ClutterRatioAlsoAgainstKnownAssociationWithoutItsGate) {
  ScratchDir out("clutter_no_gate");
  const auto write_run = [&](const std::string& name, double ate_aligned) { write_clutter_run(out, name, ate_aligned); };
  for (int seed = 1; seed <= 3; ++seed) {
    const std::string world = "rooms-c2-s" + std::to_string(seed);
    write_run(world + "-known_no_gate", 0.1 * seed);
    write_run(world + "-known", 0.2 * seed);
    write_run(world + "-jcbb", 0.3 * seed);
  }
  ASSERT_EQ(run_to_end({kPython, kSource + "/analysis/studies/clutter.py", out.str()}, out / "log.txt"), 0)
      << read_text(out / "log.txt");
  const std::string table = read_text(out / "clutter.md");
  const std::size_t second = table.find("without its gate (known_no_gate)");
  ASSERT_NE(second, std::string::npos) << table;
  EXPECT_NE(table.find("| rooms | 2 | jcbb | 3 | 1.5 | 1.5 – 1.5 |"), std::string::npos) << table;
  EXPECT_NE(table.find("| rooms | 2 | jcbb | 3 | 3 | 3 – 3 |", second), std::string::npos) << table;
  EXPECT_EQ(table.find("| rooms | 2 | known | 3 |", second), std::string::npos)
      << "the gated reference is not a strategy of the second table";
}

// A world run under several filter seeds (clutter_study.sh FILTER_OFFSETS) is one sample, not several: its
// runs are averaged before the bootstrap. Here JCBB's runs are 1x and 2x known association's on every world,
// so each world's ratio is 1.5 and so is the whole interval; resampling the runs would widen it.
TEST_F(AnalysisScripts, ClutterStudyAveragesAWorldsFilterSeedsBeforeItsInterval) {
  ScratchDir out("clutter_filter_seeds");
  const auto write_run = [&](const std::string& name, double ate_aligned) { write_clutter_run(out, name, ate_aligned); };
  for (int seed = 1; seed <= 3; ++seed) {
    const std::string world = "rooms-c2-s" + std::to_string(seed), other = "-f" + std::to_string(seed + 1000);
    write_run(world + "-known", 0.1 * seed);
    write_run(world + other + "-known", 0.1 * seed);
    write_run(world + "-jcbb", 0.1 * seed);
    write_run(world + other + "-jcbb", 0.2 * seed);
  }
  ASSERT_EQ(run_to_end({kPython, kSource + "/analysis/studies/clutter.py", out.str()}, out / "log.txt"), 0)
      << read_text(out / "log.txt");
  const std::string table = read_text(out / "clutter.md");
  EXPECT_NE(table.find("| rooms | 2 | jcbb | 3 | 0.98 | 1 | 0.3 | 1.5 |"), std::string::npos) << table;
  EXPECT_NE(table.find("| rooms | 2 | jcbb | 3 | 1.5 | 1.5 – 1.5 |"), std::string::npos) << table;
}

// Honest statistics: with two seeds a table lists both values, not "mean ± 12.7 standard errors"; a paired
// comparison pairs runs by scenario and seed, gives no interval below three pairs, and calls a difference
// significant only when its interval excludes zero. Here JCBB's ATE is below NN's on every one of 4 seeds by
// 0.1 m, while the seeds' own ATEs spread over 1 m: unpaired, the intervals would overlap.
TEST_F(AnalysisScripts, PairedComparisonsPairBySeedAndNeedThreePairs) {
  ScratchDir out("paired");
  const auto row = [](const std::string& assoc, int seed, double ate, int particles) {
    return "{\"key\":\"" + assoc + std::to_string(seed) + "p" + std::to_string(particles) +
           "\",\"status\":\"ok\",\"filter\":\"fastslam2\",\"map\":\"tree\",\"assoc\":\"" + assoc +
           "\",\"particles\":" + std::to_string(particles) + ",\"seed\":" + std::to_string(seed) +
           ",\"threads\":1,\"scenario\":\"s" + std::to_string(seed) + "\",\"ate_rmse_m\":" + std::to_string(ate) +
           "}\n";
  };
  {
    std::ofstream f(out / "results.jsonl");
    for (int seed = 1; seed <= 4; ++seed) {
      f << row("nn", seed, 0.5 * seed + 0.1, 100) << row("jcbb", seed, 0.5 * seed, 100);
      if (seed <= 2) f << row("nn", seed, 0.5 * seed + 0.3, 10) << row("jcbb", seed, 0.5 * seed, 10);
    }
  }
  std::string log;
  ASSERT_NO_FATAL_FAILURE(run_on_results(
      out,
      "from arbor_analysis import accuracy, paired\n"
      "for s in accuracy.make(df, '" + out.str() + "') + paired.make(df, '" + out.str() + "'):"
      " print(s.text)\n",
      &log));
  // 10 particles: two seeds, so the two values (0.5 and 1); 100 particles: four, so an interval.
  EXPECT_NE(log.find("| jcbb | 10 | 0.5 / 1 | 2 |"), std::string::npos) << log;
  EXPECT_NE(log.find("| jcbb | 100 | 1.25 ± 1 | 4 |"), std::string::npos) << log;
  // All 6 pairs have JCBB lower: the 4 at 100 particles by 0.1 m, the 2 at 10 by 0.3 m.
  EXPECT_NE(log.find("| jcbb − nn | ATE RMSE | 6 | -0.167 | ± 0.11 | 6 / 0 | yes |"), std::string::npos) << log;
  EXPECT_NE(log.find("- **jcbb** beats nn on ATE RMSE"), std::string::npos) << log;
  // Particles: two seeds × two strategies pair; NN gains 0.2 m from more particles, JCBB nothing: no claim.
  EXPECT_NE(log.find("| particles = 10 − particles = 100 | ATE RMSE | 4 | 0.1 | ± 0.18 | 0 / 2 | no |"),
            std::string::npos) << log;
  EXPECT_EQ(log.find("beats particles"), std::string::npos) << log;
}

// A real dataset's report opens with its accuracy table: the reference named from the scenario's metadata,
// dead reckoning beside the filter, and the run time against the data's duration; a simulated sweep has none.
TEST_F(AnalysisScripts, DatasetSweepsGetAnAccuracyTableAgainstTheirReference) {
  ScratchDir out("dataset");
  {
    std::ofstream rows(out / "results.jsonl");
    for (const char* assoc : {"nn", "jcbb"})
      for (int seed = 1; seed <= 3; ++seed) {
        const std::string key = std::string(assoc) + std::to_string(seed);
        rows << R"({"key":")" << key << R"(","status":"ok","dataset":"d/park.scn","filter":"fastslam2","map":"trie",)"
             << R"("assoc":")" << assoc << R"(","particles":100,"seed":)" << seed << R"(,"threads":1,"scenario":"d/park.scn",)"
             << R"("run_dir":"runs/)" << key << R"(","ate_rmse_m":)" << (assoc == std::string("nn") ? 2.0 : 1.0) + 0.1 * seed
             << R"(,"landmarks":200,"wall_time_s":10})" << "\n";
        const std::filesystem::path run = std::filesystem::path(out.str()) / "runs" / key;
        std::filesystem::create_directories(run);
        std::ofstream(run / "result.json")
            << R"({"scenario_duration_s":1500,"dead_reckoning_ate_m":93.1,"scenario":{"truth_track":"gps_track",)"
            << R"("source":"victoria-park","citation":"Guivant2001"}})";
      }
  }
  std::string log;
  ASSERT_NO_FATAL_FAILURE(run_on_results(
      out,
      "from arbor_analysis import dataset_accuracy\n"
      "for s in dataset_accuracy.make(df, '" + out.str() + "', '" + out.str() + "'):"
      " print('##', s.title); print(s.text)\n"
      "print('simulated:', dataset_accuracy.make(df.assign(dataset=None), '" + out.str() +
          "', '" + out.str() + "'))\n",
      &log));
  EXPECT_NE(log.find("## Accuracy on park"), std::string::npos) << log;
  EXPECT_NE(log.find("reference trajectory gps_track; source victoria-park; citation Guivant2001; 1500 s of data"),
            std::string::npos) << log;
  EXPECT_NE(log.find("| jcbb | 3 | 1.2 ± 0.25 | 93.1 | 200 | 10 | 150× |"), std::string::npos) << log;
  EXPECT_NE(log.find("| nn | 3 | 2.2 ± 0.25 | 93.1 | 200 | 10 | 150× |"), std::string::npos) << log;
  EXPECT_NE(log.find("simulated: []"), std::string::npos) << log;
}

// Issue 41: failures are counted, not averaged away. A run fails when its aligned ATE is above 3x the
// smoother's on its scenario and seed, above dead reckoning's, or when it did not finish. On rooms seeds 1-5
// the smoother has 0.4 m and the runs 0.75x, 1.25x, exactly 2.9x (below dead reckoning: no failure), 2x but
// above dead reckoning (a failure) and 3.25x (a failure); seed 6 crashed. A dataset run without a smoother,
// below dead reckoning, counts in the report's table but in its own group of heldout.md.
TEST_F(AnalysisScripts, FailureRateAndTailsAreComputedRightOnHandMadeRuns) {
  ScratchDir out("failures");
  {
    std::ofstream rows(out / "results.jsonl");
    const auto write_row = [&](const std::string& key, const std::string& status, const std::string& scenario,
                               const std::string& method, int seed, const std::string& metrics) {
      rows << R"({"key":")" << key << R"(","status":")" << status << R"(",)" << scenario << "," << method
           << R"(,"seed":)" << seed << R"(,"threads":1,"scenario":")" << key << R"(","run_dir":"runs/)" << key
           << R"(",)" << metrics << "}\n";
    };
    const auto rooms = [](int seed) {
      return R"("dataset":null,"world":"rooms","world_landmarks":250,"world_steps":500,"clutter":2,"world_seed":)" +
             std::to_string(seed);
    };
    const std::string smoother = R"("filter":"smoother","map":null,"assoc":"known","particles":null)";
    const std::string fastslam = R"("filter":"fastslam2","map":"tree","assoc":"nn","particles":100)";
    const double ate[] = {0.3, 0.5, 1.16, 0.8, 1.3};
    const double dead_reckoning[] = {1.2, 1.2, 2.0, 0.7, 2.0};
    const char* horizon[] = {"null", "null", "40", "20", "10"};
    const double f1[] = {0.9, 0.95, 0.8, 0.7, 0.6};
    for (int seed = 1; seed <= 5; ++seed) {
      std::ostringstream common;
      common << R"("dead_reckoning_ate_m":)" << dead_reckoning[seed - 1];
      write_row("smoother" + std::to_string(seed), "ok", rooms(seed), smoother, seed,
                R"("ate_aligned_rmse_m":0.4,)" + common.str());
      std::ostringstream metrics;
      metrics << R"("ate_aligned_rmse_m":)" << ate[seed - 1] << "," << common.str() << R"(,"nees_median":)"
              << seed + 1 << R"(,"consistency_horizon_scan":)" << horizon[seed - 1]
              << R"(,"rejected_measurements":1,"assoc_f1":)" << f1[seed - 1];
      write_row("fastslam" + std::to_string(seed), "ok", rooms(seed), fastslam, seed, metrics.str());
    }
    write_row("fastslam6", "crashed", rooms(6), fastslam, 6, R"("error":"signal 11","ate_aligned_rmse_m":null)");
    write_row("park1", "ok",
              R"("dataset":"d/park.scn","world":null,"world_landmarks":null,"world_steps":null,"clutter":null,)"
              R"("world_seed":null)",
              fastslam, 1, R"("ate_aligned_rmse_m":2.2,"dead_reckoning_ate_m":93.1,"rejected_measurements":0)");
  }
  // The report's section: one row per configuration over every scenario, the smoother as the reference.
  std::string log;
  ASSERT_NO_FATAL_FAILURE(run_on_results(
      out,
      "from arbor_analysis import failures\n"
      "for s in failures.make(df, '" + out.str() + "'): print('##', s.title); print(s.text)\n",
      &log));
  EXPECT_NE(log.find("## Failures and tails"), std::string::npos) << log;
  EXPECT_NE(log.find("| configuration | runs | failures | mean ATE (m) | median ATE (m) | p90 ATE (m) | median NEES | "
                     "consistency horizon (scan) | mean ATE ratio to smoother |"),
            std::string::npos) << log;
  EXPECT_NE(log.find("| smoother (reference) | 5 | 0/5 (0 %) | 0.4 | 0.4 | 0.4 | – | – | – |"), std::string::npos)
      << log;
  // Finished ATEs 0.3, 0.5, 0.8, 1.16, 1.3, 2.2: median (0.8 + 1.16) / 2, p90 1.3 + 0.5 × 0.9. Mean ratio over
  // the five runs with a smoother: (0.75 + 1.25 + 2.9 + 2 + 3.25) / 5.
  EXPECT_NE(log.find("| fastslam2 | 7 | 3/7 (43 %) | 1.04 | 0.98 | 1.75 | 4 | 20 (3 of 6) | 2.03 |"), std::string::npos)
      << log;

  // heldout.md: rooms on its own, all simulated worlds (the same runs here), and the dataset apart.
  ASSERT_EQ(run_to_end({kPython, kSource + "/analysis/studies/heldout.py", out.str()}, out / "heldout.log"), 0)
      << read_text(out / "heldout.log");
  const std::string table = read_text(out / "heldout.md");
  // Finished ATEs 0.3, 0.5, 0.8, 1.16, 1.3: p90 1.16 + 0.6 × 0.14; median 0.8 over the smoother's 0.4.
  for (const char* group : {"| rooms, clutter = 2 /scan |", "| all simulated worlds |"}) {
    EXPECT_NE(table.find(std::string(group) + " fastslam2 | 6 | 3/6 (50 %) | 0.812 | 0.8 | 1.24 | 4 | 20 (3 of 5) | "
                         "5 | 0.8 | 2 |"),
              std::string::npos) << table;
    EXPECT_NE(table.find(std::string(group) + " smoother (reference) | 5 | 0/5 (0 %) | 0.4 | 0.4 | 0.4 | – | – | – | "
                         "– | 1 |"),
              std::string::npos) << table;
  }
  EXPECT_NE(table.find("| park | fastslam2 | 1 | 0/1 (0 %) | 2.2 | 2.2 | 2.2 | – | – | 0 | – | – |"), std::string::npos)
      << table;
  // The CSV keeps the numbers: runs, finished, failures, failure rate.
  const std::string csv = read_text(out / "heldout.csv");
  EXPECT_NE(csv.find("\"rooms, clutter = 2 /scan\",fastslam2,6,5,3,0.5,"), std::string::npos) << csv;
}

// results.jsonl of rooms seeds 1-3: the reference smoother at 0.1 m on each, and a FastSLAM 2.0 run per seed
// ("fastslam1".."fastslam3", in runs/) with the given strategy, aligned ATE and extra fields ("" or ",...").
void write_rooms_results(const std::filesystem::path& file, const std::string& assoc, const double (&ate)[3],
                         const std::string (&extra)[3]) {
  std::ofstream rows(file);
  const std::string rooms = R"("dataset":null,"world":"rooms","world_landmarks":250,"world_steps":500,"clutter":0)";
  for (int seed = 1; seed <= 3; ++seed) {
    const std::string n = std::to_string(seed);
    rows << R"({"key":"smoother)" << n << R"(","status":"ok",)" << rooms << R"(,"world_seed":)" << n
         << R"(,"filter":"smoother","map":null,"assoc":"known","particles":null,"seed":)" << n
         << R"(,"threads":1,"scenario":"rooms.scn","run_dir":"runs/smoother)" << n
         << R"(","ate_aligned_rmse_m":0.1,"dead_reckoning_ate_m":5})" << "\n";
    rows << R"({"key":"fastslam)" << n << R"(","status":"ok",)" << rooms << R"(,"world_seed":)" << n
         << R"(,"filter":"fastslam2","map":"tree","assoc":")" << assoc << R"(","particles":100,"seed":)" << n
         << R"(,"threads":1,"scenario":"rooms.scn","run_dir":"runs/fastslam)" << n << R"(","ate_aligned_rmse_m":)"
         << ate[seed - 1] << R"(,"dead_reckoning_ate_m":5)" << extra[seed - 1] << "}\n";
  }
}

// Issue 41: the smoother given each run's own pairings. On rooms seeds 1-3 the reference smoother has 0.1 m; run
// 1 fails (1.0 m) and its twin passes (0.2 m): its path alone failed; run 2 fails and so does its twin (0.5 m);
// run 3 passes (0.2 m) and its twin did not finish (a folder without result.json), which counts as failed. Runs
// 2 and 3 map true landmark 7 twice, the copy started 60 scans after 7 was last measured, and landmark 8
// twice, its copy 10 scans after: two landmarks mapped twice, one copy after a gap.
TEST_F(AnalysisScripts, OwnPairingsSeparatePathFromPairingFailuresAndCountLateCopies) {
  ScratchDir out("own_pairings");
  {
    std::ofstream scenario(out / "rooms.scn");
    scenario << "arbor-scenario 2\n";
    for (int step = 0; step <= 60; ++step) {
      scenario << "step " << step << " 0 0 1\n";
      if (step == 0) scenario << "scan 2\nz 1 0 - 7\nz 1 0 - 8\n";
      if (step == 10) scenario << "scan 1\nz 1 0 - 8\n";
      if (step == 60) scenario << "scan 2\nz 1 0 - 7\nz 1 0 - clutter\n";
    }
  }
  const std::filesystem::path root(out.str());
  const auto write_run = [&](const std::string& key, const std::string& associations) {
    std::filesystem::create_directories(root / "runs" / key);
    std::ofstream(root / "runs" / key / "associations.csv") << "step,measurement,landmark\n" << associations;
  };
  const auto write_twin = [&](const std::string& key, const char* ate) {
    std::filesystem::create_directories(root / "own_pairings" / key);
    if (ate) std::ofstream(root / "own_pairings" / key / "result.json") << "{\"ate_aligned_rmse_m\": " << ate << "}";
  };
  write_rooms_results(out / "results.jsonl", "jcbb", {1.0, 0.5, 0.2},
                      {R"(,"assoc_f1":0.9)", R"(,"assoc_f1":0.8)", R"(,"assoc_f1":0.7)"});
  write_run("fastslam1", "0,0,0\n0,1,1\n10,0,1\n60,0,0\n60,1,-1\n");
  for (const char* key : {"fastslam2", "fastslam3"}) write_run(key, "0,0,0\n0,1,1\n10,0,2\n60,0,3\n60,1,-1\n");
  write_twin("fastslam1", "0.2");
  write_twin("fastslam2", "0.5");
  write_twin("fastslam3", nullptr);
  ASSERT_EQ(run_to_end({kPython, kSource + "/analysis/studies/own_pairings.py", out.str()}, out / "log.txt"), 0)
      << read_text(out / "log.txt");
  const std::string table = read_text(out / "own_pairings.md");
  // Runs, failures, twins failing, path only, both, only the twin; medians of ATE (1.0, 0.5, 0.2), the finished
  // twins (0.2, 0.5), the reference, F1; landmarks mapped twice (0, 2, 2) and late copies (0, 1, 1).
  for (const char* group : {"rooms", "all"})
    EXPECT_NE(table.find(std::string("| fastslam2 | ") + group + " | 3 | 2 | 2 | 1 | 1 | 1 | 0.5 | 0.35 | 0.1 | 0.8 | 2 | 1 |"),
              std::string::npos) << table;
}

// Issue 41: the particle set's memory (steps.csv's ancestor_age_s) against the loops it closes. Rooms seeds 1-3,
// reference smoother 0.1 m, runs 1.0 / 0.5 / 0.2 m (two fail). Scans at 5, 10, 20 and 60 s; landmark 7 is seen
// at 5 s and again at 60 s (a loop of 55 s), landmark 8 at 10 and 20 s (10 s: no loop). Run 1's paths never
// meet (memory: the run so far, 5 / 10 / 20 / 60 s, median 15), so its loop is within it; runs 2 and 3 remember
// 10 and 30 s at the loop (ages 0, 5, 5 before: median 5), so theirs is closed beyond it. Median of the medians
// 5 s, p90 13 s; 3 loops, 2 beyond; the failed runs remember 15 and 5 s (median 10), the other 5 s.
TEST_F(AnalysisScripts, LineageComparesTheSetsMemoryWithItsLoops) {
  ScratchDir out("lineage");
  {
    std::ofstream scenario(out / "rooms.scn");
    scenario << "arbor-scenario 2\n";
    for (int step = 0; step <= 60; ++step) {
      scenario << "step " << step << " 0 0 1\n";
      if (step == 5 || step == 60) scenario << "scan 1\nz 1 0 - 7\n";
      if (step == 10 || step == 20) scenario << "scan 2\nz 1 0 - 8\nz 1 0 - clutter\n";
    }
  }
  const std::filesystem::path root(out.str());
  write_rooms_results(out / "results.jsonl", "known", {1.0, 0.5, 0.2}, {"", "", ""});
  const int scans[] = {5, 10, 20, 60};
  const char* ages[3][4] = {{"", "", "", ""}, {"0", "5", "5", "10"}, {"0", "5", "5", "30"}};
  for (int run = 0; run < 3; ++run) {
    const std::filesystem::path dir = root / "runs" / ("fastslam" + std::to_string(run + 1));
    std::filesystem::create_directories(dir);
    std::ofstream steps(dir / "steps.csv");
    steps << "step,time_s,scan,ancestor_age_s\n";
    for (int k = 0; k < 4; ++k)  // each scan, then an odometry step (not a scan)
      steps << scans[k] << "," << scans[k] << ",1," << ages[run][k] << "\n" << scans[k] + 1 << "," << scans[k] + 1 << ",0,\n";
  }
  ASSERT_EQ(run_to_end({kPython, kSource + "/analysis/studies/lineage.py", out.str()}, out / "log.txt"), 0)
      << read_text(out / "log.txt");
  const std::string table = read_text(out / "lineage.md");
  for (const char* group : {"rooms", "all"})
    EXPECT_NE(table.find(std::string("| fastslam2 | ") + group + " | 3 | 2 | 0.5 | 5 | 13 | 3 | 2 | 10 | 5 |"),
              std::string::npos) << table;
}

// The filter over time: a table row per configuration from its representative run's steps.csv (the largest
// particle count), and the figure with step time per back end and N_eff per strategy.
TEST_F(AnalysisScripts, StepSeriesSummarisesStepTimeAndEffectiveSampleSize) {
  ScratchDir out("steps");
  {
    std::ofstream rows(out / "results.jsonl");
    for (const char* map : {"tree", "trie"})
      for (int particles : {10, 100}) {
        const std::string key = std::string(map) + std::to_string(particles);
        rows << R"({"key":")" << key << R"(","status":"ok","filter":"fastslam2","map":")" << map
             << R"(","assoc":"nn","particles":)" << particles << R"(,"seed":1,"threads":1,"scenario":"s","run_dir":"runs/)"
             << key << R"("})" << "\n";
        const std::filesystem::path run = std::filesystem::path(out.str()) / "runs" / key;
        std::filesystem::create_directories(run);
        std::ofstream steps(run / "steps.csv");
        steps << "step,time_s,step_time_s,n_eff,resampled\n";
        // 100 particles: steps of 1, 2, 3, 4 ms with N_eff 50 or 100, resampled once in four.
        for (int k = 0; k < 4; ++k)
          steps << k << "," << 0.5 * k << "," << 0.001 * (k + 1) << "," << (k % 2 ? 50 : particles) << ","
                << (k == 3 ? 1 : 0) << "\n";
      }
  }
  std::string log;
  ASSERT_NO_FATAL_FAILURE(run_on_results(
      out,
      "from arbor_analysis import step_series\n"
      "for s in step_series.make(df, '" + out.str() + "', '" + out.str() + "'): print(s.text)\n",
      &log));
  EXPECT_NE(log.find("| tree | 100 | 2.5 | 3.85 | 0.75 | 25 % |"), std::string::npos) << log;
  EXPECT_NE(log.find("| trie | 100 | 2.5 | 3.85 | 0.75 | 25 % |"), std::string::npos) << log;
  EXPECT_EQ(log.find("| 10 |"), std::string::npos) << "only the largest particle count: " << log;
  EXPECT_GT(std::filesystem::file_size(std::filesystem::path(out.str()) / "step_time_and_neff.png"), 1000u);
}

// trace_run.py classes each decision of the best particle against the true ids, and matches its pose to the
// truth by time (the run writes its start pose and step 0's at the same time; the later one counts).
TEST_F(AnalysisScripts, TraceRunClassesEveryDecisionAgainstTheTrueIds) {
  ScratchDir out("trace_run");
  std::ofstream(out / "world.scn") << "arbor-scenario 2\n"
                                      "step 0 0 0 0\ntruth 0 0 0\nscan 2\nz 5 0 - 0\nz 3 1 - clutter\n"
                                      "step 0.5 0 1 0\ntruth 1 0 0\nscan 2\nz 4 0 - 0\nz 6 1 - 1\n"
                                      "step 1 0 1 0\ntruth 2 0 0\nscan 3\nz 3 0 - 0\nz 5 1 - 1\nz 2 2 - clutter\n";
  std::filesystem::create_directories(out / "run");
  // Step 0: landmark 0 first, clutter starts 1. Step 1: right; landmark 1 of the clutter takes true 1 (wrong).
  // Step 2: true 0 starts landmark 2 (a duplicate), true 1 is missed, and clutter is paired with landmark 0.
  std::ofstream(out / "run/associations.csv") << "step,measurement,landmark\n0,0,0\n0,1,1\n1,0,0\n1,1,1\n"
                                                 "2,0,2\n2,1,-1\n2,2,0\n";
  std::ofstream(out / "run/trajectory.tum") << "0 9 9 0 0 0 0 1\n0 0 0 0 0 0 0 1\n0.5 1.1 0 0 0 0 0 1\n"
                                               "1 2 0.2 0 0 0 0.04997916927 0.99875026\n";
  ASSERT_EQ(run_to_end({kPython, kSource + "/analysis/studies/trace_run.py", out / "world.scn", out / "run", "--csv"},
                       out / "log.txt"),
            0)
      << read_text(out / "log.txt");
  const std::string log = read_text(out / "log.txt");
  EXPECT_NE(log.find("scan,time_s,position_error_m,heading_error_deg,measurements,clutter,first,right,duplicate,"
                     "wrong,missed,clutter_paired\n0,0,0,0,2,1,1,0,0,0,0,0\n1,0.5,0.1,0,2,0,0,1,0,1,0,0\n"
                     "2,1,0.2,5.73,3,1,0,0,1,0,1,1\n"),
            std::string::npos)
      << log;
  EXPECT_NE(log.find("# whole run: 3 scans; first 1, right 1, duplicate 1, wrong 1, missed 1, clutter_paired 1"),
            std::string::npos)
      << log;
  EXPECT_NE(log.find("# heading error first over 5 deg: scan 2"), std::string::npos) << log;

  // Without true ids (real data) there is nothing to class: a clear error, not a table of zeros.
  std::ofstream(out / "unlabelled.scn") << "step 0 0 0 0\ntruth 0 0 0\nscan 1\nz 5 0 - -\n";
  std::ofstream(out / "run/associations.csv") << "step,measurement,landmark\n0,0,0\n";
  EXPECT_EQ(run_to_end({kPython, kSource + "/analysis/studies/trace_run.py", out / "unlabelled.scn", out / "run"},
                       out / "log2.txt"),
            1);
  EXPECT_NE(read_text(out / "log2.txt").find("step 0, measurement 0: the scenario gives no true id"),
            std::string::npos)
      << read_text(out / "log2.txt");
}

// The HTML report in a real browser (headless Chromium, Debian's chromium-headless-shell): the page's own
// script records on <body> how many figures were decoded and how many tables are empty. A copy with one
// figure's bytes damaged must count one broken figure, so the check can fail.
TEST_F(AnalysisScripts, HtmlReportRendersInHeadlessChromium) {
  std::string browser;
  for (const char* candidate : {"/usr/bin/chromium-headless-shell", "/usr/bin/chromium"})
    if (std::filesystem::exists(candidate)) browser = candidate;
  if (browser.empty()) GTEST_SKIP() << "no headless Chromium (Debian: apt install chromium-headless-shell)";
  ScratchDir out("browser");
  ASSERT_EQ(run_to_end({kPython, kSource + "/analysis/report", fixture(), "--out", out.str()}, out / "log.txt"), 0)
      << read_text(out / "log.txt");
  const auto body_of = [&](const std::string& page) {
    const std::string dom = out / (page + ".dom");
    run_to_end({browser, "--no-sandbox", "--disable-gpu", "--virtual-time-budget=10000", "--dump-dom",
                "file://" + (out / page)}, dom);
    const std::string text = read_text(dom);
    const std::size_t at = text.find("<body");
    return at == std::string::npos ? text : text.substr(at, text.find('>', at) - at + 1);
  };
  EXPECT_EQ(body_of("report.html"), R"(<body data-images-loaded="6" data-images-broken="0" data-empty-tables="0">)");
  std::string page = read_text(out / "report.html");
  const std::size_t figure = page.find("base64,") + 7;
  page.replace(figure, 40, std::string(40, 'A'));  // the PNG signature and header gone
  std::ofstream(out / "damaged.html") << page;
  EXPECT_EQ(body_of("damaged.html"), R"(<body data-images-loaded="5" data-images-broken="1" data-empty-tables="0">)");
}

}  // namespace
}  // namespace arbor
