// The scenario format: exact round trip, and malformed files rejected with file, line and field.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

#include "core/io/input_error.h"
#include "core/io/scenario_format.h"
#include "core/io/text_reader.h"

namespace arbor {
namespace {

std::string temp_path(const std::string& name) {
  return (std::filesystem::temp_directory_path() / ("arbor_scenario_test_" + name)).string();
}

Scenario small_scenario() {
  Scenario s;
  s.metadata["source"] = "test";
  s.motion.kind = MotionModelKind::kVelocity;
  s.sensor.sigma_signature = 0.05;
  s.initial_pose = {1.0 / 3.0, -2.0, 0.1};
  s.initial_sigma = {0.1, 0.2, 0.01};
  s.truth_landmarks = {{0, {1.5, 2.5}}, {7, {-3.25, 1e-9}}};
  s.truth_track = {{0.5, {1, 2}}};
  for (int k = 0; k < 3; ++k) {
    ScenarioStep step;
    step.time_s = 0.1 * (k + 1);
    step.control = {1.0 / 7.0, 0.2, 0.1};
    step.truth_pose = Pose2{k * 0.1, 0.0, -kPi + 0.001};
    step.has_scan = k != 1;
    if (k == 2) {
      Measurement m;
      m.range_m = 4.2;
      m.bearing_rad = -3.0;
      m.signature = 0.25f;
      m.truth_id = 7;
      step.measurements.push_back(m);
      m.truth_id = kTruthClutter;
      m.signature = std::numeric_limits<float>::quiet_NaN();
      step.measurements.push_back(m);
      m.truth_id = kTruthUnknown;
      step.measurements.push_back(m);
    }
    s.steps.push_back(step);
  }
  return s;
}

TEST(ScenarioFormat, RoundTripIsExact) {
  const Scenario s = small_scenario();
  const std::string path = temp_path("roundtrip.scn");
  write_scenario(s, path);
  const Scenario r = read_scenario(path);
  EXPECT_EQ(r.metadata, s.metadata);
  EXPECT_EQ(r.motion.kind, s.motion.kind);
  EXPECT_EQ(r.sensor.sigma_signature, s.sensor.sigma_signature);
  EXPECT_EQ(r.initial_pose.x, s.initial_pose.x);
  ASSERT_EQ(r.steps.size(), s.steps.size());
  for (std::size_t k = 0; k < s.steps.size(); ++k) {
    EXPECT_EQ(r.steps[k].time_s, s.steps[k].time_s);
    EXPECT_EQ(r.steps[k].control, s.steps[k].control);
    EXPECT_EQ(r.steps[k].truth_pose->theta, s.steps[k].truth_pose->theta);
    EXPECT_EQ(r.steps[k].has_scan, s.steps[k].has_scan);
    ASSERT_EQ(r.steps[k].measurements.size(), s.steps[k].measurements.size());
    for (std::size_t i = 0; i < s.steps[k].measurements.size(); ++i) {
      EXPECT_EQ(r.steps[k].measurements[i].range_m, s.steps[k].measurements[i].range_m);
      EXPECT_EQ(r.steps[k].measurements[i].truth_id, s.steps[k].measurements[i].truth_id);
    }
  }
  EXPECT_EQ(r.truth_landmarks[1].position, s.truth_landmarks[1].position);
  EXPECT_EQ(r.truth_track.size(), 1u);
}

// Writes a valid file, applies an edit to one line, and checks the error names that line and field.
struct Malformed {
  std::string name;
  std::string find;     // text of the line to replace ("" = append)
  std::string replace;  // its replacement
  int expect_line;      // 0: the error may name any line
  std::string expect_field;
};

class MalformedScenario : public ::testing::TestWithParam<Malformed> {};

TEST_P(MalformedScenario, ErrorNamesFileLineAndField) {
  const Malformed c = GetParam();
  const std::string good = temp_path("good.scn");
  write_scenario(small_scenario(), good);
  std::ifstream in(good);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  int target = -1;
  for (std::size_t i = 0; i < lines.size(); ++i)
    if (lines[i].rfind(c.find, 0) == 0) {
      target = static_cast<int>(i);
      break;
    }
  ASSERT_GE(target, 0) << "no line starts with " << c.find;
  if (c.replace == "<truncate>") lines.resize(target + 1), lines.back() = lines.back().substr(0, lines.back().size() / 2);
  else if (c.replace == "<cut>") lines.resize(target);
  else lines[target] = c.replace;
  const std::string bad = temp_path(c.name + ".scn");
  {
    std::ofstream out(bad);
    for (const auto& l : lines) out << l << "\n";
  }
  try {
    read_scenario(bad);
    FAIL() << "accepted a malformed scenario: " << c.name;
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), bad);
    if (c.expect_line != 0) {
      EXPECT_EQ(e.line(), c.expect_line == -1 ? target + 1 : c.expect_line) << e.what();
    }
    EXPECT_EQ(e.field(), c.expect_field) << e.what();
    EXPECT_NE(std::string(e.what()).find(bad), std::string::npos);
  }
}

