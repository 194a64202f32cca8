// Tiny hand-built scenarios for the smoother tests: a robot driving a loop among a ring of landmarks, with
// seeded noise and true association ids. Small enough that every test runs in milliseconds.
#ifndef ARBOR_TESTS_SMOOTHING_TINY_WORLD_H_
#define ARBOR_TESTS_SMOOTHING_TINY_WORLD_H_

#include <cmath>
#include <random>

#include <Eigen/Cholesky>

#include "core/engine/rng.h"
#include "core/types/scenario.h"
#include "core/models/range_bearing_model.h"

namespace arbor::testing {

struct TinyWorldOptions {
  int landmarks = 16;
  int steps = 80;              // one loop of a circle of radius 10 m
  int scan_every = 1;          // a scan every n-th step (the others only move the robot)
  double max_range_m = 8.0;
  MotionModelKind motion = MotionModelKind::kOdometry;
  unsigned seed = 1;
  double noise_scale = 1.0;  // multiplies every noise standard deviation (odometry and sensor)
};

// Truth: the robot drives a circle of radius 10 m; landmarks on rings of radius 6 and 14 m. Controls carry
// noise drawn from the model's Q_u; measurements from R. Every measured landmark has its truth id.
inline Scenario make_tiny_world(const TinyWorldOptions& o) {
  std::mt19937 rng(o.seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  Scenario s;
  s.metadata["source"] = "tests/smoothing/tiny_world.h";
  s.motion.kind = o.motion;
  // About 4 cm along-track and 0.025 rad of heading per 0.79 m step (the velocity and Ackermann models keep
  // their defaults).
  const double variance_scale = o.noise_scale * o.noise_scale;
  s.motion.odometry = TwistNoise{1e-6 * variance_scale, 1e-6 * variance_scale, 2e-3 * variance_scale, 8e-4 * variance_scale, 0.0};
  s.sensor.max_range_m = o.max_range_m;
  s.sensor.sigma_range_m = 0.1 * o.noise_scale;
  s.sensor.sigma_bearing_rad = 0.02 * o.noise_scale;
  const double radius = 10.0;
  s.initial_pose = Pose2{radius, 0.0, kPi / 2};
  for (int j = 0; j < o.landmarks; ++j) {
    const double a = 2.0 * kPi * j / o.landmarks;
    const double r = (j % 2 == 0) ? 6.0 : 14.0;
    s.truth_landmarks.push_back({j, Vec2(r * std::cos(a), r * std::sin(a))});
  }
  Pose2 truth = s.initial_pose;
  const double dphi = 2.0 * kPi / o.steps, dt = 1.0;
  for (int k = 0; k < o.steps; ++k) {
    // The true motion along the circle, expressed as a noise-free control of the chosen model.
    const Pose2 next{radius * std::cos(dphi * (k + 1)), radius * std::sin(dphi * (k + 1)), wrap_angle(kPi / 2 + dphi * (k + 1))};
    Vec3 u;
    switch (o.motion) {
      case MotionModelKind::kOdometry: u = odometry_between(truth, next); break;
      case MotionModelKind::kVelocity: {
        const double w = dphi / dt, v = radius * w;  // exact arc
        u = Vec3(v, w, dt);
        break;
      }
      case MotionModelKind::kAckermann: u = Vec3(1.0, 0.05, 0.5); break;  // a gentle left turn
    }
    // The true motion is the logged control's plus a draw of its process noise (the model the filter and the
    // smoother assume). The first motion is exact: no scan precedes it, so its error would rotate the whole
    // solution against the truth (a gauge error no method can see), and the tests compare without alignment.
    const Eigen::LLT<Mat3> llt(s.motion.process_noise(truth, u, dt) + 1e-18 * Mat3::Identity());
    const Vec3 noise = k == 0 ? Vec3::Zero() : Vec3(llt.matrixL() * draw_vec3([&] { return normal(rng); }));
    truth = Pose2::from_vector(s.motion.apply(truth, u).vector() + noise);
    const Vec3 measured = u;
    ScenarioStep step;
    step.time_s = dt * (k + 1);
    step.control = measured;
    step.truth_pose = truth;
    step.has_scan = (k % o.scan_every) == 0;
    if (step.has_scan) {
      for (const TruthLandmark& lm : s.truth_landmarks) {
        const Vec2 z_true = range_bearing_predict(truth, lm.position);
        if (!s.sensor.in_view(z_true)) continue;
        Measurement m;
        m.range_m = z_true.x() + s.sensor.sigma_range_m * normal(rng);
        m.bearing_rad = wrap_angle(z_true.y() + s.sensor.sigma_bearing_rad * normal(rng));
        m.truth_id = lm.id;
        step.measurements.push_back(m);
      }
    }
    s.steps.push_back(step);
  }
  return s;
}

// The pose a scenario's step ends at, following the controls from the initial pose (dead reckoning).
inline std::vector<Pose2> dead_reckoning(const Scenario& s) {
  std::vector<Pose2> poses;
  Pose2 x = s.initial_pose;
  for (const ScenarioStep& step : s.steps) poses.push_back(x = s.motion.apply(x, step.control));
  return poses;
}

}  // namespace arbor::testing

#endif  // ARBOR_TESTS_SMOOTHING_TINY_WORLD_H_
