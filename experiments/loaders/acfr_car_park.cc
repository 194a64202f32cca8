// ACFR Car Park loader: CSV readers, beacon extraction from the raw laser, and the beacon-fitted poses used to
// estimate the noise models.
#include "experiments/loaders/acfr_car_park.h"

#include <algorithm>
#include <set>

#include <fmt/core.h>

#include "core/io/field_limits.h"
#include "core/io/text_reader.h"
#include "core/metrics/run_statistics.h"
#include "core/metrics/trajectory_metrics.h"
#include "core/models/range_bearing_model.h"
#include "experiments/loaders/loader_util.h"
#include "experiments/loaders/step_merger.h"

namespace arbor {
namespace {

constexpr int kBeams = 361;
constexpr double kBeamStepRad = 0.5 * kPi / 180.0;
constexpr double kMotionWindowS = 2.0;

struct LaserScan {
  std::int64_t time_ms;
  std::vector<double> values;
};

std::vector<LaserScan> read_laser(const std::string& path, char prefix) {
  TextReader in(path, ",");
  if (!in.next()) throw InputError(path, 0, "header", "empty file (expected a header time_s,...)");
  in.expect_fields(kBeams + 1, kBeams + 1, "header");
  if (in.field(0) != "time_s") in.fail("time_s", "first header column must be 'time_s'");
  for (int k = 0; k < kBeams; ++k)
    if (in.field(k + 1) != fmt::format("{}{}", prefix, k)) in.fail(fmt::format("{}{}", prefix, k), "unexpected header column");
  TimeOrder order(/*strict=*/true);
  std::vector<LaserScan> scans;
  std::vector<std::string> names(kBeams);
  for (int k = 0; k < kBeams; ++k) names[k] = fmt::format("{}{}", prefix, k);
  while (in.next()) {
    in.expect_fields(kBeams + 1, kBeams + 1, "laser");
    LaserScan s{seconds_to_ms(time_field(in, 0, "time_s")), std::vector<double>(kBeams)};
    order.check(in, s.time_ms, "time_s");
    for (int k = 0; k < kBeams; ++k) {
      s.values[k] = non_negative_within(in, k + 1, names[k], scenario_limits::kMaxRange);
    }
    scans.push_back(std::move(s));
  }
  return scans;
}

std::vector<TruthLandmark> read_beacons(const std::string& path) {
  TextReader in(path, ",");
  expect_csv_header(in, {"beacon_row", "x_east_m", "y_north_m"});
  std::vector<TruthLandmark> beacons;
  std::set<std::int64_t> ids;
  while (in.next()) {
    in.expect_fields(3, 3, "beacon");
    const std::int64_t id = in.integer(0, "beacon_row");
    if (id < 0 || id > INT32_MAX || !ids.insert(id).second) in.fail("beacon_row", fmt::format("bad or repeated beacon id {}", id));
    beacons.push_back({static_cast<std::int32_t>(id), {coordinate_field(in, 1, "x_east_m"), coordinate_field(in, 2, "y_north_m")}});
  }
  if (beacons.empty()) throw InputError(path, 0, "", "no beacons");
  return beacons;
}

// Position on a GPS track at time t (linear), and the heading of the track over +-half_window_s.
std::optional<Vec2> gps_at(const std::vector<TimedPosition>& track, double t) {
  if (track.empty() || t < track.front().time_s || t > track.back().time_s) return std::nullopt;
  const auto hi = std::lower_bound(track.begin(), track.end(), t, [](const TimedPosition& p, double v) { return p.time_s < v; });
  if (hi == track.begin()) return hi->position;
  const auto lo = hi - 1;
  const double f = (t - lo->time_s) / (hi->time_s - lo->time_s);
  return Vec2(lo->position + f * (hi->position - lo->position));
}
std::optional<double> gps_heading(const std::vector<TimedPosition>& track, double t, double half_window_s = 0.5) {
  const auto a = gps_at(track, t - half_window_s), b = gps_at(track, t + half_window_s);
  if (!a || !b || (*b - *a).norm() < 0.3) return std::nullopt;  // too slow for the track to give a heading
  return std::atan2(b->y() - a->y(), b->x() - a->x());
}

// The laser sits ahead of the rear axle, so in a turn it moves sideways: its track direction exceeds the
// vehicle's heading by beta. From the Ackermann model the laser's body-frame velocity is (v_c - k b, k a) with
// k = v_c tan(alpha) / L, hence beta = atan2(a tan(alpha) / L, 1 - b tan(alpha) / L).
double heading_from_track(double track_direction, double steering, const AckermannVehicle& car) {
  const double t = std::tan(steering) / car.wheelbase_m;
  return wrap_angle(track_direction - std::atan2(car.laser_forward_m * t, 1.0 - car.laser_left_m * t));
}

struct FittedScan {
  std::size_t step;
  Pose2 pose;
  Vec2 gps_in_vehicle;  // GPS position in the fitted laser frame (minus the lever arm's sign)
  std::vector<std::int32_t> ids;  // per measurement, or kTruthUnknown
};

// One pass: guess the laser pose from GPS + lever arm, associate within gate, fit where >= 3 beacons.
std::vector<FittedScan> fit_scans(const Scenario& s, const Vec2& lever, double gate_m) {
  std::vector<FittedScan> fitted;
  for (std::size_t i = 0; i < s.steps.size(); ++i) {
    const ScenarioStep& step = s.steps[i];
    if (step.measurements.size() < 3) continue;
    const auto g = gps_at(s.truth_track, step.time_s);
    const auto h = gps_heading(s.truth_track, step.time_s);
    if (!g || !h) continue;
    Pose2 guess{g->x(), g->y(), heading_from_track(*h, step.control[1], s.motion.vehicle)};
    guess = guess.compose({lever.x(), lever.y(), 0.0});
    for (int pass = 0; pass < 2; ++pass) {
      std::vector<Vec2> p, q;
      std::vector<std::int32_t> ids(step.measurements.size(), kTruthUnknown);
      std::set<std::int32_t> used;
      for (std::size_t k = 0; k < step.measurements.size(); ++k) {
        const Vec2 world = range_bearing_inverse(guess, step.measurements[k].z());
        const TruthLandmark* best = nullptr;
        double best_d = pass == 0 ? gate_m : 0.5;
        for (const auto& l : s.truth_landmarks) {
          const double d = (l.position - world).norm();
          if (d < best_d && !used.count(l.id)) {
            best = &l;
            best_d = d;
          }
        }
        if (!best) continue;
        used.insert(best->id);
        ids[k] = best->id;
        p.push_back(range_bearing_inverse(Pose2{}, step.measurements[k].z()));
        q.push_back(best->position);
      }
      if (p.size() < 3) break;
      guess = align_se2(p, q);  // the laser pose taking scan points p onto world points q
      if (pass == 1) fitted.push_back({i, guess, guess.between({g->x(), g->y(), 0.0}).position(), ids});
    }
  }
  return fitted;
}

}  // namespace

std::vector<Measurement> extract_beacons(const std::vector<double>& r, const std::vector<double>& intensity,
                                         const BeaconExtraction& o) {
  std::vector<Measurement> out;
  const int n = static_cast<int>(std::min(r.size(), intensity.size()));
  const auto reflective = [&](int k) { return intensity[k] > 0.0 && r[k] > o.min_range_m && r[k] < o.max_range_m; };
  for (int k = 0; k < n;) {
    if (!reflective(k)) {
      ++k;
      continue;
    }
    int last = k;
    double sum = r[k];
    while (last + 1 < n && reflective(last + 1) && std::abs(r[last + 1] - r[last]) < o.max_range_jump_m) sum += r[++last];
    Measurement m;
    m.range_m = sum / (last - k + 1) + o.pole_radius_m;
    // Beam k looks at k * 0.5 degrees from the vehicle's right; the vehicle frame has 0 = ahead.
    m.bearing_rad = wrap_angle(0.5 * (k + last) * kBeamStepRad - kPi / 2.0);
    out.push_back(m);
    k = last + 1;
  }
  return out;
}

Scenario load_acfr_car_park(const std::string& dir, LoadReport* report, const BeaconExtraction& extraction) {
  const auto controls = read_ackermann_dead_reckoning(join_path(dir, "csv/dead_reckoning.csv"), {"time_s", false}, "velocity_mps");
  const std::string ranges_path = join_path(dir, "csv/laser_ranges.csv");
  const std::string intensity_path = join_path(dir, "csv/laser_intensity.csv");
  const auto ranges = read_laser(ranges_path, 'r');
  const auto intensity = read_laser(intensity_path, 'i');
  if (ranges.size() != intensity.size())
    throw InputError(intensity_path, 0, "", fmt::format("{} intensity scans but {} range scans in {}", intensity.size(), ranges.size(), ranges_path));
  // Header-only laser files converted to a scenario of 0 scans (hostile B9); Victoria Park refuses the same.
  if (ranges.empty()) throw InputError(ranges_path, 0, "", "no laser scans");
  std::vector<TimedScan> scans;
  std::int64_t detections = 0;
  for (std::size_t k = 0; k < ranges.size(); ++k) {
    if (ranges[k].time_ms != intensity[k].time_ms)
      throw InputError(intensity_path, static_cast<int>(k) + 2, "time_s", "time differs from the same row of laser_ranges.csv");
    // Every scan is kept, even without a beacon: it still says which beacons were not seen.
    scans.push_back({ranges[k].time_ms, extract_beacons(ranges[k].values, intensity[k].values, extraction)});
    detections += static_cast<std::int64_t>(scans.back().measurements.size());
  }

  Scenario s;
  const std::string gps_path = join_path(dir, "csv/gps.csv");
  s.truth_track = read_position_track(gps_path, {"time_s", false}, "x_east_m", "y_north_m");
  s.truth_landmarks = read_beacons(join_path(dir, "csv/beacons_groundtruth.csv"));
  s.metadata["source"] = "acfr-car-park";
  s.metadata["citation"] = "Nieto_Nebot_ACFR_car_park";
  s.metadata["time_base"] = "seconds_data_set_mat_clock";
  s.metadata["truth_track"] = "gps_east_north_m";
  s.motion.kind = MotionModelKind::kAckermann;
  s.motion.vehicle = AckermannVehicle{2.83, 0.76, 3.78, 0.50};
  s.motion.ackermann = {CarParkNoiseDefaults::kQvM2ps, CarParkNoiseDefaults::kQsteerRad2s};
  s.sensor.max_range_m = extraction.max_range_m;
  s.sensor.min_range_m = extraction.min_range_m;
  s.sensor.fov_rad = kPi;
  s.sensor.sigma_range_m = CarParkNoiseDefaults::kSigmaRangeM;
  s.sensor.sigma_bearing_rad = CarParkNoiseDefaults::kSigmaBearingRad;

  StepMergeOptions merge;
  merge.start_ms = std::min(controls.front().time_ms, scans.empty() ? INT64_MAX : scans.front().time_ms);
  merge.before_first = {merge.start_ms, 0.0, controls.front().u2};
  merge.controls_path = join_path(dir, "csv/dead_reckoning.csv");
  s.start_time_s = merge.start_ms / 1000.0;
  s.steps = merge_controls_and_scans(controls, scans, merge);

  // Initial laser pose from GPS: the track's position and heading, moved by the lever arm that the beacon
  // fits measure (the antenna's place on the ute is not documented). A convention for overlaying results on
  // the surveyed frame, not ground truth.
  // A track too short for either used to start the run silently at the origin or heading 0 (hostile B9).
  const double t0 = s.truth_track.empty() ? s.start_time_s : std::max(s.start_time_s, s.truth_track.front().time_s);
  const std::optional<Vec2> p0 = gps_at(s.truth_track, t0);
  if (!p0) throw InputError(gps_path, 0, "", fmt::format("no GPS fix at the start (t = {} s): the start pose is taken from the track", t0));
  const std::optional<double> h0 = gps_heading(s.truth_track, t0 + 0.5);
  if (!h0)
    throw InputError(gps_path, 0, "", fmt::format("too few fixes for a start heading: the track must cover t = {} to {} s "
                                                  "and move at least 0.3 m in it", t0, t0 + 1.0));
  s.initial_pose = {p0->x(), p0->y(), heading_from_track(*h0, controls.front().u2, s.motion.vehicle)};
  const CarParkNoiseEstimate est = estimate_car_park_noise(s);
  s.initial_pose = s.initial_pose.compose({est.gps_to_laser_m.x(), est.gps_to_laser_m.y(), 0.0});
  s.initial_sigma = Vec3::Zero();

  report->add("dead-reckoning samples", static_cast<std::int64_t>(controls.size()));
  report->add("scans", static_cast<std::int64_t>(scans.size()));
  report->add("beacon detections", detections);
  report->add("gps fixes", static_cast<std::int64_t>(s.truth_track.size()));
  report->add("steps", static_cast<std::int64_t>(s.steps.size()));
  report->notes["gps_to_laser_m"] = fmt::format("({:.2f}, {:.2f}) from {} beacon-fitted scans", est.gps_to_laser_m.x(),
                                                est.gps_to_laser_m.y(), est.fitted_scans);
  return s;
}

CarParkNoiseEstimate estimate_car_park_noise(const Scenario& s) {
  CarParkNoiseEstimate out;
  // Pass 1 without a lever arm and a wide gate; the median GPS offset in the fitted laser frames is the lever arm.
  std::vector<FittedScan> fitted = fit_scans(s, Vec2::Zero(), 3.0);
  if (fitted.empty()) return out;
  std::vector<double> lx, ly;
  for (const auto& f : fitted) {
    lx.push_back(-f.gps_in_vehicle.x());
    ly.push_back(-f.gps_in_vehicle.y());
  }
  out.gps_to_laser_m = {median(lx), median(ly)};
  fitted = fit_scans(s, out.gps_to_laser_m, 1.5);
  out.fitted_scans = static_cast<std::int64_t>(fitted.size());
  Scenario truth = s;
  for (auto& step : truth.steps) step.truth_pose.reset();
  std::int64_t residuals = 0;
  for (const auto& f : fitted) {
    ScenarioStep& step = truth.steps[f.step];
    step.truth_pose = f.pose;
    for (std::size_t k = 0; k < step.measurements.size(); ++k) {
      step.measurements[k].truth_id = f.ids[k];
      if (f.ids[k] != kTruthUnknown) residuals += 2;
    }
  }
  const double n = static_cast<double>(residuals), p = 3.0 * static_cast<double>(fitted.size());
  out.measurement = estimate_measurement_noise(truth, n > p ? std::sqrt(n / (n - p)) : 1.0);
  // Too few scans see three beacons for motion windows, so the motion noise uses the GPS track instead: the
  // laser pose at every step from the interpolated GPS position plus the lever arm, heading from the track.
  Scenario gps_truth = s;
  for (auto& step : gps_truth.steps) {
    step.truth_pose.reset();
    const auto g = gps_at(s.truth_track, step.time_s);
    const auto h = gps_heading(s.truth_track, step.time_s);
    if (g && h)
      step.truth_pose = Pose2{g->x(), g->y(), heading_from_track(*h, step.control[1], s.motion.vehicle)}.compose({out.gps_to_laser_m.x(), out.gps_to_laser_m.y(), 0.0});
  }
  out.motion = estimate_motion_noise(gps_truth, kMotionWindowS, 0.5);
  return out;
}

void apply_noise_estimate(const CarParkNoiseEstimate& e, Scenario* scenario) {
  if (e.measurement.count > 0) {
    scenario->sensor.sigma_range_m = e.measurement.sigma_range_m;
    scenario->sensor.sigma_bearing_rad = e.measurement.sigma_bearing_rad;
  }
  if (e.motion.windows > 0) scenario->motion.ackermann = {e.motion.q_1, e.motion.q_2};
}

}  // namespace arbor
