// The second hostile-input review (/work/hostile_findings.md): one case per finding fixed, named after its id
// (A: crashes and hangs, B: silent wrong answers, C: messages). Each runs the real `arbor` binary and checks
// the contract of hostile_harness.h: a finite run, or exit 2 naming the file, line and field.
#include <filesystem>
#include <functional>
#include <regex>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tests/experiments/hostile_harness.h"
#include "tests/support/scratch.h"

namespace arbor {
namespace {

using namespace hostile;  // NOLINT: the shared harness

const std::string kReviewRun = "{arbor} run --scenario {dir}/w.scn --quiet --out {dir}/out --particles 8 ";
const std::string kMapHeader = "id,x,y,cov_xx,cov_xy,cov_yy,log_odds,signature,truth_label\n";
const std::string kSmoothRun1 = "{arbor} smooth --scenario {dir}/w.scn --associations {dir}/r1 --quiet --out {dir}/out";
const std::string kByteOrderMark = "\xEF\xBB\xBF";

// Every line of w.scn matching pattern replaced (scenario_edit replaces the first only).
std::function<void(const fs::path&)> scenario_edit_every(std::string pattern, std::string replacement) {
  return [=](const fs::path& dir) {
    const std::regex re(pattern, std::regex::ECMAScript | std::regex::multiline);
    write_text(dir / "w.scn", std::regex_replace(testing::read_file((dir / "w.scn").string()), re, replacement));
  };
}

// w.scn simulated again with these odometry noise densities (the drawn controls carry that noise too).
std::function<void(const fs::path&)> simulated_with_odometry_noise(std::string densities) {
  return [=](const fs::path& dir) {
    const auto r = testing::run_command(testing::arbor_binary() + " simulate --landmarks 20 --steps 10 --odometry-noise " +
                                        densities + " --out " + (dir / "w.scn").string());
    ASSERT_EQ(r.exit_code, 0) << r.output;
  };
}

// A FastSLAM run of w.scn into dir/r1, then the first match of pattern in r1/name replaced: the run directory
// `smooth --associations` reads.
std::function<void(const fs::path&)> run_then_edit(std::string name, std::string pattern, std::string replacement) {
  return [=](const fs::path& dir) {
    const auto r = testing::run_command(testing::arbor_binary() + " run --scenario " + (dir / "w.scn").string() +
                                        " --particles 8 --quiet --out " + (dir / "r1").string());
    ASSERT_EQ(r.exit_code, 0) << r.output;
    mutate(dir / "r1" / name, dir / "r1" / name, pattern, replacement);
  };
}

// A file with a UTF-8 byte-order mark put before its first line.
std::function<void(const fs::path&)> with_byte_order_mark(std::string name) {
  return [=](const fs::path& dir) { write_text(dir / name, kByteOrderMark + testing::read_file((dir / name).string())); };
}

// An Ackermann scenario whose second step steers at `steering` rad for a vehicle of the given geometry.
std::string ackermann_scenario(const std::string& vehicle, const std::string& steering) {
  return "arbor-scenario 2\nmotion ackermann 0.01 2.5e-05 " + vehicle +
         "\nsensor 20 0 3.141592653589793 0.1 0.008726646259971648 -\ninitial 0 0 0 0 0 0 0\nlandmark 0 5 0\n"
         "step 0 0 0 0\nscan 1\nz 5 0 - 0\nstep 1 1 " + steering + " 1\nscan 1\nz 5 0 - 0\nend 2\n";
}

std::vector<HostileCase> review_cases() {
  const std::string field_re = R"(:\d+: field ')";
  const std::string breakdown = R"(w.scn:\d+: field 'step': the (fastslam2|ekf) filter's arithmetic broke down at step \d+)";
  return {
      // A1, A2: motion noise or controls inside the format's limits, together too large for a filter's double
      // precision, aborted on a NaN weight or an indefinite covariance (SIGABRT); now exit 2 naming the step.
      {"A1", "motion_noise_1e6_fastslam2", simulated_with_odometry_noise("1e6 1e6 1e6 1e6 1e6"),
       "{arbor} run --scenario {dir}/w.scn --quiet --out {dir}/out --assoc known --particles 5", 2, breakdown},
      {"A1", "motion_noise_3e5_ekf", simulated_with_odometry_noise("0 0 3e5 0 0"),
       "{arbor} run --scenario {dir}/w.scn --quiet --out {dir}/out --filter ekf --assoc known", 2, breakdown},
      {"A2", "controls_1e6_fastslam2", scenario_edit_every(R"(^step ([^ \n]+) .*)", "step $1 0 1e6 0"),
       kReviewRun + "--assoc known", 2, breakdown},
      {"A2", "controls_1e6_ekf", scenario_edit_every(R"(^step ([^ \n]+) .*)", "step $1 0 1e6 0"),
       "{arbor} run --scenario {dir}/w.scn --quiet --out {dir}/out --filter ekf --assoc known", 2, breakdown},
      {"A2", "velocity_controls_1e3_fastslam2",
       [](const fs::path& dir) {
         scenario_edit(R"(^motion odometry .*)", "motion velocity 1e-6 1e-6 0.001 0.0005 0.0004")(dir);
         scenario_edit_every(R"(^step ([^ \n]+) .*)", "step $1 1e3 0 1e3")(dir);
       },
       kReviewRun + "--assoc known", 2, breakdown},
      // ... while FastSLAM 1.0, whose proposal ignores the measurements, still runs them to a finite end.
      {"A2", "controls_1e6_fastslam1", scenario_edit_every(R"(^step ([^ \n]+) .*)", "step $1 0 1e6 0"),
       kReviewRun + "--filter fastslam1 --assoc known", 0, ""},
      // A3: the documented largest prior-map id, 2^30 - 1, aborted the engine; it leaves [2^30, 2^31 - 1] for
      // the landmarks the filter starts.
      {"A3", "prior_map_largest_id_fastslam2", file("m.csv", kMapHeader + "1073741823,1,2,0.1,0,0.1,8,,0\n"),
       kReviewRun + "--prior-map {dir}/m.csv", 0, ""},
      {"A3", "prior_map_largest_id_ekf", file("m.csv", kMapHeader + "1073741823,1,2,0.1,0,0.1,8,,0\n"),
       "{arbor} run --scenario {dir}/w.scn --quiet --out {dir}/out --filter ekf --prior-map {dir}/m.csv", 0, ""},
      // A4, A5: thread counts TBB's arena crashed on (SIGSEGV) or Ceres allocated for without bound.
      {"A4", "run_threads_ten_million", no_setup, kReviewRun + "--threads 10000000", 2,
       R"(--threads: must lie in \[0, 1024\] \(got 10000000\))"},
      {"A5", "smooth_threads_a_billion", no_setup,
       "{arbor} smooth --scenario {dir}/w.scn --quiet --out {dir}/out --threads 1000000000", 2,
       R"(--threads: must lie in \[1, 1024\])"},
      // A6: relocalize's clutter had no cap; 1e9 spurious measurements a scan hung and exhausted memory.
      {"A6", "relocalize_clutter_a_billion", no_setup, "{arbor} relocalize --landmarks 50 --trials 2 --clutter 1e9", 2,
       R"(--clutter: must lie in \[0, 500\])"},
      // B8: a negative standard deviation for the known map ran without a word.
      {"B8", "relocalize_negative_map_sigma", no_setup, "{arbor} relocalize --landmarks 50 --trials 1 --map-sigma -1", 2,
       R"(--map-sigma: must lie in \[0, 1000\])"},
      // C6: relocalize's world had no memory check, and the out-of-memory hint named options it does not have.
      {"C6", "relocalize_two_billion_landmarks", no_setup, "{arbor} relocalize --landmarks 2000000000 --trials 1", 2,
       "field '--landmarks': 2000000000 landmarks need at least"},
      // B1: steering that makes the axle-centre speed v_e / (1 - tan(steering) H / L) divide by zero gave NaN
      // trajectories with exit 0 (here L = tan(1), H = 1); the ute beyond its lock made a 20 m jump.
      {"B1", "ackermann_steering_at_the_pole", file("ack.scn", ackermann_scenario("1.5574077246549023 1 3.78 0.5", "1.0")),
       "{arbor} run --scenario {dir}/ack.scn --quiet --out {dir}/out --assoc known --particles 5", 2,
       "ack.scn:9: field 'u2': steering 1 rad is outside the vehicle's range"},
      {"B1", "ackermann_steering_beyond_the_lock", file("ack.scn", ackermann_scenario("2.83 0.76 3.78 0.5", "1.3086")),
       "{arbor} run --scenario {dir}/ack.scn --quiet --out {dir}/out --assoc known --particles 5", 2,
       "ack.scn:9: field 'u2': steering 1.3086 rad is outside the vehicle's range"},
      {"B1", "ackermann_steering_inside_the_range", file("ack.scn", ackermann_scenario("2.83 0.76 3.78 0.5", "0.5")),
       "{arbor} run --scenario {dir}/ack.scn --quiet --out {dir}/out --assoc known --particles 5", 0, ""},
      // B2: only the first header column was checked, so a map with x and y swapped was read as it stood.
      {"B2", "prior_map_columns_swapped", file("m.csv", "id,y,x,cov_xx,cov_xy,cov_yy,log_odds,signature,truth_label\n"
                                                      "0,2,1,0.1,0,0.1,8,,0\n"),
       kReviewRun + "--prior-map {dir}/m.csv", 2, "m.csv:1: field 'header': expected the map.csv header"},
      // B3, C5: a signature beyond float range became inf, a variance of 1e300 was taken, and one of 1e-300 was
      // reported as an indefinite covariance.
      {"B3", "prior_map_signature_1e300", file("m.csv", kMapHeader + "0,1,2,0.1,0,0.1,8,1e300,0\n"),
       kReviewRun + "--prior-map {dir}/m.csv", 2, "m.csv:2: field 'signature': 1e\\+300 is outside"},
      {"B3", "prior_map_variance_1e300", file("m.csv", kMapHeader + "0,1,2,1e300,0,0.1,8,,0\n"),
       kReviewRun + "--prior-map {dir}/m.csv", 2, "m.csv:2: field 'cov_xx': 1e\\+300 is outside"},
      {"C5", "prior_map_variance_1e_minus_300", file("m.csv", kMapHeader + "0,1,2,1e-300,0,1e-300,8,,0\n"),
       kReviewRun + "--prior-map {dir}/m.csv", 2, "m.csv:2: field 'cov_xx': 1e-300 is outside"},
      // C2: the trajectory `smooth --associations` starts from (the best particle's, with its map) reached Ceres
      // as inf, or was taken when empty.
      {"C2", "trajectory_at_1e300", run_then_edit("trajectory_best.tum", R"(^([^ \n]+) [^ \n]+)", "$1 1e300"), kSmoothRun1, 2,
       "trajectory_best.tum:1: field 'x': 1e\\+300 is outside"},
      {"C2", "trajectory_empty", run_then_edit("trajectory_best.tum", R"([\s\S]*)", ""), kSmoothRun1, 2,
       "trajectory_best.tum: no poses"},
      // B4, B5: a landmark id past 32 bits was truncated into the smoothed map, and a measurement decided twice
      // took the last row.
      {"B4", "associations_id_past_32_bits", run_then_edit("associations.csv", R"(^(\d+),(\d+),-?\d+$)", "$1,$2,4294967296"),
       kSmoothRun1, 2, "associations.csv:2: field 'landmark': landmark id 4294967296 is outside"},
      {"B4", "associations_id_2_to_the_31", run_then_edit("associations.csv", R"(^(\d+),(\d+),-?\d+$)", "$1,$2,2147483648"),
       kSmoothRun1, 2, "associations.csv:2: field 'landmark'"},
      {"B5", "associations_measurement_decided_twice",
       run_then_edit("associations.csv", R"(^(\d+,\d+),-?\d+\n)", "$&$1,7\n"), kSmoothRun1, 2,
       R"(associations.csv:3: field 'measurement': step \d+ measurement 0 already decided at line 2)"},
      // C3: an iSAM landmark id past the readers' range was blamed on the converted scenario, and `smooth --isam`
      // wrote it into a map.csv that --prior-map refuses.
      {"C3", "convert_isam_landmark_id_2e9",
       dataset_edit("victoria_park", "isam_gtsam/victoria_park.txt", R"(^(LANDMARK \d+) \d+ )", "$1 2000000000 "),
       "{arbor} convert --from isam --input {dir}/victoria_park/isam_gtsam/victoria_park.txt --out {dir}/out/i.scn", 2,
       "victoria_park.txt" + field_re + "l': landmark id 2000000000 is outside"},
      {"C3", "smooth_isam_landmark_id_2e9",
       dataset_edit("victoria_park", "isam_gtsam/victoria_park.txt", R"(^(LANDMARK \d+) \d+ )", "$1 2000000000 "),
       "{arbor} smooth --isam {dir}/victoria_park/isam_gtsam/victoria_park.txt --out {dir}/out", 2,
       "victoria_park.txt" + field_re + "l'"},
      // C4: a UTF-8 byte-order mark made every reader report a different, wrong problem; it is skipped.
      {"C4", "scenario_with_a_byte_order_mark", with_byte_order_mark("w.scn"), kReviewRun, 0, ""},
      {"C4", "prior_map_with_a_byte_order_mark",
       [](const fs::path& dir) { write_text(dir / "m.csv", kByteOrderMark + kMapHeader + "0,1,2,0.1,0,0.1,8,,0\n"); },
       kReviewRun + "--prior-map {dir}/m.csv", 0, ""},
      // B7: the problem generator wrote NaN and inf problems, and took a negative standard deviation.
      {"B7", "generate_density_zero", no_setup,
       "{arbor} associate --generate --landmarks 5 --observations 2 --density 0 --out {dir}/p.txt", 2,
       R"(--density: must lie in \[1e-06, 1e\+06\] \(got 0\))"},
      {"B7", "generate_bearing_sigma_1e300", no_setup,
       "{arbor} associate --generate --landmarks 5 --observations 2 --bearing-sigma 1e300 --out {dir}/p.txt", 2,
       "--bearing-sigma: must lie in"},
      {"B7", "generate_pose_sigma_negative", no_setup,
       "{arbor} associate --generate --landmarks 5 --observations 2 --pose-sigma -1 0 0 --out {dir}/p.txt", 2,
       "--pose-sigma: must lie in"},
      // B9: a GPS track too short for a start heading set it to 0, an empty one put the start at the origin,
      // and header-only laser files made a scenario of 0 scans, each with exit 0.
      converted_dataset_edit("B9", "car_park_gps_one_fix", "acfr_car_park", "csv/gps.csv",
                             R"(^(time_s[^\n]*\n[^\n]*\n)[\s\S]*)", "$1", "gps.csv: too few fixes for a start heading"),
      converted_dataset_edit("B9", "car_park_gps_header_only", "acfr_car_park", "csv/gps.csv",
                             R"(^(time_s[^\n]*\n)[\s\S]*)", "$1", "gps.csv: no GPS fix at the start"),
      {"B9", "car_park_laser_header_only",
       [](const fs::path& dir) {
         fs::copy(kShippedData + "acfr_car_park", dir / "acfr_car_park", fs::copy_options::recursive);
         for (const char* name : {"laser_ranges.csv", "laser_intensity.csv"}) {
           const fs::path path = dir / "acfr_car_park/csv" / name;
           const std::string text = testing::read_file(path.string());  // too long for std::regex's recursion
           write_text(path, text.substr(0, text.find('\n') + 1));
         }
       },
       "{arbor} convert --from acfr-car-park --input {dir}/acfr_car_park --out {dir}/out/c.scn", 2,
       "laser_ranges.csv: no laser scans"},
      {"B9", "car_park_estimate_noise_from_nothing",
       dataset_edit("acfr_car_park", "csv/gps.csv", R"(^(time_s[^\n]*\n(?:[^\n]*\n){7})[\s\S]*)", "$1"),
       "{arbor} convert --from acfr-car-park --input {dir}/acfr_car_park --out {dir}/out/c.scn --estimate-noise", 2,
       "field '--estimate-noise': .* gives nothing to estimate the measurement noise from"},
  };
}

class HostileReview : public ::testing::TestWithParam<HostileCase> {};

TEST_P(HostileReview, ExitsCleanlyAndSaysWhere) { expect_exits_cleanly(GetParam()); }

INSTANTIATE_TEST_SUITE_P(Findings, HostileReview, ::testing::ValuesIn(review_cases()),
                         [](const ::testing::TestParamInfo<HostileCase>& info) {
                           return info.param.klass + "_" + info.param.name;
                         });

}  // namespace
}  // namespace arbor