INSTANTIATE_TEST_SUITE_P(
    Cases, MalformedScenario,
    ::testing::Values(Malformed{"truncated_line", "step 0.2", "<truncate>", -1, "#4"},
                      Malformed{"non_numeric", "step 0.2", "step 0.2 0.5 abc 0.1", -1, "u2"},
                      Malformed{"nan", "truth 0.1", "truth nan 0 0", -1, "x"},
                      Malformed{"negative_range", "z 4.2 -3 0.25 7", "z -4.2 -3 0.25 7", -1, "range"},
                      Malformed{"unknown_type", "step 0.2", "stop 0.2 1 1 1", -1, "type"},
                      Malformed{"time_backwards", "step 0.3", "step 0.05 1 0.2 0.1", -1, "time"},
                      Malformed{"missing_measurement", "z 4.2 -3 - clutter", "<cut>", 0, "z"},
                      Malformed{"missing_end", "end", "<cut>", 0, "end"},
                      Malformed{"bad_truth_id", "z 4.2 -3 0.25 7", "z 4.2 -3 0.25 seven", -1, "truth"},
                      Malformed{"wrong_header", "arbor-scenario", "arbor-scenery 1", 1, "header"},
                      // A second one-off line used to replace the first silently; a landmark listed twice
                      // was counted twice.
                      Malformed{"second_motion", "landmark 0", "motion velocity 0.1 0.1 0 0 0", -1, "motion"},
                      Malformed{"second_sensor", "landmark 0", "sensor 20 0 3 0.1 0.01 -", -1, "sensor"},
                      Malformed{"second_initial", "landmark 0", "initial 0 0 0 0 0.1 0.1 0.01", -1, "initial"},
                      Malformed{"landmark_twice", "landmark 7", "landmark 0 5 5", -1, "id"},
                      Malformed{"min_above_max_range", "sensor", "sensor 10 20 3 0.1 0.01 -", -1, "min_range"},
                      // Outside the format's physical limits (scenario_limits): a denormal sigma made the
                      // engine abort on a singular covariance; 1e300 overflows when squared.
                      Malformed{"denormal_sigma_range", "sensor", "sensor 20 0 3 1e-310 0.01 -", -1, "sigma_range"},
                      Malformed{"huge_control", "step 0.2", "step 0.2 1e300 0.2 0.1", -1, "u1"},
                      Malformed{"far_landmark", "landmark 7", "landmark 7 1e200 0", -1, "x"},
                      Malformed{"huge_noise_density", "motion", "motion velocity 1e300 0 0 0 0", -1, "q_v"},
                      Malformed{"scan_beyond_the_budget", "scan 3", "scan 20000", -1, "count"}),
    [](const auto& info) { return info.param.name; });

TEST(ScenarioFormat, MissingFileIsAnInputError) {
  EXPECT_THROW(read_scenario("/nonexistent/dir/x.scn"), InputError);
}

// A writer never emits a file its reader rejects: it reads its text back first, and writes nothing when
// that fails (before: `simulate --sigma-range 0` wrote a scenario no command could read).
TEST(ScenarioFormat, TheWriterRefusesWhatTheReaderWouldReject) {
  const std::string dir = temp_path("writer_check");
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  Scenario s = small_scenario();
  s.sensor.sigma_range_m = 0.0;
  try {
    write_scenario(s, dir + "/bad.scn");
    FAIL() << "wrote a scenario with sigma_range 0";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), dir + "/bad.scn");
    EXPECT_EQ(e.field(), "sigma_range") << e.what();
  }
  EXPECT_TRUE(std::filesystem::is_empty(dir));  // neither the file nor its temporary
  s.sensor.sigma_range_m = 0.1;
  write_scenario(s, dir + "/good.scn");
  EXPECT_EQ(read_scenario(dir + "/good.scn").sensor.sigma_range_m, 0.1);
}

TEST(ScenarioFormat, ADirectoryIsNamedAsOne) {
  try {
    read_scenario(std::filesystem::temp_directory_path().string());
    FAIL() << "read a directory as a scenario";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("is a directory"), std::string::npos) << e.what();
  }
}

// A header and an end line are not a scenario: without steps, the check at the first step never ran.
TEST(ScenarioFormat, AFileWithoutMotionSensorOrInitialLinesIsRefused) {
  const std::string path = temp_path("header_only.scn");
  std::ofstream(path) << "arbor-scenario 2\nend 0\n";
  try {
    read_scenario(path);
    FAIL() << "accepted a scenario with no motion, sensor or initial line";
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "motion") << e.what();
  }
}

// docs/scenario_format.md promises every form strtod reads; from_chars alone refused hex floats.
TEST(ScenarioFormat, NumbersReadEveryStrtodFormButNonFiniteOnes) {
  double v = 0.0;
  for (const auto& [text, expected] : std::vector<std::pair<std::string, double>>{
           {"0x1p-2", 0.25}, {"-0X1.8p1", -3.0}, {"+2.5", 2.5}, {"1e-3", 1e-3}, {"-0", 0.0}}) {
    ASSERT_TRUE(parse_finite_double(text, &v)) << text;
    EXPECT_EQ(v, expected) << text;
  }
  for (const std::string text : {"nan", "inf", "-inf", "1e999", "0x", "--1", "+-1", "0x-1", "1.5x", ""})
    EXPECT_FALSE(parse_finite_double(text, &v)) << text;
}

}  // namespace
}  // namespace arbor
