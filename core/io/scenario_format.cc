// Scenario text format reader and writer. The grammar is documented in docs/scenario_format.md.
#include "core/io/scenario_format.h"

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <system_error>
#include <unordered_map>
#include <utility>

#include <fmt/core.h>

#include "core/io/atomic_file.h"
#include "core/io/text_reader.h"
#include "core/models/ackermann_model.h"

namespace arbor {
namespace {

constexpr std::string_view kHeader = "arbor-scenario";
// Version 2: motion noise as continuous-time densities (core/models/twist_motion.h). Version 1 held
// per-reading sigmas, whose meaning depended on the reading rate; such a file is refused, not reinterpreted.
constexpr int kVersion = 2;

std::string signature_text(float s) { return std::isnan(s) ? "-" : fmt::format("{}", s); }
std::string truth_text(std::int32_t id) {
  if (id == kTruthUnknown) return "-";
  if (id == kTruthClutter) return "clutter";
  return fmt::format("{}", id);
}

namespace lim = scenario_limits;

// The five densities of TwistNoise, fields 2-6 of an odometry or velocity motion line.
TwistNoise read_twist_noise(const TextReader& in) {
  TwistNoise n;
  n.q_v = non_negative_within(in, 2, "q_v", lim::kMaxNoiseDensity);
  n.q_omega = non_negative_within(in, 3, "q_omega", lim::kMaxNoiseDensity);
  n.k_v = non_negative_within(in, 4, "k_v", lim::kMaxNoiseDensity);
  n.k_wv = non_negative_within(in, 5, "k_wv", lim::kMaxNoiseDensity);
  n.k_ww = non_negative_within(in, 6, "k_ww", lim::kMaxNoiseDensity);
  return n;
}

void read_motion(const TextReader& in, MotionModel* motion) {
  const std::string_view kind = in.field(1);
  if (!from_string(kind, &motion->kind))
    in.fail("model", fmt::format("unknown motion model '{}' (odometry, velocity, ackermann)", kind));
  switch (motion->kind) {
    case MotionModelKind::kOdometry:
      in.expect_fields(7, 7, "motion odometry");
      motion->odometry = read_twist_noise(in);
      break;
    case MotionModelKind::kVelocity:
      in.expect_fields(7, 7, "motion velocity");
      motion->velocity = read_twist_noise(in);
      break;
    case MotionModelKind::kAckermann:
      in.expect_fields(8, 8, "motion ackermann");
      motion->ackermann.q_v = non_negative_within(in, 2, "q_v", lim::kMaxNoiseDensity);
      motion->ackermann.q_steer = non_negative_within(in, 3, "q_steer", lim::kMaxNoiseDensity);
      motion->vehicle.wheelbase_m = number_within(in, 4, "wheelbase", 0.0, lim::kMaxRange);
      if (motion->vehicle.wheelbase_m <= 0.0) in.fail("wheelbase", "must be positive");
      motion->vehicle.encoder_offset_m = number_within(in, 5, "encoder_offset", -lim::kMaxRange, lim::kMaxRange);
      motion->vehicle.laser_forward_m = number_within(in, 6, "laser_forward", -lim::kMaxRange, lim::kMaxRange);
      motion->vehicle.laser_left_m = number_within(in, 7, "laser_left", -lim::kMaxRange, lim::kMaxRange);
      break;
  }
}

// An Ackermann control's steering (field u2) within the vehicle's range: the converters' lock limit, and a
// finite axle-centre speed (at 1 - tan(steering) H / L = 0 the model divides by zero and the run was NaN).
void check_steering(const TextReader& in, double steering, const AckermannVehicle& car) {
  if (std::abs(steering) >= lim::kMaxSteering)
    in.fail("u2", fmt::format("steering {} rad is outside the vehicle's range (|steering| < {} rad)", steering,
                              lim::kMaxSteering));
  const double denominator = encoder_to_axle_divisor(std::tan(steering), car);
  if (!(denominator >= lim::kMinSteeringDenominator))
    in.fail("u2", fmt::format("steering {} rad is outside the vehicle's range: 1 - tan(steering) * encoder_offset / "
                              "wheelbase = {:.3g}, below {} (the axle-centre speed divides by it)",
                              steering, denominator, lim::kMinSteeringDenominator));
}

}  // namespace

Scenario read_scenario(const std::string& path) {
  TextReader in(path);
  Scenario s;
  if (!in.next()) throw InputError(path, 0, "header", "empty file (expected 'arbor-scenario 2')");
  if (in.field(0) != kHeader) in.fail("header", "not a scenario file (first line must be 'arbor-scenario 2')");
  in.expect_fields(2, 2, "header");
  const std::int64_t version = in.integer(1, "version");
  if (version == 1)
    in.fail("version", "version 1 scenarios hold per-reading motion noise, which this build no longer reads; "
                       "re-create the file with this build's `arbor simulate` or `arbor convert`");
  if (version != kVersion) in.fail("version", fmt::format("unsupported version (this build reads {})", kVersion));

  // The line of each one-off line (0: not yet seen); a second one would silently replace the first.
  int motion_line = 0, sensor_line = 0, initial_line = 0;
  bool ended = false;
  const auto once = [&](int* seen, std::string_view what) {
    if (*seen > 0) in.fail(what, fmt::format("a second '{}' line (the first is line {})", what, *seen));
    *seen = in.line_number();
  };
  std::unordered_map<std::int32_t, int> landmark_line;  // truth landmark id -> the line that gave it
  int scan_expected = 0;  // measurements still owed by the current scan
  int scan_line = 0;
  double last_time = -INFINITY;
  const auto need_no_pending_scan = [&](std::string_view what) {
    if (scan_expected > 0)
      in.fail("z", fmt::format("scan at line {} announced more measurements than it has; found '{}' instead", scan_line, what));
  };

  while (in.next()) {
    const std::string_view kind = in.field(0);
    if (ended) in.fail("type", "data after the 'end' line");
    if (kind == "z") {
      in.expect_fields(5, 5, "z");
      if (scan_expected == 0) in.fail("z", "measurement outside a scan (a 'scan N' line must announce it)");
      Measurement m;
      m.range_m = number_within(in, 1, "range", -INFINITY, lim::kMaxRange);
      if (m.range_m < 0.0) in.fail("range", fmt::format("negative range {}", m.range_m));
      m.bearing_rad = in.number(2, "bearing");
      if (std::abs(m.bearing_rad) > kPi + 1e-9) in.fail("bearing", fmt::format("bearing {} outside [-pi, pi]", m.bearing_rad));
      m.bearing_rad = wrap_angle(m.bearing_rad);
      if (in.field(3) != "-") m.signature = static_cast<float>(number_within(in, 3, "signature", -lim::kMaxSignature, lim::kMaxSignature));
      const std::string_view truth = in.field(4);
      if (truth == "clutter") {
        m.truth_id = kTruthClutter;
      } else if (truth != "-") {
        const std::int64_t id = in.integer(4, "truth");
        if (id < 0 || id > lim::kMaxLandmarkId)
          in.fail("truth", fmt::format("truth must be a landmark id in [0, {}], 'clutter' or '-'", lim::kMaxLandmarkId));
        m.truth_id = static_cast<std::int32_t>(id);
      }
      s.steps.back().measurements.push_back(m);
      --scan_expected;
      continue;
    }
    need_no_pending_scan(kind);
    if (kind == "step") {
      in.expect_fields(5, 5, "step");
      if (motion_line == 0 || sensor_line == 0 || initial_line == 0)
        in.fail("step", "the 'motion', 'sensor' and 'initial' lines must come before the first step");
      ScenarioStep step;
      step.time_s = time_field(in, 1, "time");
      if (step.time_s < last_time) in.fail("time", fmt::format("time goes backwards ({} after {})", step.time_s, last_time));
      last_time = step.time_s;
      step.control = {control_field(in, 2, "u1"), control_field(in, 3, "u2"), control_field(in, 4, "u3")};
      if (s.motion.kind != MotionModelKind::kOdometry && step.control[2] < 0.0) in.fail("u3", "dt must not be negative");
      if (s.motion.kind == MotionModelKind::kAckermann) check_steering(in, step.control[1], s.motion.vehicle);
      step.source_line = in.line_number();
      s.steps.push_back(std::move(step));
    } else if (kind == "truth") {
      in.expect_fields(4, 4, "truth");
      if (s.steps.empty()) in.fail("truth", "ground-truth pose before the first step");
      s.steps.back().truth_pose = Pose2{coordinate_field(in, 1, "x"), coordinate_field(in, 2, "y"), wrap_angle(coordinate_field(in, 3, "theta"))};
    } else if (kind == "scan") {
      in.expect_fields(2, 2, "scan");
      if (s.steps.empty()) in.fail("scan", "scan before the first step");
      if (s.steps.back().has_scan) in.fail("scan", "a step has at most one scan");
      const std::int64_t n = in.integer(1, "count");
      if (n < 0 || n > lim::kMaxMeasurementsPerScan)
        in.fail("count", fmt::format("measurement count {} is outside [0, {}]", n, lim::kMaxMeasurementsPerScan));
      s.steps.back().has_scan = true;
      s.steps.back().measurements.reserve(n);
      scan_expected = static_cast<int>(n);
      scan_line = in.line_number();
    } else if (kind == "landmark") {
      in.expect_fields(4, 4, "landmark");
      const std::int32_t id = landmark_id_field(in, 1, "id");
      const auto [first, inserted] = landmark_line.emplace(id, in.line_number());
      if (!inserted) in.fail("id", fmt::format("landmark {} is listed twice (first at line {})", id, first->second));
      s.truth_landmarks.push_back({id, {coordinate_field(in, 2, "x"), coordinate_field(in, 3, "y")}});
    } else if (kind == "gps") {
      in.expect_fields(4, 4, "gps");
      const double t = time_field(in, 1, "time");
      if (!s.truth_track.empty() && t < s.truth_track.back().time_s) in.fail("time", "gps time goes backwards");
      s.truth_track.push_back({t, {coordinate_field(in, 2, "x"), coordinate_field(in, 3, "y")}});
    } else if (kind == "motion") {
      in.expect_fields(2, 8, "motion");
      once(&motion_line, "motion");
      read_motion(in, &s.motion);
    } else if (kind == "sensor") {
      in.expect_fields(7, 7, "sensor");
      once(&sensor_line, "sensor");
      s.sensor.max_range_m = non_negative_within(in, 1, "max_range", lim::kMaxRange);
      s.sensor.min_range_m = non_negative_within(in, 2, "min_range", lim::kMaxRange);
      if (s.sensor.min_range_m > s.sensor.max_range_m)
        in.fail("min_range", fmt::format("min_range {} exceeds max_range {}", s.sensor.min_range_m, s.sensor.max_range_m));
      s.sensor.fov_rad = non_negative_within(in, 3, "fov", 1e300);
      if (s.sensor.fov_rad > 2.0 * kPi + 1e-9) in.fail("fov", "field of view larger than 2 pi");
      s.sensor.sigma_range_m = number_within(in, 4, "sigma_range", lim::kMinSigmaRange, lim::kMaxSigma);
      s.sensor.sigma_bearing_rad = number_within(in, 5, "sigma_bearing", lim::kMinSigmaBearing, lim::kMaxSigma);
      if (in.field(6) != "-") s.sensor.sigma_signature = non_negative_within(in, 6, "sigma_signature", lim::kMaxSigma);
    } else if (kind == "initial") {
      in.expect_fields(8, 8, "initial");
      once(&initial_line, "initial");
      s.start_time_s = time_field(in, 1, "time");
      last_time = s.start_time_s;
      s.initial_pose = {coordinate_field(in, 2, "x"), coordinate_field(in, 3, "y"), wrap_angle(coordinate_field(in, 4, "theta"))};
      s.initial_sigma = {non_negative_within(in, 5, "sigma_x", lim::kMaxSigma), non_negative_within(in, 6, "sigma_y", lim::kMaxSigma),
                         non_negative_within(in, 7, "sigma_theta", lim::kMaxSigma)};
    } else if (kind == "meta") {
      in.expect_fields(2, 1000, "meta");
      std::string value;
      for (std::size_t i = 2; i < in.field_count(); ++i) value += (i > 2 ? " " : "") + std::string(in.field(i));
      s.metadata[std::string(in.field(1))] = value;
    } else if (kind == "end") {
      in.expect_fields(2, 2, "end");
      const std::int64_t n = in.integer(1, "steps");
      if (n != static_cast<std::int64_t>(s.steps.size()))
        in.fail("steps", fmt::format("file says {} steps but {} were read", n, s.steps.size()));
      ended = true;
    } else {
      in.fail("type", fmt::format("unknown line type '{}' (expected step, truth, scan, z, landmark, gps, motion, "
                                  "sensor, initial, meta or end)", kind));
    }
  }
  if (scan_expected > 0)
    throw InputError(path, in.line_number(), "z", fmt::format("file ends inside the scan at line {}: {} measurement(s) missing", scan_line, scan_expected));
  if (!ended) throw InputError(path, in.line_number(), "end", "file ends without its 'end N' line (truncated?)");
  // A file without steps never reached the check at its first step.
  for (const auto& [line, what] : {std::pair{motion_line, "motion"}, {sensor_line, "sensor"}, {initial_line, "initial"}})
    if (line == 0) throw InputError(path, in.line_number(), what, fmt::format("the file has no '{}' line", what));
  return s;
}

void write_scenario(const Scenario& s, const std::string& path) {
  std::string out;
  out.reserve(64 * (s.steps.size() + 16));
  auto emit = [&out]<typename... T>(fmt::format_string<T...> f, T&&... args) {
    fmt::format_to(std::back_inserter(out), f, std::forward<T>(args)...);
  };
  emit("{} {}\n", kHeader, kVersion);
  emit("# Arbor scenario: see docs/scenario_format.md\n");
  for (const auto& [key, value] : s.metadata) emit("meta {} {}\n", key, value);
  const MotionModel& m = s.motion;
  switch (m.kind) {
    case MotionModelKind::kOdometry:
    case MotionModelKind::kVelocity: {
      const TwistNoise& n = m.kind == MotionModelKind::kOdometry ? m.odometry : m.velocity;
      emit("motion {} {} {} {} {} {}\n", to_string(m.kind), n.q_v, n.q_omega, n.k_v, n.k_wv, n.k_ww);
      break;
    }
    case MotionModelKind::kAckermann:
      emit("motion ackermann {} {} {} {} {} {}\n", m.ackermann.q_v, m.ackermann.q_steer,
           m.vehicle.wheelbase_m, m.vehicle.encoder_offset_m, m.vehicle.laser_forward_m, m.vehicle.laser_left_m);
      break;
  }
  const SensorModel& z = s.sensor;
  emit("sensor {} {} {} {} {} {}\n", z.max_range_m, z.min_range_m, z.fov_rad, z.sigma_range_m, z.sigma_bearing_rad,
       std::isnan(z.sigma_signature) ? std::string("-") : fmt::format("{}", z.sigma_signature));
  emit("initial {} {} {} {} {} {} {}\n", s.start_time_s, s.initial_pose.x, s.initial_pose.y, s.initial_pose.theta,
       s.initial_sigma.x(), s.initial_sigma.y(), s.initial_sigma.z());
  for (const auto& l : s.truth_landmarks) emit("landmark {} {} {}\n", l.id, l.position.x(), l.position.y());
  for (const auto& g : s.truth_track) emit("gps {} {} {}\n", g.time_s, g.position.x(), g.position.y());
  for (const auto& step : s.steps) {
    emit("step {} {} {} {}\n", step.time_s, step.control[0], step.control[1], step.control[2]);
    if (step.truth_pose) emit("truth {} {} {}\n", step.truth_pose->x, step.truth_pose->y, step.truth_pose->theta);
    if (step.has_scan) {
      emit("scan {}\n", step.measurements.size());
      for (const auto& meas : step.measurements)
        emit("z {} {} {} {}\n", meas.range_m, meas.bearing_rad, signature_text(meas.signature), truth_text(meas.truth_id));
    }
  }
  emit("end {}\n", s.steps.size());
  // A writer never emits a file its reader rejects (a simulation asked for zero noise, a converter fed a
  // landmark at 1e200): the text is read back under a temporary name first, and moved into place only then.
  // A writer killed while it read back (or out of memory) left its copy, hundreds of MB: the next one removes it.
  remove_orphaned_temporaries(path, "check");
  const std::string checked = fmt::format("{}.check.{}", path, static_cast<long>(getpid()));
  write_file_atomically(checked, out);
  try {
    read_scenario(checked);
  } catch (const InputError& e) {
    std::error_code ignored;
    std::filesystem::remove(checked, ignored);
    throw InputError(path, e.line(), e.field(), "not written: the scenario breaks a rule of the format: " + e.message());
  }
  std::filesystem::rename(checked, path);
}

}  // namespace arbor
