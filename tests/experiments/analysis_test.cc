// The analysis scripts run with the system Python on the committed results fixture and produce their files.
// Skipped (with the reason) where /usr/bin/python3 lacks numpy, pandas or matplotlib.
#include <filesystem>
#include <fstream>
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
  for (const char* section : {"## FastSLAM vs smoother", "## Runs that did not finish", "synthetic failure"})
    EXPECT_NE(report.find(section), std::string::npos) << section;
  // The fixture's slopes are known by construction: naive ~1, tree ~0 (see make_fixture.py).
  EXPECT_NE(read_text(out / "log.txt").find("naive: log-log slope 0.9"), std::string::npos) << read_text(out / "log.txt");
  // The half-written last row of the fixture is not a row.
  EXPECT_EQ(report.find("half-written"), std::string::npos);
}

// The report imports every figure module; the scripts' own command line is one shared wrapper
// (arbor_results.main_for), so one script and the run-directory plot stand for the rest (Python start-up with
// matplotlib costs seconds per process on the 2-core CI machine).
TEST_F(AnalysisScripts, FigureScriptsRunOnTheirOwn) {
  ScratchDir out("figures");
  ASSERT_EQ(run_to_end({kPython, kSource + "/analysis/accuracy.py", fixture(), "--out", out.str()}, out / "log.txt"), 0)
      << read_text(out / "log.txt");
  EXPECT_GT(std::filesystem::file_size(out / "accuracy_vs_particles.png"), 1000u);
  const std::string run = fixture() + "/runs/uniform-n100-t300-c0__smoother-s1-t1";
  ASSERT_EQ(run_to_end({kPython, kSource + "/analysis/trajectory.py", run, "--out", out / "run.png"}, out / "log.txt"), 0)
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
  const std::string script =
      "import sys; sys.path.insert(0, '" + kSource + "/analysis'); import arbor_results as ar\n"
      "df = ar.load_results('" + out.str() + "')\n"
      "print(ar.run_option_columns(df), sorted(df['likelihood']))\n"
      "for name, g in ar.lines_for(df.assign(x=[1, 2]), 'x', min_points=1): print(name)\n"
      "print(ar.label(df.iloc[0], ['filter', 'assoc', 'clutter', 'particles']))\n";
  ASSERT_EQ(run_to_end({kPython, "-c", script}, out / "log.txt"), 0) << read_text(out / "log.txt");
  const std::string log = read_text(out / "log.txt");
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
    const std::filesystem::path dir = std::filesystem::path(out.str()) / "runs" / name;
    std::filesystem::create_directories(dir);
    std::ofstream(dir / "result.json")
        << "{\"assoc_f1\": 0.98, \"ate_rmse_m\": 1.0, \"ate_aligned_rmse_m\": " << ate_aligned << ", \"landmarks\": "
        << landmarks << ", \"observed_true_landmarks\": 100, \"spurious_landmarks\": 2, \"wall_time_s\": 1.5}";
  };
  write_run("rooms-c2-s1-known", 0.2, 100);
  write_run("rooms-c2-s2-known", 0.4, 100);
  write_run("rooms-c2-s1-jcbb", 0.3, 104);
  write_run("rooms-c2-s2-jcbb", 0.6, 106);
  write_run("not-a-run", 9.0, 1);
  ASSERT_EQ(run_to_end({kPython, kSource + "/analysis/clutter.py", out.str()}, out / "log.txt"), 0)
      << read_text(out / "log.txt");
  const std::string table = read_text(out / "clutter.md");
  EXPECT_NE(table.find("| rooms | 2 | known | 2 | 0.98 | 1 | 0.3 | 1 | 1 |"), std::string::npos) << table;
  EXPECT_NE(table.find("| rooms | 2 | jcbb | 2 | 0.98 | 1 | 0.45 | 1.5 | 1.05 |"), std::string::npos) << table;
  EXPECT_GT(std::filesystem::file_size(out / "clutter.png"), 1000u);
}

}  // namespace
}  // namespace arbor
