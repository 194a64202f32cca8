// Loop trajectory, odometry and range-bearing measurement simulation.
#include "experiments/sim/simulator.h"

#include <algorithm>
#include <array>
#include <cmath>

#include <Eigen/Cholesky>
#include <fmt/core.h>

#include "core/engine/rng.h"
#include "core/io/input_error.h"
#include "core/io/memory_budget.h"
#include "core/models/range_bearing_model.h"

namespace arbor {
namespace {

void require(bool ok, const char* field, const std::string& message) {
  if (!ok) throw InputError("", 0, field, message);
}

// Knuth's multiplication method; rates here are small (a few per scan, at most kMaxClutterRate).

int sample_poisson(double rate, RandomStream& rng) {
  if (rate <= 0.0) return 0;
  const double limit = std::exp(-rate);
  int k = 0;
  for (double product = rng.uniform(); product > limit; product *= rng.uniform()) ++k;
  return k;
}

std::array<Vec2, 4> loop_corners(const World& world, const SimulationOptions& o) {
  const double lo = o.loop_inset_fraction * world.side_m, hi = (1.0 - o.loop_inset_fraction) * world.side_m;
  std::array<Vec2, 4> corners{Vec2(lo, lo), Vec2(hi, lo), Vec2(hi, hi), Vec2(lo, hi)};
  if (world.kind == WorldKind::kRooms) {  // through room centres, so every wall is crossed at its doorway
    const double s = world.room_size_m;
    for (Vec2& c : corners) c = ((c / s).array().floor() * s + 0.5 * s).matrix();
  }
  return corners;
}

}  // namespace

Scenario simulate(const SimulationOptions& o) {
  require(o.world.landmarks >= 1, "landmarks", "need at least one landmark");
  require(o.world.density_per_m2 > 0.0, "density", "density must be positive");
  require(o.steps >= 1, "steps", "need at least one step");
  // 170 bytes a landmark at 10^6 (peak RSS 184 MB, 5 steps): 10^7 on a small machine ended in std::bad_alloc.
  require_memory(o.world.landmarks, 150.0, "landmarks", "landmarks");
  require(o.controls_per_scan >= 1 && o.controls_per_scan <= 1000, "controls-per-scan",
          fmt::format("controls per scan must lie in [1, 1000] (got {})", o.controls_per_scan));
  require(o.speed_mps > 0.0 && o.dt_s > 0.0, "speed", "speed and dt must be positive");
  // The Poisson sampler multiplies uniforms down to exp(-rate), which underflows above a rate of about 745:
  // larger rates all gave about 755 measurements a scan while the metadata claimed the rate asked for.
  require(o.clutter_rate >= 0.0 && o.clutter_rate <= kMaxClutterRate, "clutter",
          fmt::format("clutter rate must lie in [0, {}] per scan (got {})", kMaxClutterRate, o.clutter_rate));
  require(o.detection_probability > 0.0 && o.detection_probability <= 1.0, "detection",
          "detection probability must lie in (0, 1]");
  require(o.loop_inset_fraction > 0.0 && o.loop_inset_fraction < 0.5, "inset", "loop inset must lie in (0, 0.5)");
  require(std::isfinite(o.kidnap_time_s), "kidnap", "kidnap time must be finite");
  // A kidnap after the last scan never happens, and the metadata would record one.
  const double last_scan_s = (o.steps - 1) * o.dt_s;
  require(o.kidnap_time_s < 0.0 || o.kidnap_time_s <= last_scan_s, "kidnap",
          fmt::format("kidnap time {} s is after the last scan ({} s)", o.kidnap_time_s, last_scan_s));

  const World world = make_world(o.world);
  Scenario s;
  s.metadata = {{"source", "simulation"},
                {"world", std::string(to_string(o.world.kind))},
                {"landmarks", fmt::format("{}", o.world.landmarks)},
                {"density_per_m2", fmt::format("{}", o.world.density_per_m2)},
                {"clutter_rate", fmt::format("{}", o.clutter_rate)},
                {"detection_probability", fmt::format("{}", o.detection_probability)},
                {"steps", fmt::format("{}", o.steps)},
                {"controls_per_scan", fmt::format("{}", o.controls_per_scan)},
                {"seed", fmt::format("{}", o.seed)}};
  if (o.kidnap_time_s >= 0.0) s.metadata["kidnap_time_s"] = fmt::format("{}", o.kidnap_time_s);
  s.motion.kind = MotionModelKind::kOdometry;
  s.motion.odometry = o.odometry;
  s.sensor = o.sensor;
  if (o.signatures && std::isnan(s.sensor.sigma_signature)) s.sensor.sigma_signature = 0.05;
  if (!o.signatures) s.sensor.sigma_signature = std::numeric_limits<double>::quiet_NaN();
  s.truth_landmarks = world.landmarks;

  const auto corners = loop_corners(world, o);
  Pose2 truth{corners[0].x(), corners[0].y(),
              std::atan2(corners[1].y() - corners[0].y(), corners[1].x() - corners[0].x())};
  s.initial_pose = truth;
  s.start_time_s = 0.0;
  const LandmarkGrid grid(world, std::max(5.0, s.sensor.max_range_m));
  int target = 1;
  ScenarioStep scan_step;

  s.steps.reserve(static_cast<std::size_t>(o.steps - 1) * o.controls_per_scan + 1);
  const int K = o.controls_per_scan;
  const double dt = o.dt_s / K;
  // Step 0 stands still and scans from the known initial pose: the first landmarks are anchored to it, as the
  // initial pose anchors the gauge. Without it the first motion's heading error rotates the whole map.
  std::vector<Pose2> scan_poses;  // the true pose at each scan, for the kidnapping
  bool kidnapped = false;
  for (int k = 0; k < o.steps; ++k) {
    RandomStream rng(o.seed, k, 0, RandomPurpose::kSimulation);
    if (k > 0 && !kidnapped && o.kidnap_time_s >= 0.0 && k * o.dt_s >= o.kidnap_time_s) {
      truth = scan_poses[k / 2];  // carried off between two readings; the odometer sees nothing
      kidnapped = true;
    }
    if (k > 0) {
      // Steer towards the next corner with a bounded turn rate, chosen once per scan interval; the robot moves
      // along the exact arc, read by the odometer K times. The turn cancels the heading error in one interval
      // (rate = error / dt). Twice that gain, which the simulator had until the change that wrote this, maps
      // an error e to -e at the next scan: after the first corner the robot swung +-0.095 rad about every edge
      // each half second without end, and every trajectory plot showed the zigzag.
      if ((truth.position() - corners[target]).norm() < 1.5 * o.speed_mps * o.dt_s) target = (target + 1) % 4;
      const Vec2 to_target = corners[target] - truth.position();
      const double heading_error = wrap_angle(std::atan2(to_target.y(), to_target.x()) - truth.theta);
      const double omega = std::clamp(heading_error / o.dt_s, -o.max_turn_rate_radps, o.max_turn_rate_radps);
      for (int c = 0; c < K; ++c) {
        RandomStream odometer(o.seed, k, c + 1, RandomPurpose::kSimulation);
        const Pose2 next = velocity_apply(truth, Vec3(o.speed_mps, omega, dt), nullptr, nullptr);
        // The odometer believes in a pose off the true one by a draw of the reading's own process noise, so
        // that the filter's model (true = apply(reading) + noise of covariance Q_d) holds.
        const Mat3 Q = odometry_body_noise(odometry_between(truth, next), dt, o.odometry).at(truth.theta);
        const Eigen::LLT<Mat3> llt(Q + 1e-18 * Mat3::Identity());
        const Vec3 e = llt.matrixL() * draw_vec3([&] { return odometer.normal(); });
        ScenarioStep step;
        step.time_s = (k - 1) * o.dt_s + (c + 1) * dt;
        step.control = odometry_between(truth, Pose2::from_vector(next.vector() + e));
        step.truth_pose = next;
        truth = next;
        if (c + 1 < K) s.steps.push_back(std::move(step));
        else scan_step = std::move(step);
      }
    }
    ScenarioStep step = k > 0 ? std::move(scan_step) : ScenarioStep{};
    step.time_s = k * o.dt_s;
    step.truth_pose = truth;
    step.has_scan = true;
    scan_poses.push_back(truth);

    grid.visit_within(truth.position(), s.sensor.max_range_m, [&](int index) {
      const Vec2& m = world.landmarks[index].position;
      const Vec2 z = range_bearing_predict(truth, m);
      if (!s.sensor.in_view(z) || !world.line_of_sight(truth.position(), m)) return;
      if (rng.uniform() > o.detection_probability) return;
      Measurement meas;
      meas.range_m = std::max(0.0, z.x() + s.sensor.sigma_range_m * rng.normal());
      meas.bearing_rad = wrap_angle(z.y() + s.sensor.sigma_bearing_rad * rng.normal());
      if (o.signatures)
        meas.signature = static_cast<float>(world.signatures[index] + s.sensor.sigma_signature * rng.normal());
      meas.truth_id = index;
      step.measurements.push_back(meas);
    });
    const int clutter = sample_poisson(o.clutter_rate, rng);
    for (int c = 0; c < clutter; ++c) {
      Measurement meas;
      meas.range_m = s.sensor.min_range_m + (s.sensor.max_range_m - s.sensor.min_range_m) * rng.uniform();
      meas.bearing_rad = (rng.uniform() - 0.5) * s.sensor.fov_rad;
      if (o.signatures)
        meas.signature = static_cast<float>(o.world.signature_min + (o.world.signature_max - o.world.signature_min) * rng.uniform());
      meas.truth_id = kTruthClutter;
      step.measurements.push_back(meas);
    }
    // A sensor reports in bearing order; the order must not give away which measurement is which.
    std::stable_sort(step.measurements.begin(), step.measurements.end(),
                     [](const Measurement& a, const Measurement& b) { return a.bearing_rad < b.bearing_rad; });
    s.steps.push_back(std::move(step));
  }
  return s;
}

}  // namespace arbor
