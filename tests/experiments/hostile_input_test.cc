// The hostile-input suite: one case per hostile input found by the review behind issue 14, grouped by its
// class. Each runs the real `arbor` binary on a mutated copy of a valid input and asserts the contract that
// hostile_harness.h checks.
#include <algorithm>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tests/experiments/hostile_harness.h"
#include "tests/support/scratch.h"

namespace arbor {
namespace {

using namespace hostile;  // NOLINT: the harness, shared with hostile_review_test.cc

// The robot stands still for its first four steps and sees every landmark of those scans at range 0: the
// landmarks start at the sensor and are measured there again.
void standing_on_its_landmarks(const fs::path& dir) {
  std::istringstream in(testing::read_file((dir / "w.scn").string()));
  std::string text;
  int steps = 0;
  const std::regex step(R"(^step ([^ ]+) .*)"), z(R"(^z [^ ]+ (.*))");
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("step ", 0) == 0) ++steps;
    if (steps <= 4) line = std::regex_replace(std::regex_replace(line, step, "step $1 0 0 0"), z, "z 0 $1");
    text += line + "\n";
  }
  write_text(dir / "w.scn", text);
}

// A sweep spec over the scenario w.scn with the given [grid] or [sweep] additions.
std::string sweep_spec(const std::string& sweep_extra, const std::string& grid) {
  return "[sweep]\nname = \"hostile\"\n" + sweep_extra + "\n[scenarios]\ndatasets = [\"w.scn\"]\n\n[grid]\n" +
         "filter = \"fastslam2\"\nmap = \"naive\"\nassoc = \"known\"\n" + grid;
}

const std::string kRunBase = "{arbor} run --scenario {dir}/w.scn --quiet --out {dir}/out ";
const std::string kRun = kRunBase + "--particles 8 ";
const std::string kSimulate = "{arbor} simulate --landmarks 20 --steps 5 --out {dir}/out/s.scn ";
const std::string kIsam = "victoria_park/isam_gtsam/victoria_park.txt";

// A prior map (`arbor run --prior-map`, map.csv) of these rows, refused with a message matching `message`.
HostileCase bad_prior_map(std::string name, std::string rows, std::string message) {
  return {"reader_gaps", std::move(name),
          file("m.csv", "id,x,y,cov_xx,cov_xy,cov_yy,log_odds,signature,truth_label\n" + std::move(rows)),
          kRun + "--prior-map {dir}/m.csv", 2, std::move(message)};
}

