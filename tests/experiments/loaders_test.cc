// The real-data loaders: excerpts of the shipped files (tests/data/), deliberately broken copies of them
// (errors must name file, line and field), the full shipped datasets' counts, and the noise estimators.
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/io/input_error.h"
#include "core/io/scenario_format.h"
#include "core/models/range_bearing_model.h"
#include "experiments/loaders/acfr_car_park.h"
#include "experiments/loaders/isam_victoria_park.h"
#include "experiments/loaders/noise_estimation.h"
#include "experiments/loaders/step_merger.h"
#include "experiments/loaders/utias_mrclam.h"
#include "experiments/loaders/victoria_park.h"

namespace arbor {
namespace {

namespace fs = std::filesystem;

const std::string kSource = ARBOR_SOURCE_DIR;
const std::string kTestData = kSource + "/tests/data/";
const std::string kData = kSource + "/data/";

// A scratch copy of a test-data directory that a test may break.
class BrokenCopy {
 public:
  explicit BrokenCopy(const std::string& source_dir) {
    static int counter = 0;
    dir_ = fs::temp_directory_path() / ("arbor_loaders_test_" + std::to_string(::getpid()) + "_" + std::to_string(counter++));
    fs::remove_all(dir_);
    fs::copy(source_dir, dir_, fs::copy_options::recursive);
  }
  ~BrokenCopy() { fs::remove_all(dir_); }
  std::string dir() const { return dir_.string(); }
  std::string path(const std::string& file) const { return (dir_ / file).string(); }
  // Replaces the 1-based line n of file with text.
  void replace_line(const std::string& file, int n, const std::string& text) {
    std::vector<std::string> lines = read(file);
    lines.at(n - 1) = text;
    write(file, lines);
  }
  std::string line(const std::string& file, int n) { return read(file).at(n - 1); }
  void remove(const std::string& file) { fs::remove(dir_ / file); }

