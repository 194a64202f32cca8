// Victoria Park loader: reads and checks the three raw files, converts the tree bearings to the vehicle
// frame and merges controls and scans in time order.
#include "experiments/loaders/victoria_park.h"

#include <algorithm>

#include <fmt/core.h>

#include "core/io/field_limits.h"
#include "core/io/text_reader.h"
#include "experiments/loaders/loader_util.h"
#include "experiments/loaders/step_merger.h"

namespace arbor {
namespace {

// Rows of one scan share a time stamp; each row is (t [s, relative], range [m], bearing [rad, laser frame
// 0..pi, 0 = right], diameter [m]).
std::vector<TimedScan> read_trees(const std::string& path, LoadReport* report) {
  TextReader in(path);
  TimeOrder order(/*strict=*/false);
  std::vector<TimedScan> scans;
  while (in.next()) {
    in.expect_fields(4, 4, "tree detection");
    const std::int64_t t = seconds_to_ms(time_field(in, 0, "time")) + kVictoriaParkOriginMs;
    const bool same_scan = order.check(in, t, "time");
    Measurement m;
    m.range_m = in.number(1, "range");
    if (m.range_m <= 0.0 || m.range_m > 81.91) in.fail("range", fmt::format("range {} m outside the laser's (0, 81.91]", m.range_m));
    const double bearing_laser = in.number(2, "bearing");
    if (bearing_laser < 0.0 || bearing_laser > kPi)
      in.fail("bearing", fmt::format("bearing {} rad outside the laser's [0, pi]", bearing_laser));
    // Laser frame: 0 = vehicle's right, pi/2 = ahead; the vehicle frame has 0 = ahead, counter-clockwise.
    m.bearing_rad = wrap_angle(bearing_laser - kPi / 2.0);
    const double diameter = non_negative_within(in, 3, "diameter", scenario_limits::kMaxSignature);
    m.signature = static_cast<float>(diameter);
    if (!same_scan) scans.push_back({t, {}});
    scans.back().measurements.push_back(m);
  }
  // An empty (or all-comment) file converted to a scenario of odometry alone, exit 0.
  if (scans.empty()) throw InputError(path, in.line_number(), "", "no tree detections");
  report->add("tree detections", 0);
  for (const auto& s : scans) report->add("tree detections", static_cast<std::int64_t>(s.measurements.size()));
  return scans;
}

}  // namespace

Scenario load_victoria_park(const std::string& dir, LoadReport* report, const VictoriaParkTuning& tuning) {
  const std::vector<ControlSample> controls = read_ackermann_dead_reckoning(join_path(dir, VictoriaParkFiles::kDeadReckoning), {"time_ms", true}, "speed_mps");
  std::vector<TimedScan> scans = read_trees(join_path(dir, VictoriaParkFiles::kTrees), report);
  Scenario s;
  s.truth_track = read_position_track(join_path(dir, VictoriaParkFiles::kGps), {"time_ms", true}, "Lo_m", "La_m", kVictoriaParkOriginMs);

  s.metadata["source"] = "victoria-park";
  s.metadata["citation"] = "Guivant_Nebot_IEEE-TRA_2001";
  s.metadata["time_base"] = "seconds_since_gps_time_20967_ms";
  s.metadata["truth_track"] = "gps_aa3_gpsx_Lo_La_m";
  s.metadata["signature"] = "trunk_diameter_m";

  s.motion.kind = MotionModelKind::kAckermann;
  s.motion.vehicle = AckermannVehicle{2.83, 0.76, 3.78, 0.50};  // info.txt: L, H, L + a, b
  s.motion.ackermann.q_v = tuning.q_v_m2ps;
  s.motion.ackermann.q_steer = tuning.q_steer_rad2s;

  s.sensor.max_range_m = tuning.max_range_m;
  s.sensor.min_range_m = 0.0;
  s.sensor.fov_rad = kPi;  // SICK LMS, 180 degrees centred on the heading
  s.sensor.sigma_range_m = tuning.sigma_range_m;
  s.sensor.sigma_bearing_rad = tuning.sigma_bearing_rad;

  // The state is the laser's pose. Start where the GPS track starts, heading 35.5 degrees in the Lo/La frame:
  // a convention used to overlay results on GPS (not ground truth); evaluation aligns in SE(2) anyway.
  s.initial_pose = {-67.6493, -41.7142, 35.5 * kPi / 180.0};
  s.initial_sigma = Vec3::Zero();

  // Detections beyond the sensor model's range are dropped (the scan itself is kept): the filter considers
  // only landmarks within range as association candidates, so a far tree would start a new landmark at every
  // sighting.
  for (auto& scan : scans) {
    const auto far = std::remove_if(scan.measurements.begin(), scan.measurements.end(),
                                    [&](const Measurement& m) { return m.range_m > tuning.max_range_m; });
    report->add("dropped: detection beyond max range", static_cast<std::int64_t>(scan.measurements.end() - far));
    scan.measurements.erase(far, scan.measurements.end());
  }

  StepMergeOptions merge;
  merge.start_ms = std::min(controls.front().time_ms, scans.empty() ? INT64_MAX : scans.front().time_ms);
  merge.origin_ms = static_cast<double>(kVictoriaParkOriginMs);
  merge.before_first = {merge.start_ms, 0.0, controls.front().u2};  // standing still until the first reading
  merge.controls_path = join_path(dir, VictoriaParkFiles::kDeadReckoning);
  s.start_time_s = (merge.start_ms - kVictoriaParkOriginMs) / 1000.0;
  s.steps = merge_controls_and_scans(controls, scans, merge);

  report->add("dead-reckoning samples", static_cast<std::int64_t>(controls.size()));
  report->add("scans", static_cast<std::int64_t>(scans.size()));
  report->add("gps fixes", static_cast<std::int64_t>(s.truth_track.size()));
  report->add("steps", static_cast<std::int64_t>(s.steps.size()));
  return s;
}

}  // namespace arbor
