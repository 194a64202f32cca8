// UTIAS MRCLAM loader: barcode table, landmark survey, one robot's odometry, measurements and Vicon poses.
#include "experiments/loaders/utias_mrclam.h"

#include <algorithm>
#include <map>
#include <set>

#include <fmt/core.h>

#include "core/io/field_limits.h"
#include "core/io/text_reader.h"
#include "experiments/loaders/loader_util.h"
#include "experiments/loaders/step_merger.h"

namespace arbor {
namespace {

struct TimedPose {
  std::int64_t time_ms;
  Pose2 pose;
};

std::map<std::int64_t, std::int32_t> read_barcodes(const std::string& path) {
  TextReader in(path);
  std::map<std::int64_t, std::int32_t> subject_of_barcode;
  std::set<std::int64_t> subjects;
  while (in.next()) {
    in.expect_fields(2, 2, "barcode");
    const std::int64_t subject = in.integer(0, "subject");
    const std::int64_t barcode = in.integer(1, "barcode");
    if (subject < 1 || subject > INT32_MAX) in.fail("subject", fmt::format("subject {} must be a positive id", subject));
    if (!subjects.insert(subject).second) in.fail("subject", fmt::format("subject {} listed twice", subject));
    if (!subject_of_barcode.emplace(barcode, static_cast<std::int32_t>(subject)).second)
      in.fail("barcode", fmt::format("barcode {} listed twice", barcode));
  }
  if (subject_of_barcode.empty()) throw InputError(path, 0, "", "no barcodes");
  return subject_of_barcode;
}

std::vector<TruthLandmark> read_landmarks(const std::string& path, const std::set<std::int32_t>& subjects) {
  TextReader in(path);
  std::vector<TruthLandmark> landmarks;
  std::map<std::int64_t, int> line_of;  // a repeated subject was found only when the scenario was written
  while (in.next()) {
    in.expect_fields(5, 5, "landmark ground truth");
    const std::int64_t id = in.integer(0, "subject");
    // Checked as read: a cast first made 4294967302 the subject 6.
    if (id < 1 || id > INT32_MAX || !subjects.count(static_cast<std::int32_t>(id)))
      in.fail("subject", fmt::format("landmark subject {} has no barcode in Barcodes.dat", id));
    if (const auto [it, fresh] = line_of.emplace(id, in.line_number()); !fresh)
      in.fail("subject", fmt::format("landmark subject {} is listed twice (first at line {})", id, it->second));
    landmarks.push_back({static_cast<std::int32_t>(id), {coordinate_field(in, 1, "x"), coordinate_field(in, 2, "y")}});
    non_negative_within(in, 3, "x_std", scenario_limits::kMaxSigma);
    non_negative_within(in, 4, "y_std", scenario_limits::kMaxSigma);
  }
  if (landmarks.empty()) throw InputError(path, 0, "", "no landmarks");
  return landmarks;
}

std::vector<TimedPose> read_groundtruth(const std::string& path) {
  TextReader in(path);
  TimeOrder order(/*strict=*/true);
  std::vector<TimedPose> poses;
  while (in.next()) {
    in.expect_fields(4, 4, "ground-truth pose");
    const std::int64_t t = seconds_to_ms(time_field(in, 0, "time"));
    order.check(in, t, "time");
    poses.push_back({t, {coordinate_field(in, 1, "x"), coordinate_field(in, 2, "y"), wrap_angle(control_field(in, 3, "orientation"))}});
  }
  if (poses.size() < 2) throw InputError(path, in.line_number(), "", "fewer than two ground-truth poses");
  return poses;
}

std::vector<ControlSample> read_odometry(const std::string& path, LoadReport* report) {
  TextReader in(path);
  TimeOrder order(/*strict=*/false);
  std::vector<ControlSample> controls;
  while (in.next()) {
    in.expect_fields(3, 3, "odometry");
    ControlSample c;
    c.time_ms = seconds_to_ms(time_field(in, 0, "time"));
    c.u1 = UtiasNoiseDefaults::kSpeedScale * control_field(in, 1, "v");
    c.u2 = UtiasNoiseDefaults::kTurnRateScale * control_field(in, 2, "omega");
    c.line = in.line_number();
    // Known dirty: robots 2-5 of Dataset 6 log a few commands twice in one millisecond. The later one is
    // the command in force, so it replaces the earlier.
    if (order.check(in, c.time_ms, "time")) {
      report->add("warning: repeated odometry time (later command kept)");
      controls.back() = c;
    } else {
      controls.push_back(c);
    }
  }
  if (controls.empty()) throw InputError(path, 0, "", "no odometry");
  return controls;
}

std::vector<TimedScan> read_measurements(const std::string& path, const std::map<std::int64_t, std::int32_t>& subject_of_barcode,
                                         const std::set<std::int32_t>& landmark_ids, const UtiasOptions& options,
                                         LoadReport* report) {
  TextReader in(path);
  TimeOrder order(/*strict=*/false);
  std::vector<TimedScan> scans;
  std::int64_t last_scan_ms = INT64_MIN;
  while (in.next()) {
    in.expect_fields(4, 4, "measurement");
    const std::int64_t t = seconds_to_ms(time_field(in, 0, "time"));
    order.check(in, t, "time");
    const std::int64_t barcode = in.integer(1, "barcode");
    Measurement m;
    m.range_m = range_field(in, 2, "range");
    if (m.range_m <= 0.0) in.fail("range", fmt::format("range {} m must be positive", m.range_m));
    m.bearing_rad = in.number(3, "bearing");
    if (std::abs(m.bearing_rad) > kPi) in.fail("bearing", fmt::format("bearing {} rad outside [-pi, pi]", m.bearing_rad));
    const auto it = subject_of_barcode.find(barcode);
    if (it == subject_of_barcode.end()) {
      if (options.strict_barcodes)
        in.fail("barcode", fmt::format("barcode {} is not in Barcodes.dat (a false detection?)", barcode));
      report->add("dropped: unknown barcode");
      continue;
    }
    if (!landmark_ids.count(it->second)) {
      report->add("dropped: measurement of another robot");
      continue;
    }
    m.truth_id = it->second;
    if (t != last_scan_ms) scans.push_back({t, {}});
    last_scan_ms = t;
    scans.back().measurements.push_back(m);
  }
  return scans;
}

// Linear interpolation of the Vicon track at t; nullopt outside it or across a gap longer than max_gap_ms.
std::optional<Pose2> interpolate(const std::vector<TimedPose>& track, std::int64_t t, std::int64_t max_gap_ms) {
  if (t < track.front().time_ms || t > track.back().time_ms) return std::nullopt;
  const auto hi = std::lower_bound(track.begin(), track.end(), t, [](const TimedPose& p, std::int64_t v) { return p.time_ms < v; });
  if (hi->time_ms == t) return hi->pose;
  const auto lo = hi - 1;
  if (hi->time_ms - lo->time_ms > max_gap_ms) return std::nullopt;
  const double f = static_cast<double>(t - lo->time_ms) / static_cast<double>(hi->time_ms - lo->time_ms);
  const Pose2& a = lo->pose;
  const Pose2& b = hi->pose;
  return Pose2{a.x + f * (b.x - a.x), a.y + f * (b.y - a.y), wrap_angle(a.theta + f * wrap_angle(b.theta - a.theta))};
}

}  // namespace

Scenario load_utias_mrclam(const std::string& dir, const UtiasOptions& options, LoadReport* report) {
  if (options.robot < 1) throw InputError("", 0, "robot", fmt::format("robot number {} must be positive", options.robot));
  const auto subject_of_barcode = read_barcodes(join_path(dir, "Barcodes.dat"));
  std::set<std::int32_t> subjects;
  for (const auto& [barcode, subject] : subject_of_barcode) subjects.insert(subject);
  Scenario s;
  s.truth_landmarks = read_landmarks(join_path(dir, "Landmark_Groundtruth.dat"), subjects);
  std::set<std::int32_t> landmark_ids;
  for (const auto& l : s.truth_landmarks) landmark_ids.insert(l.id);
  if (!subjects.count(options.robot) || landmark_ids.count(options.robot))
    throw InputError(join_path(dir, "Barcodes.dat"), 0, "robot", fmt::format("subject {} is not a robot of this dataset", options.robot));

  const std::string prefix = fmt::format("Robot{}_", options.robot);
  const auto truth = read_groundtruth(join_path(dir, prefix + "Groundtruth.dat"));
  const auto controls = read_odometry(join_path(dir, prefix + "Odometry.dat"), report);
  const auto all_scans = read_measurements(join_path(dir, prefix + "Measurement.dat"), subject_of_barcode, landmark_ids,
                                           options, report);

  // The run: from the first command (odometry starts seconds after Vicon) until either record ends (robot 1's
  // Vicon track stops 128 s before its odometry).
  const std::int64_t start_ms = std::max(controls.front().time_ms, truth.front().time_ms);
  const std::int64_t end_ms = std::min(controls.back().time_ms, truth.back().time_ms);
  if (end_ms <= start_ms) throw InputError(join_path(dir, prefix + "Odometry.dat"), 0, "time", "odometry and ground truth do not overlap");
  std::vector<TimedScan> scans;
  for (const auto& scan : all_scans) {
    if (scan.time_ms <= start_ms || scan.time_ms > end_ms)
      report->add("dropped: measurement outside the run", static_cast<std::int64_t>(scan.measurements.size()));
    else
      scans.push_back(scan);
  }

  s.metadata["source"] = "utias-mrclam";
  s.metadata["citation"] = "Leung_Halpern_Barfoot_Liu_IJRR_2011";
  s.metadata["robot"] = fmt::format("{}", options.robot);
  s.metadata["time_base"] = fmt::format("seconds_since_unix_time_{:.3f}", start_ms / 1000.0);
  s.motion.kind = MotionModelKind::kVelocity;
  s.motion.velocity = {UtiasNoiseDefaults::kQvM2ps, UtiasNoiseDefaults::kQomegaRad2ps, 0.0, 0.0, 0.0};
  // The camera: 0.9-8.6 m ranges and bearings within about +-0.6 rad in the data.
  s.sensor.max_range_m = 9.0;
  s.sensor.min_range_m = 0.0;
  s.sensor.fov_rad = 1.3;
  s.sensor.sigma_range_m = UtiasNoiseDefaults::kSigmaRangeM;
  s.sensor.sigma_bearing_rad = UtiasNoiseDefaults::kSigmaBearingRad;

  const std::int64_t max_gap_ms = seconds_to_ms(options.max_truth_gap_s);
  s.initial_pose = *interpolate(truth, start_ms, INT64_MAX);
  s.initial_sigma = Vec3::Zero();
  s.start_time_s = 0.0;
  StepMergeOptions merge;
  merge.start_ms = start_ms;
  merge.end_ms = end_ms;
  merge.origin_ms = static_cast<double>(start_ms);
  merge.controls_path = join_path(dir, prefix + "Odometry.dat");
  s.steps = merge_controls_and_scans(controls, scans, merge);
  for (auto& step : s.steps) {
    step.truth_pose = interpolate(truth, seconds_to_ms(step.time_s) + start_ms, max_gap_ms);
    if (!step.truth_pose) report->add("warning: step without ground truth (Vicon gap)");
  }

  std::int64_t kept = 0;
  for (const auto& scan : scans) kept += static_cast<std::int64_t>(scan.measurements.size());
  report->add("landmark measurements", kept);
  report->add("scans", static_cast<std::int64_t>(scans.size()));
  report->add("steps", static_cast<std::int64_t>(s.steps.size()));
  report->add("odometry samples", static_cast<std::int64_t>(controls.size()));
  return s;
}

}  // namespace arbor