 private:
  std::vector<std::string> read(const std::string& file) {
    std::ifstream in(dir_ / file);
    std::vector<std::string> lines;
    for (std::string l; std::getline(in, l);) lines.push_back(l);
    return lines;
  }
  void write(const std::string& file, const std::vector<std::string>& lines) {
    std::ofstream out(dir_ / file);
    for (const auto& l : lines) out << l << '\n';
  }
  fs::path dir_;
};

// Runs f, expecting an InputError that names the file (by suffix), the line and the field.
template <typename F>
void expect_input_error(F f, const std::string& file_suffix, int line, const std::string& field) {
  try {
    f();
    ADD_FAILURE() << "no InputError thrown; expected one at " << file_suffix << ":" << line << " field " << field;
  } catch (const InputError& e) {
    EXPECT_TRUE(e.file().size() >= file_suffix.size() && e.file().compare(e.file().size() - file_suffix.size(), file_suffix.size(), file_suffix) == 0)
        << e.what();
    EXPECT_EQ(e.line(), line) << e.what();
    EXPECT_EQ(e.field(), field) << e.what();
  }
}

// ---------------------------------------------------------------------------------------------------------
TEST(StepMerger, StepsAtTheUnionOfTimesWithZeroOrderHold) {
  const std::vector<ControlSample> controls = {{100, 1.0, 0.1}, {200, 2.0, 0.2}, {300, 3.0, 0.3}};
  std::vector<TimedScan> scans(3);
  scans[0].time_ms = 150;  // inside (100, 200]: splits it
  scans[1].time_ms = 200;  // on a control time: no split
  scans[2].time_ms = 250;
  scans[0].measurements.resize(2);
  StepMergeOptions o;
  o.start_ms = 100;
  const auto steps = merge_controls_and_scans(controls, scans, o);
  ASSERT_EQ(steps.size(), 4u);  // 150, 200, 250, 300
  const double times[] = {0.15, 0.2, 0.25, 0.3};
  const double u1[] = {1.0, 1.0, 2.0, 2.0};  // the reading in force at each interval's start
  for (int k = 0; k < 4; ++k) {
    EXPECT_DOUBLE_EQ(steps[k].time_s, times[k]);
    EXPECT_DOUBLE_EQ(steps[k].control[0], u1[k]);
    EXPECT_DOUBLE_EQ(steps[k].control[2], 0.05);
  }
  EXPECT_TRUE(steps[0].has_scan && steps[1].has_scan && steps[2].has_scan && !steps[3].has_scan);
  EXPECT_EQ(steps[0].measurements.size(), 2u);
}

TEST(StepMerger, ScanBeforeTheFirstControlUsesTheRestControl) {
  const std::vector<ControlSample> controls = {{100, 1.0, 0.1}};
  std::vector<TimedScan> scans(1);
  scans[0].time_ms = 80;
  StepMergeOptions o;
  o.start_ms = 80;
  o.before_first = {0, 0.0, 0.1};
  const auto steps = merge_controls_and_scans(controls, scans, o);
  ASSERT_EQ(steps.size(), 2u);
  EXPECT_DOUBLE_EQ(steps[0].control[2], 0.0);  // the scan at the start: a step of length zero
  EXPECT_TRUE(steps[0].has_scan);
  EXPECT_DOUBLE_EQ(steps[1].control[0], 0.0);
  EXPECT_DOUBLE_EQ(steps[1].control[2], 0.02);
}

// ---------------------------------------------------------------------------------------------------------
TEST(VictoriaPark, ExcerptLoads) {
  LoadReport report;
  const Scenario s = load_victoria_park(kTestData + "victoria_park", &report);
  // 400 dead-reckoning samples and 43 scan times, one of them on a DR time stamp: 442 distinct times. The
  // first scan (0.852 s) precedes the first DR sample, so it starts the run and every DR time ends a step.
  EXPECT_EQ(s.steps.size(), 442u);
  EXPECT_EQ(report.count("scans"), 43);
  EXPECT_EQ(report.count("tree detections"), 382);
  EXPECT_EQ(report.count("dropped: detection beyond max range"), 37);
  EXPECT_EQ(s.truth_track.size(), 47u);
  EXPECT_EQ(s.motion.kind, MotionModelKind::kAckermann);
  EXPECT_DOUBLE_EQ(s.start_time_s, 0.852);
  EXPECT_DOUBLE_EQ(s.steps.front().time_s, 0.852);
  EXPECT_TRUE(s.steps.front().has_scan);
  // First tree of the first scan: 20.46202 m at 0.88575 rad in the laser frame.
  EXPECT_DOUBLE_EQ(s.steps.front().measurements.front().range_m, 20.46202);
  EXPECT_NEAR(s.steps.front().measurements.front().bearing_rad, 0.88575 - kPi / 2, 1e-12);
  EXPECT_NEAR(s.steps.front().measurements.front().signature, 0.35404, 1e-6);
  double dt_sum = 0.0;
  for (const auto& step : s.steps) {
    dt_sum += step.control[2];
    for (const auto& m : step.measurements) EXPECT_LE(std::abs(m.bearing_rad), kPi / 2);
  }
  EXPECT_NEAR(dt_sum, s.steps.back().time_s - s.start_time_s, 1e-9);
}

TEST(VictoriaPark, FullDatasetHasTheExpectedScansAndSteps) {
  LoadReport report;
  const Scenario s = load_victoria_park(kData + "victoria_park", &report);
  // 7230 distinct scan times in measurements.dat; 61945 DR samples; 285 scans fall on a DR time stamp, one
  // precedes the first DR sample (it starts the run) and 6944 split a DR interval: 61945 + 7230 - 285 = 68890.
  EXPECT_EQ(report.count("scans"), 7230);
  EXPECT_EQ(report.count("dead-reckoning samples"), 61945);
  EXPECT_EQ(report.count("tree detections"), 52974);
  EXPECT_EQ(report.count("dropped: detection beyond max range"), 15576);  // range > 30 m
  EXPECT_EQ(s.steps.size(), 68890u);
  EXPECT_EQ(s.truth_track.size(), 4466u);
  std::size_t with_scan = 0;
  for (const auto& step : s.steps) with_scan += step.has_scan;
  EXPECT_EQ(with_scan, 7230u);
  EXPECT_NEAR(s.steps.back().time_s - s.start_time_s, (1570540 - 21819) / 1000.0, 1e-9);
}

TEST(VictoriaPark, ScenarioRoundTripsThroughTheTextFormat) {
  LoadReport report;
  const Scenario s = load_victoria_park(kTestData + "victoria_park", &report);
  const std::string path = (fs::temp_directory_path() / ("arbor_vp_roundtrip_" + std::to_string(::getpid()) + ".txt")).string();
  write_scenario(s, path);
  const Scenario back = read_scenario(path);
  fs::remove(path);
  ASSERT_EQ(back.steps.size(), s.steps.size());
  for (std::size_t k = 0; k < s.steps.size(); ++k) {
    EXPECT_EQ(back.steps[k].time_s, s.steps[k].time_s);
    EXPECT_EQ(back.steps[k].control, s.steps[k].control);
    EXPECT_EQ(back.steps[k].measurements.size(), s.steps[k].measurements.size());
  }
  EXPECT_EQ(back.truth_track.size(), s.truth_track.size());
}

TEST(VictoriaPark, BrokenCopiesGiveErrorsNamingFileLineAndField) {
  const std::string trees = "leung_extracted/measurements.dat", dr = "csv_from_mat/aa3_dr.csv", gps = "csv_from_mat/aa3_gpsx.csv";
  LoadReport report;
  {  // truncated line: the diameter is missing
    BrokenCopy c(kTestData + "victoria_park");
    c.replace_line(trees, 5, "     0.852   12.74537    1.35263");
    expect_input_error([&] { load_victoria_park(c.dir(), &report); }, trees, 5, "#4");
  }
  {  // non-numeric field
    BrokenCopy c(kTestData + "victoria_park");
    c.replace_line(dr, 10, "22140,fast,-0.0042");
    expect_input_error([&] { load_victoria_park(c.dir(), &report); }, dr, 10, "speed_mps");
  }
  {  // time going backwards in the dead reckoning
    BrokenCopy c(kTestData + "victoria_park");
    c.replace_line(dr, 20, "21000,0,0");
    expect_input_error([&] { load_victoria_park(c.dir(), &report); }, dr, 20, "time_ms");
  }
  {  // reordered tree detections: a later scan's row moved up
    BrokenCopy c(kTestData + "victoria_park");
    const std::string later = c.line(trees, 30);
    c.replace_line(trees, 2, later);
    expect_input_error([&] { load_victoria_park(c.dir(), &report); }, trees, 3, "time");
  }
  {  // a bearing outside the laser's half circle
    BrokenCopy c(kTestData + "victoria_park");
    c.replace_line(trees, 1, "     0.852   20.46202    3.50000    0.35404");
    expect_input_error([&] { load_victoria_park(c.dir(), &report); }, trees, 1, "bearing");
  }
  {  // wrong header
    BrokenCopy c(kTestData + "victoria_park");
    c.replace_line(gps, 1, "time_ms,La_m,Lo_m");
    expect_input_error([&] { load_victoria_park(c.dir(), &report); }, gps, 1, "Lo_m");
  }
  {  // missing file
    BrokenCopy c(kTestData + "victoria_park");
    c.remove(trees);
    expect_input_error([&] { load_victoria_park(c.dir(), &report); }, trees, 0, "");
  }
}

// ---------------------------------------------------------------------------------------------------------
TEST(UtiasMrclam, ExcerptLoadsWithTruthEverywhere) {
  LoadReport report;
  const Scenario s = load_utias_mrclam(kTestData + "utias_mrclam", {}, &report);
  EXPECT_EQ(s.motion.kind, MotionModelKind::kVelocity);
  EXPECT_EQ(s.truth_landmarks.size(), 15u);
  EXPECT_EQ(report.count("dropped: measurement of another robot"), 27);  // barcodes 14, 41: robots 2, 3
  EXPECT_EQ(report.count("dropped: unknown barcode"), 0);
  EXPECT_EQ(report.count("landmark measurements"), 89);
  std::int64_t measurements = 0;
  for (const auto& step : s.steps) {
    ASSERT_TRUE(step.truth_pose.has_value());
    for (const auto& m : step.measurements) {
      EXPECT_GE(m.truth_id, 6);
      EXPECT_LE(m.truth_id, 20);
      ++measurements;
    }
  }
  EXPECT_EQ(measurements, 89);
  // The Vicon pose at the first command, 12.053 s after the track starts.
  EXPECT_NEAR(s.initial_pose.x, s.steps.front().truth_pose->x, 0.05);
}

TEST(UtiasMrclam, UnknownBarcodeIsCountedOrAnErrorWhenStrict) {
  BrokenCopy c(kTestData + "utias_mrclam");
  const std::string file = "Robot1_Measurement.dat";
  c.replace_line(file, 7, "1248444189.828 \t  43 \t  6.600 \t -0.022");  // 43: a known false detection
  LoadReport report;
  load_utias_mrclam(c.dir(), {}, &report);
  EXPECT_EQ(report.count("dropped: unknown barcode"), 1);
  UtiasOptions strict;
  strict.strict_barcodes = true;
  expect_input_error([&] { load_utias_mrclam(c.dir(), strict, &report); }, file, 7, "barcode");
}

TEST(UtiasMrclam, BrokenCopiesGiveErrorsNamingFileLineAndField) {
  LoadReport report;
  {
    BrokenCopy c(kTestData + "utias_mrclam");
    c.replace_line("Robot1_Odometry.dat", 20, "1248444187.300 \t  0.086");
    expect_input_error([&] { load_utias_mrclam(c.dir(), {}, &report); }, "Robot1_Odometry.dat", 20, "#3");
  }
  {
    BrokenCopy c(kTestData + "utias_mrclam");
    c.replace_line("Robot1_Odometry.dat", 30, "1248444100.000 \t  0.086 \t -0.398");
    expect_input_error([&] { load_utias_mrclam(c.dir(), {}, &report); }, "Robot1_Odometry.dat", 30, "time");
  }
  {
    BrokenCopy c(kTestData + "utias_mrclam");
    c.replace_line("Robot1_Groundtruth.dat", 8, "1248444175.180 \t 1.41 \t x \t 2.269");
    expect_input_error([&] { load_utias_mrclam(c.dir(), {}, &report); }, "Robot1_Groundtruth.dat", 8, "y");
  }
  {
    BrokenCopy c(kTestData + "utias_mrclam");
    c.remove("Barcodes.dat");
    expect_input_error([&] { load_utias_mrclam(c.dir(), {}, &report); }, "Barcodes.dat", 0, "");
  }
  {
    BrokenCopy c(kTestData + "utias_mrclam");
    c.replace_line("Barcodes.dat", 6, "  2 \t   5");  // barcode 5 twice
    expect_input_error([&] { load_utias_mrclam(c.dir(), {}, &report); }, "Barcodes.dat", 6, "barcode");
  }
  {  // 2^32 + 6: a cast before the check read it as subject 6
    BrokenCopy c(kTestData + "utias_mrclam");
    c.replace_line("Landmark_Groundtruth.dat", 5, "  4294967302 \t 0.588 \t -4.282 \t 0.00004 \t 0.00027");
    expect_input_error([&] { load_utias_mrclam(c.dir(), {}, &report); }, "Landmark_Groundtruth.dat", 5, "subject");
  }
  {  // a robot the dataset does not have
    UtiasOptions o;
    o.robot = 7;
    expect_input_error([&] { load_utias_mrclam(kTestData + "utias_mrclam", o, &report); }, "Barcodes.dat", 0, "robot");
  }
}

TEST(UtiasMrclam, Robot1DropsOtherRobotsAndFalseDetections) {
  LoadReport report;
  const Scenario s = load_utias_mrclam(kData + "utias_mrclam/MRCLAM_Dataset6", {}, &report);
  // SOURCE.md: robot 1 has 1942 measurements: 1534 of landmarks, 407 of robots, 1 unknown barcode.
  EXPECT_EQ(report.count("dropped: measurement of another robot"), 407);
  EXPECT_EQ(report.count("dropped: unknown barcode"), 1);
  EXPECT_EQ(report.count("landmark measurements") + report.count("dropped: measurement outside the run"), 1534);
  EXPECT_GT(s.steps.size(), 40000u);
}

// ---------------------------------------------------------------------------------------------------------
TEST(NoiseEstimation, RecoversKnownMeasurementNoiseDespiteOutliers) {
  Scenario s;
  s.truth_landmarks = {{1, {5.0, 0.0}}, {2, {0.0, 4.0}}, {3, {-3.0, -3.0}}};
  std::mt19937_64 rng(7);
  std::normal_distribution<double> nr(0.0, 0.1), nb(0.0, 0.02);
  std::uniform_real_distribution<double> junk(-3.0, 3.0);
  for (int k = 0; k < 3000; ++k) {
    ScenarioStep step;
    step.truth_pose = Pose2{0.01 * k, -0.005 * k, 0.001 * k};
    step.has_scan = true;
    for (const auto& l : s.truth_landmarks) {
      const Vec2 z = range_bearing_predict(*step.truth_pose, l.position);
      Measurement m;
      m.range_m = z.x() + nr(rng);
      m.bearing_rad = wrap_angle(z.y() + nb(rng));
      if (k % 50 == 0) m.range_m += std::abs(junk(rng)) + 1.0;  // 2 % gross outliers
      m.truth_id = l.id;
      step.measurements.push_back(m);
    }
    s.steps.push_back(step);
  }
  const MeasurementNoiseEstimate e = estimate_measurement_noise(s);
  EXPECT_EQ(e.count, 9000);
  EXPECT_NEAR(e.sigma_range_m, 0.1, 0.008);
  EXPECT_NEAR(e.sigma_bearing_rad, 0.02, 0.0015);
  EXPECT_NEAR(e.outlier_fraction, 0.02, 0.01);
}

TEST(NoiseEstimation, RecoversKnownVelocityNoiseFromReplayedWindows) {
  // Truth: a unicycle driven by noisy commands; the scenario logs the noise-free commands.
  Scenario s;
  s.motion.kind = MotionModelKind::kVelocity;
  std::mt19937_64 rng(11);
  const double sigma_v = 0.05, sigma_w = 0.1, dt = 0.01;
  std::normal_distribution<double> nv(0.0, sigma_v), nw(0.0, sigma_w);
  Pose2 truth;
  for (int k = 1; k <= 60000; ++k) {
    ScenarioStep step;
    step.time_s = k * dt;
    step.control = {0.3, 0.2 * std::sin(0.01 * k), dt};
    truth = velocity_apply(truth, {step.control[0] + nv(rng), step.control[1] + nw(rng), dt}, nullptr, nullptr);
    step.truth_pose = truth;
    s.steps.push_back(step);
  }
  const MotionNoiseEstimate e = estimate_motion_noise(s, 1.0);
  EXPECT_GT(e.windows, 500);
  // Per-step white noise of variance sigma^2 at step dt is a density of sigma^2 dt.
  EXPECT_NEAR(e.q_1, sigma_v * sigma_v * dt, 0.25 * sigma_v * sigma_v * dt);
  EXPECT_NEAR(e.q_2, sigma_w * sigma_w * dt, 0.25 * sigma_w * sigma_w * dt);
}

// Heavy but real tails (Laplace residuals: standard deviation b sqrt(2), while 1.4826 MAD = 1.028 b): the
// default estimate keeps them, the MAD figure does not; a filter told the MAD would be overconfident.
TEST(NoiseEstimation, TheDefaultSigmaRespectsHeavyTails) {
  Scenario s;
  s.truth_landmarks = {{1, {5.0, 0.0}}};
  std::mt19937_64 rng(5);
  std::exponential_distribution<double> expo(1.0);
  std::bernoulli_distribution sign(0.5);
  const double b_range = 0.05, b_bearing = 0.01;
  const auto laplace = [&](double b) {
    const double magnitude = b * expo(rng);  // drawn before the sign: the operands of * are unsequenced
    return (sign(rng) ? 1.0 : -1.0) * magnitude;
  };
  for (int k = 0; k < 20000; ++k) {
    ScenarioStep step;
    step.truth_pose = Pose2{0.0, 0.0, 0.0};
    step.has_scan = true;
    Measurement m;
    m.range_m = 5.0 + laplace(b_range);
    m.bearing_rad = laplace(b_bearing);
    m.truth_id = 1;
    step.measurements.push_back(m);
    s.steps.push_back(step);
  }
  const MeasurementNoiseEstimate e = estimate_measurement_noise(s);
  EXPECT_NEAR(e.sigma_range_m, b_range * std::sqrt(2.0), 0.05 * b_range * std::sqrt(2.0));
  EXPECT_NEAR(e.sigma_bearing_rad, b_bearing * std::sqrt(2.0), 0.05 * b_bearing * std::sqrt(2.0));
  EXPECT_NEAR(e.mad_sigma_range_m, 1.028 * b_range, 0.05 * b_range);
  EXPECT_GT(e.beyond_3sigma_fraction, 0.01);  // Laplace: 1.4 % beyond 3 standard deviations
}

// ---------------------------------------------------------------------------------------------------------
TEST(AcfrCarPark, ExtractsOnePointPerReflectiveRun) {
  std::vector<double> r(361, 81.9), intensity(361, 0.0);
  for (int k = 100; k <= 102; ++k) {  // a pole at 10 m, beams 100-102 (mean 50.5 degrees from the right)
    r[k] = 10.0;
    intensity[k] = 8192;
  }
  r[200] = 0.9;  // too close: the vehicle itself
  intensity[200] = 8192;
  r[300] = 5.0;  // a single-beam pole next to a far reflective return: two beacons
  intensity[300] = 16384;
  r[301] = 12.0;
  intensity[301] = 16384;
  const auto z = extract_beacons(r, intensity);
  ASSERT_EQ(z.size(), 3u);
  EXPECT_NEAR(z[0].range_m, 10.03, 1e-12);
  EXPECT_NEAR(z[0].bearing_rad, (101 * 0.5 - 90) * kPi / 180, 1e-12);
  EXPECT_NEAR(z[1].range_m, 5.03, 1e-12);
  EXPECT_NEAR(z[2].range_m, 12.03, 1e-12);
}

TEST(AcfrCarPark, ExcerptLoads) {
  LoadReport report;
  const Scenario s = load_acfr_car_park(kTestData + "acfr_car_park", &report);
  EXPECT_EQ(report.count("scans"), 47);
  EXPECT_EQ(report.count("dead-reckoning samples"), 400);
  EXPECT_EQ(s.truth_landmarks.size(), 15u);
  EXPECT_EQ(s.truth_track.size(), 50u);
  EXPECT_EQ(s.motion.kind, MotionModelKind::kAckermann);
  std::size_t scans = 0;
  for (const auto& step : s.steps) scans += step.has_scan;
  EXPECT_EQ(scans, 47u);
}

TEST(AcfrCarPark, BrokenCopiesGiveErrorsNamingFileLineAndField) {
  LoadReport report;
  {
    BrokenCopy c(kTestData + "acfr_car_park");
    c.replace_line("csv/laser_ranges.csv", 3, c.line("csv/laser_ranges.csv", 3) + ",1.0");
    expect_input_error([&] { load_acfr_car_park(c.dir(), &report); }, "csv/laser_ranges.csv", 3, "#363");
  }
  {
    BrokenCopy c(kTestData + "acfr_car_park");
    std::string l = c.line("csv/laser_intensity.csv", 4);
    l.replace(l.find(",0,"), 3, ",x,");
    c.replace_line("csv/laser_intensity.csv", 4, l);
    try {
      load_acfr_car_park(c.dir(), &report);
      ADD_FAILURE() << "no error";
    } catch (const InputError& e) {
      EXPECT_EQ(e.line(), 4);
      EXPECT_EQ(e.field().front(), 'i');  // names the beam column, e.g. "i17"
    }
  }
  {
    BrokenCopy c(kTestData + "acfr_car_park");
    c.replace_line("csv/dead_reckoning.csv", 50, "45.0,1.0,0.1");
    expect_input_error([&] { load_acfr_car_park(c.dir(), &report); }, "csv/dead_reckoning.csv", 50, "time_s");
  }
  {
    BrokenCopy c(kTestData + "acfr_car_park");
    c.remove("csv/gps.csv");
    expect_input_error([&] { load_acfr_car_park(c.dir(), &report); }, "csv/gps.csv", 0, "");
  }
}

TEST(AcfrCarPark, FullDatasetNoiseEstimateIsPlausible) {
  LoadReport report;
  const Scenario s = load_acfr_car_park(kData + "acfr_car_park", &report);
  EXPECT_EQ(report.count("scans"), 586);
  const CarParkNoiseEstimate e = estimate_car_park_noise(s);
  EXPECT_GT(e.fitted_scans, 30);
  // A 6 cm pole seen by a laser with centimetre ranges and 0.5 degree beams: centimetres to decimetres.
  EXPECT_GT(e.measurement.sigma_range_m, 0.005);
  EXPECT_LT(e.measurement.sigma_range_m, 0.3);
  EXPECT_GT(e.measurement.sigma_bearing_rad, 0.001);
  EXPECT_LT(e.measurement.sigma_bearing_rad, 0.05);
}

// ---------------------------------------------------------------------------------------------------------
TEST(IsamVictoriaPark, FullFileHasTheDocumentedCounts) {
  const IsamDataset d = read_isam_dataset(kData + "victoria_park/isam_gtsam/victoria_park.txt");
  EXPECT_EQ(d.pose_ids.size(), 6969u);
  EXPECT_EQ(d.odometry.size(), 6968u);
  EXPECT_EQ(d.observations.size(), 3640u);
  EXPECT_EQ(d.landmark_ids.size(), 151u);
  EXPECT_EQ(d.pose_ids.size() + d.landmark_ids.size(), 7120u);  // GTSAM's test: 7120 variables
  EXPECT_NEAR(d.odometry.front().covariance(0, 0), 1e-4, 1e-18);
  const Scenario s = isam_to_scenario(d);
  EXPECT_EQ(s.steps.size(), 6968u);
  std::size_t observations = 0;
  for (const auto& step : s.steps)
    for (const auto& m : step.measurements) {
      EXPECT_GE(m.truth_id, 0);
      ++observations;
    }
  EXPECT_EQ(observations, 3640u);
}

TEST(IsamVictoriaPark, BrokenCopiesGiveErrorsNamingFileLineAndField) {
  const std::string file = "isam_gtsam/victoria_park.txt";
  {
    BrokenCopy c(kTestData + "victoria_park");
    c.replace_line(file, 3, "ODOMETRY 2 3 0.0265992 -4.82655e-07 -4.12159e-05 0.0001 0 0 4e-06 0");
    expect_input_error([&] { read_isam_dataset(c.path(file)); }, file, 3, "#12");
  }
  {  // the chain broken: odometry from a pose that is not the last one
    BrokenCopy c(kTestData + "victoria_park");
    c.replace_line(file, 3, "ODOMETRY 1 3 0.0265992 -4.82655e-07 -4.12159e-05 0.0001 0 0 4e-06 0 4e-06");
    expect_input_error([&] { read_isam_dataset(c.path(file)); }, file, 3, "i");
  }
  {  // not positive definite
    BrokenCopy c(kTestData + "victoria_park");
    c.replace_line(file, 5, "LANDMARK 4 5 11.5387 -3.2007 0.4 0.5 0.4");
    expect_input_error([&] { read_isam_dataset(c.path(file)); }, file, 5, "c_xx");
  }
  {
    BrokenCopy c(kTestData + "victoria_park");
    c.replace_line(file, 5, "LANDMARK 4 5 11.5387 abc 0.4 0 0.4");
    expect_input_error([&] { read_isam_dataset(c.path(file)); }, file, 5, "y");
  }
  expect_input_error([&] { read_isam_dataset(kTestData + "no_such_file.txt"); }, "no_such_file.txt", 0, "");
}

}  // namespace
}  // namespace arbor