std::vector<HostileCase> hostile_cases() {
  const std::string field_re = R"(:\d+: field ')";
  return {
      // 1. Aborts on accepted input: now either a finite run or an input error.
      {"aborts", "zero_range_known", scenario_edit("^z [^ \n]+", "z 0"), kRun + "--assoc known", 0, ""},
      {"aborts", "zero_range_fastslam1_nn", scenario_edit("^z [^ \n]+", "z 0"), kRun + "--filter fastslam1 --assoc nn", 0, ""},
      {"aborts", "zero_range_jcbb", scenario_edit("^z [^ \n]+", "z 0"), kRun + "--assoc jcbb", 0, ""},
      {"aborts", "zero_range_locality", scenario_edit("^z [^ \n]+", "z 0"), kRun + "--assoc locality", 0, ""},
      {"aborts", "standing_on_its_landmarks_fastslam1_nn", standing_on_its_landmarks, kRun + "--filter fastslam1 --assoc nn", 0, ""},
      {"aborts", "standing_on_its_landmarks_fastslam2_known", standing_on_its_landmarks, kRun + "--assoc known", 0, ""},
      // Every landmark at the sensor is compatible with every measurement: JCBB searches until its budget (the
      // default's 6e6 nodes take 1 s in Release and 54 s under ASan, so a smaller one here).
      {"aborts", "standing_on_its_landmarks_jcbb", standing_on_its_landmarks, kRun + "--assoc jcbb --max-hypotheses 10000", 0, ""},
      {"aborts", "smoother_standing_on_its_landmarks", standing_on_its_landmarks,
       "{arbor} smooth --scenario {dir}/w.scn --quiet --out {dir}/out", 0, ""},
      {"aborts", "denormal_sigma_range", scenario_edit(R"(^(sensor [^ \n]+ [^ \n]+ [^ \n]+) [^ \n]+)", "$1 5e-324"), kRun, 2,
       "w.scn" + field_re + "sigma_range'"},
      {"aborts", "sigmas_at_their_lower_limits_nn",
       scenario_edit(R"(^(sensor [^ \n]+ [^ \n]+ [^ \n]+) [^ \n]+ [^ \n]+)", "$1 1e-6 1e-9"), kRun + "--assoc nn", 0, ""},
      {"aborts", "control_1e300", scenario_edit(R"(^step ([^ \n]+) [^ \n]+)", "step $1 1e300"), kRun, 2, "w.scn" + field_re + "u1'"},
      {"aborts", "controls_at_their_limit_fastslam1_nn",
       scenario_edit(R"(^step ([^ \n]+) [^ \n]+ [^ \n]+ [^ \n]+)", "step $1 1e6 1e6 1e6"), kRun + "--filter fastslam1 --assoc nn", 0, ""},
      {"aborts", "motion_noise_1e300", scenario_edit(R"(^motion odometry [^ \n]+)", "motion odometry 1e300"), kRun, 2,
       "w.scn" + field_re + "q_v'"},
      {"aborts", "motion_noise_at_its_limit_jcbb",
       scenario_edit(R"(^motion odometry .*)", "motion odometry 1e6 1e6 1e6 1e6 1e6"), kRun + "--assoc jcbb", 0, ""},
      {"aborts", "initial_sigma_at_its_limit_nn",
       scenario_edit(R"(^(initial [^ \n]+ [^ \n]+ [^ \n]+ [^ \n]+) .*)", "$1 1e3 1e3 1e3"), kRun + "--assoc nn", 0, ""},
      {"aborts", "new_landmark_chi2_nan", no_setup, "{arbor} associate --problem {dir}/p --new-landmark-chi2 nan", 2,
       "--new-landmark-chi2"},
      {"aborts", "new_landmark_chi2_two", no_setup, "{arbor} associate --problem {dir}/p --new-landmark-chi2 2", 2,
       "--new-landmark-chi2"},
      {"aborts", "smooth_isam_huge_covariance", dataset_edit("victoria_park", "isam_gtsam/victoria_park.txt",
                                                             R"(0\.4 0 0\.4$)", "1e300 0 1e300"),
       "{arbor} smooth --isam {dir}/" + kIsam + " --out {dir}/out", 2, "victoria_park.txt" + field_re + "c_xx'"},
      // 2. Exit 0 with NaN or nonsense.
      {"nan_output", "empty_out", no_setup, "{arbor} run --scenario {dir}/w.scn --out ''", 2, "--out: must not be empty"},
      converted_dataset_edit("nan_output", "victoria_park_speed_1e300", "victoria_park", "csv_from_mat/aa3_dr.csv",
                             R"(^(21965),[^,\n]+)", "$1,1e300", "aa3_dr.csv" + field_re + "speed_mps'"),
      {"nan_output", "smooth_isam_landmark_at_1e200",
       dataset_edit("victoria_park", "isam_gtsam/victoria_park.txt", R"(^(LANDMARK \d+ \d+) [^ \n]+)", "$1 1e200"),
       "{arbor} smooth --isam {dir}/" + kIsam + " --out {dir}/out", 2, "victoria_park.txt" + field_re + "x'"},
      converted_dataset_edit("nan_output", "utias_odometry_speed_1e300", "utias_mrclam", "Robot1_Odometry.dat",
                             R"(^(\s*[0-9.]+\s+)[^\s]+)", "$1 1e300", "Robot1_Odometry.dat" + field_re + "v'"),
      converted_dataset_edit("nan_output", "car_park_gps_at_1e300", "acfr_car_park", "csv/gps.csv",
                             R"(^([0-9.]+),[^,\n]+)", "$1,1e300", "gps.csv" + field_re + "x_east_m'"),
      // A control file cut mid-run converted with exit 0: its last reading was held through the remaining scans.
      converted_dataset_edit("nan_output", "car_park_dead_reckoning_cut", "acfr_car_park", "csv/dead_reckoning.csv",
                             R"(^49\.[\s\S]*)", "", "dead_reckoning.csv" + field_re + "time'"),
      converted_dataset_edit("nan_output", "victoria_park_no_detections", "victoria_park", "leung_extracted/measurements.dat",
                             R"([\s\S]*)", "", "measurements.dat: no tree detections"),
      // 3. Writers that emitted files their own reader rejects: now refused, and nothing written.
      {"writers", "simulate_sigma_range_zero", no_setup, kSimulate + "--sigma-range 0", 2, "field 'sigma_range'"},
      {"writers", "simulate_fov_100", no_setup, kSimulate + "--fov 100", 2, "field 'fov'"},
      {"writers", "simulate_sigma_range_1e308", no_setup, kSimulate + "--sigma-range 1e308", 2, "field 'sigma_range'"},
      {"writers", "convert_isam_landmark_at_1e200",
       dataset_edit("victoria_park", "isam_gtsam/victoria_park.txt", R"(^(LANDMARK \d+ \d+) [^ \n]+)", "$1 1e200"),
       "{arbor} convert --from isam --input {dir}/" + kIsam + " --out {dir}/out/i.scn", 2, "victoria_park.txt" + field_re + "x'"},
      converted_dataset_edit("writers", "victoria_park_time_int64_min", "victoria_park", "csv_from_mat/aa3_dr.csv",
                             R"(^21965,)", "-9223372036854775808,", "aa3_dr.csv" + field_re + "time_ms'"),
      // 4. Hangs and blow-ups: counts are checked against the bytes before anything is allocated.
      {"blowups", "problem_declaring_1e7_predictions", file("p", "arbor-association-problem 1\nobservations 0\npredictions 10000000\n"),
       "{arbor} associate --problem {dir}/p", 2, "p" + field_re + "predictions count'"},
      {"blowups", "problem_with_10001_observations", file("p", "arbor-association-problem 1\nobservations 10001\n"),
       "{arbor} associate --problem {dir}/p", 2, "p" + field_re + "observations count'"},
      {"blowups", "scan_declaring_20000_measurements", scenario_edit(R"(^scan \d+)", "scan 20000"), kRun, 2,
       "w.scn" + field_re + "count'"},
      {"blowups", "sweep_range_to_nan", file("s.toml", sweep_spec("", "particles = 4\nseed = { from = 1, to = nan }\n")),
       "{arbor} sweep {dir}/s.toml --out {dir}/out", 2, "s.toml" + field_re + "grid.seed.to'"},
      {"blowups", "sweep_float_range_to_nan",
       file("s.toml", "[sweep]\nname = \"nan\"\n[scenarios]\nworld = \"uniform\"\nlandmarks = 20\nsteps = 5\n"
                      "clutter = { from = 0.0, to = nan, step = 0.5 }\n[grid]\nfilter = \"fastslam2\"\nmap = \"naive\"\n"
                      "assoc = \"known\"\nparticles = 4\nseed = 1\n"),
       "{arbor} sweep {dir}/s.toml --out {dir}/out", 2, "s.toml" + field_re + "scenarios.clutter"},
      {"blowups", "sweep_grid_too_large", file("s.toml", sweep_spec("", "particles = 4\nseed = { from = 1, to = 100000000 }\n")),
       "{arbor} sweep {dir}/s.toml --out {dir}/out", 2, "s.toml"},
      {"blowups", "tree_search_budget_is_counted", no_setup,
       "{arbor} associate --generate --landmarks 300 --observations 30 --clutter 10 --pose-sigma 3 3 0.5 --out {dir}/p && "
       "{arbor} associate --problem {dir}/p --assoc itree --max-hypotheses 2000",
       0, "budget_exhausted=1"},
      {"blowups", "jcbb_work_budget_is_counted", no_setup,
       "{arbor} associate --generate --landmarks 60 --observations 50 --clutter 50 --pose-sigma 3 3 0.5 --density 0.2 "
       "--out {dir}/p && {arbor} associate --problem {dir}/p --assoc jcbb --max-work 1000000",
       0, "budget_exhausted=1"},
      // 5. Two sweeps into one --out. The concurrent case (a sweep while another holds the directory) is
      //    SweepEndToEnd.ASecondProcessIntoTheSameOutIsRefused, which holds the lock in-process.
      {"sweeps", "a_different_spec_into_a_used_out",
       [](const fs::path& dir) {
         write_text(dir / "a.toml", sweep_spec("", "particles = 4\nseed = 1\n"));
         write_text(dir / "b.toml", sweep_spec("", "particles = 5\nseed = 1\n"));
       },
       "{arbor} sweep {dir}/a.toml --out {dir}/out >/dev/null && {arbor} sweep {dir}/b.toml --out {dir}/out", 2, "spec"},
      // 6. A stale result.json: a failed rerun removes the earlier one before it fails.
      {"stale_result", "rerun_with_a_bad_scenario", file("bad.scn", "arbor-scenario 2\nmotion odometry 1 1 1 1\n"),
       kRun + ">/dev/null && {arbor} run --scenario {dir}/bad.scn --out {dir}/out", 2, "bad.scn" + field_re},
      {"stale_result", "rerun_with_a_bad_option", no_setup, kRun + ">/dev/null && " + kRunBase + "--particles 0", 2, "particles must be at least 1"},
      // 7. Reader gaps.
      {"reader_gaps", "header_and_end_only", file("w.scn", "arbor-scenario 2\nend 0\n"), kRun, 2, "w.scn" + field_re},
      {"reader_gaps", "motion_line_twice", scenario_edit(R"(^(motion .*))", "$1\n$1"), kRun, 2, "w.scn" + field_re + "motion'"},
      {"reader_gaps", "duplicate_landmark_id", scenario_edit(R"(^landmark 1 )", "landmark 0 "), kRun, 2, "w.scn" + field_re},
      {"reader_gaps", "min_range_above_max_range", scenario_edit(R"(^sensor [^ \n]+ [^ \n]+)", "sensor 20 30"), kRun, 2,
       "w.scn" + field_re + "min_range'"},
      {"reader_gaps", "hex_floats_are_numbers", scenario_edit(R"(^z [^ \n]+)", "z 0x1.4p+3"), kRun, 0, ""},
      {"reader_gaps", "a_directory_as_scenario", [](const fs::path& dir) { fs::create_directories(dir / "d.scn"); },
       "{arbor} run --scenario {dir}/d.scn --out {dir}/out", 2, "is a directory"},
      // A prior map (`arbor run --prior-map`, map.csv) is read with the same care as a scenario.
      bad_prior_map("prior_map_id_twice", "0,1,2,0.1,0,0.1,8,,0\n0,3,4,0.1,0,0.1,8,,1\n", "m.csv:3: field 'id'"),
      bad_prior_map("prior_map_covariance_not_positive_definite", "0,1,2,0.1,0.2,0.1,8,,0\n", "m.csv:2: field 'cov_xy'"),
      bad_prior_map("prior_map_negative_id", "-3,1,2,0.1,0,0.1,8,,0\n", "m.csv:2: field 'id'"),
      bad_prior_map("prior_map_id_leaves_no_room_for_new_ids", "2147483647,1,2,0.1,0,0.1,8,,0\n", "m.csv:2: field 'id'"),
      bad_prior_map("prior_map_coordinate_beyond_the_limits", "0,1e300,2,0.1,0,0.1,8,,0\n", "m.csv:2: field 'x'"),
      {"reader_gaps", "prior_map_absent", no_setup, kRun + "--prior-map {dir}/none.csv", 2, "--prior-map"},
      {"reader_gaps", "prior_map_surveyed", no_setup,
       "{arbor} simulate --landmarks 20 --steps 8 --clutter 1 --out {dir}/w.scn --survey-out {dir}/m.csv >/dev/null && " +
           kRun + "--assoc jcbb --prior-map {dir}/m.csv",
       0, ""},
      // 8. Exit codes and messages.
      {"messages", "run_out_under_a_file_fails_before_the_run", no_setup,
       "{arbor} run --scenario {dir}/w.scn --quiet --particles 8 --out {dir}/w.scn/out", 1,
       "w.scn/out: cannot create the output directory"},
      {"messages", "unwritable_out_exits_one", no_setup, "{arbor} simulate --landmarks 20 --steps 5 --out /proc/arbor_hostile.scn", 1,
       "/proc/arbor_hostile.scn"},
      {"messages", "option_error_names_no_empty_file", no_setup, kRunBase + "--particles 0", 2,
       "arbor: error: field 'options'"},
      {"messages", "range_bounds_are_short", no_setup, "{arbor} convert --from victoria-park --out {dir}/out/v.scn --max-gps-speed -1", 2,
       R"(--max-gps-speed: must be at least 0 \(got -1\)\n)"},
      {"messages", "max_hypotheses_negative", no_setup, kRun + "--max-hypotheses -5", 2, R"(must be at least 1 \(got -5\))"},
      {"messages", "seed_negative", no_setup, kRun + "--seed -1", 2, "--seed: must not be negative"},
      {"messages", "seed_beyond_64_bits", no_setup, kRun + "--seed 99999999999999999999999999999", 2, "--seed: must be at most"},
      {"messages", "simulate_seed_beyond_64_bits", no_setup,
       "{arbor} simulate --landmarks 20 --steps 5 --seed 18446744073709551616 --out {dir}/w.scn", 2, "--seed: must be at most"},
      {"messages", "prune_nan", no_setup, kRun + "--prune nan", 2, "--prune: must be a finite number"},
      {"messages", "max_gps_speed_nan", no_setup, "{arbor} convert --from victoria-park --out {dir}/out/v.scn --max-gps-speed nan", 2,
       "--max-gps-speed: must be a finite number"},
      // A repeated landmark row was reported against the scenario being written, not the file that held it.
      // Sizes no machine holds: refused before anything is allocated, naming the option (std::bad_alloc before).
      {"blowups", "run_with_two_billion_particles", no_setup, kRunBase + "--particles 2000000000", 2,
       "field 'particles': 2000000000 particles need at least"},
      {"blowups", "simulate_two_billion_landmarks", no_setup,
       "{arbor} simulate --landmarks 2000000000 --steps 5 --out {dir}/out/s.scn", 2,
       "field 'landmarks': 2000000000 landmarks need at least"},
      // Options the help says do not combine ran silently, one of them ignored (issue 44): both are named.
      {"messages", "known_association_with_close_loops", no_setup, kRun + "--assoc known --close-loops", 2,
       "field 'close-loops': --close-loops does not apply with --assoc known"},
      {"messages", "known_gate_without_known_association", no_setup, kRun + "--assoc jcbb --known-gate 0.9", 2,
       "field 'known-gate': --known-gate applies only to --assoc known"},
      {"messages", "move_window_with_relocalize", no_setup, kRun + "--assoc jcbb --move-window 5 --relocalize", 2,
       "field 'move-window': --move-window and --relocalize do not combine"},
      converted_dataset_edit("messages", "utias_landmark_listed_twice", "utias_mrclam", "Landmark_Groundtruth.dat",
                             R"(^(\s*6\s[^\n]*\n))", "$1$1",
                             "Landmark_Groundtruth.dat" + field_re + "subject': landmark subject 6 is listed twice"),
      converted_dataset_edit("messages", "utias_landmark_id_past_32_bits", "utias_mrclam", "Landmark_Groundtruth.dat",
                             R"(^(\s*)6(\s))", "$14294967302$2", "Landmark_Groundtruth.dat" + field_re + "subject'"),
      {"messages", "sweep_metric_typo", file("s.toml", sweep_spec("metrics = [\"ate_rmse\"]", "particles = 4\nseed = 1\n")),
       "{arbor} sweep {dir}/s.toml --out {dir}/out", 2, "s.toml" + field_re + "sweep.metrics'"},
      {"messages", "simulate_clutter_beyond_the_sampler", no_setup, kSimulate + "--clutter 5000", 2, "clutter rate must lie in"},
      {"messages", "simulate_kidnap_after_the_run", no_setup, kSimulate + "--kidnap 1e300", 2, "after the last scan"},
      {"messages", "simulate_survey_out_is_out", no_setup, kSimulate + "--survey-out {dir}/out/../out/s.scn", 2,
       "field 'survey-out'"},
      {"messages", "sweep_range_to_nan",
       file("s.toml", sweep_spec("timeout_s = { from = 0.0, to = nan, step = 0.001 }", "particles = 4\nseed = 1\n")),
       "{arbor} sweep {dir}/s.toml --out {dir}/out", 2, "s.toml" + field_re + "sweep.timeout_s.to'"},
  };
}

