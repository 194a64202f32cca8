// The simulator: a robot drives a loop through a World with a noisy odometer and a range-bearing sensor that
// misses detections and reports clutter. Deterministic from a seed; the Scenario it returns carries ground
// truth for poses, landmarks and each measurement's landmark id.
#ifndef ARBOR_EXPERIMENTS_SIM_SIMULATOR_H_
#define ARBOR_EXPERIMENTS_SIM_SIMULATOR_H_

#include <cstdint>

#include "core/types/scenario.h"
#include "experiments/sim/world.h"

namespace arbor {

// The largest clutter rate the Poisson sampler serves (Knuth's method is for small rates); `arbor relocalize`
// applies it too, since each spurious measurement there is drawn and searched.
inline constexpr double kMaxClutterRate = 500.0;

struct SimulationOptions {
  WorldOptions world;
  int steps = 500;              // scans; the first stands still at the initial pose
  int controls_per_scan = 1;    // odometry readings between two scans, dt_s / K apart
  double speed_mps = 1.0;
  double dt_s = 0.5;
  double max_turn_rate_radps = 0.6;
  // The loop is the world's square shrunk by this fraction on every side (room centres in the rooms world).
  double loop_inset_fraction = 0.25;
  SensorModel sensor = default_sensor();
  double detection_probability = 0.9;
  double clutter_rate = 0.0;  // expected spurious measurements per scan (Poisson), at most kMaxClutterRate
  // Continuous-time (TwistNoise). The defaults give about 2.5 cm along-track and 0.016 rad of heading per 0.5 m
  // of driving, the per-reading noise of Arbor's earlier simulator at its 0.5 s step.
  OdometryNoise odometry{1e-6, 1e-6, 1.25e-3, 5e-4, 4e-4};
  bool signatures = false;    // report a noisy signature (sigma: sensor.sigma_signature, default 0.05)
  // Kidnapped robot: at the first scan at or after this time [s] the robot is carried, unseen by its
  // odometer, to where it was at half that time (a place it has mapped), and drives on from there.
  // Negative: never.
  double kidnap_time_s = -1.0;
  std::uint64_t seed = 1;

  static SensorModel default_sensor() {
    SensorModel s;
    s.max_range_m = 20.0;
    s.min_range_m = 0.5;
    s.fov_rad = kPi;
    s.sigma_range_m = 0.1;
    s.sigma_bearing_rad = 0.5 * kPi / 180.0;
    return s;
  }
};

// Throws InputError (field named after the option) for options out of range.
Scenario simulate(const SimulationOptions& options);

}  // namespace arbor

#endif  // ARBOR_EXPERIMENTS_SIM_SIMULATOR_H_