class HostileInput : public ::testing::TestWithParam<HostileCase> {};

TEST_P(HostileInput, ExitsCleanlyAndSaysWhere) { expect_exits_cleanly(GetParam()); }

INSTANTIATE_TEST_SUITE_P(Issue14, HostileInput, ::testing::ValuesIn(hostile_cases()),
                         [](const ::testing::TestParamInfo<HostileCase>& info) {
                           return info.param.klass + "_" + info.param.name;
                         });

// Class 8: a temporary file that a killed writer left (NAME.tmp.PID, its process gone) is removed by the
// next write of NAME; a live process's is kept.
TEST(HostileInputTemporaries, AKilledWritersTemporaryIsRemovedByTheNextRun) {
  const fs::path dir = testing::scratch_dir("hostile_temporaries");
  ASSERT_EQ(testing::run_command(testing::arbor_binary() + " simulate --landmarks 20 --steps 5 --out " + (dir / "w.scn").string()).exit_code, 0);
  // A pid that exited: a child of this test that is gone by now.
  const auto gone = testing::run_command("sh -c 'echo $$'");
  const std::string dead_pid = gone.output.substr(0, gone.output.find('\n'));
  write_text(dir / "out" / ("result.json.tmp." + dead_pid), "partial");
  write_text(dir / "out" / ("map.csv.tmp." + std::to_string(::getpid())), "live");
  const auto r = testing::run_command(testing::arbor_binary() + " run --scenario " + (dir / "w.scn").string() +
                                      " --particles 4 --quiet --out " + (dir / "out").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_FALSE(fs::exists(dir / "out" / ("result.json.tmp." + dead_pid)));
  EXPECT_TRUE(fs::exists(dir / "out" / ("map.csv.tmp." + std::to_string(::getpid()))));
  // The scenario writer's read-back copy (NAME.check.PID) of a writer killed while it read, hundreds of MB for
  // a large world, goes the same way.
  write_text(dir / ("w.scn.check." + dead_pid), "partial");
  ASSERT_EQ(testing::run_command(testing::arbor_binary() + " simulate --landmarks 20 --steps 5 --out " + (dir / "w.scn").string()).exit_code, 0);
  EXPECT_FALSE(fs::exists(dir / ("w.scn.check." + dead_pid)));
}

}  // namespace
}  // namespace arbor
