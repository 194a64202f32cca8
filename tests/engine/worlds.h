// The engine tests' small world helper: the default simulated world, a robot standing before a handful of
// landmarks, a FastSLAM run's config, and the check that a run is the same to the last bit with every map back
// end on 1 and 2 threads.
#ifndef ARBOR_TESTS_ENGINE_WORLDS_H_
#define ARBOR_TESTS_ENGINE_WORLDS_H_

#include <functional>
#include <limits>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "experiments/run/fastslam_run.h"
#include "experiments/sim/simulator.h"
#include "tests/support/scratch.h"
#include "variants/registry.h"

namespace arbor::testing {

// The default simulated world (experiments/sim/simulator.h), world and noise from one seed.
inline Scenario simulated_world(std::uint64_t seed, int scans, double clutter = 0.0, int controls_per_scan = 1) {
  SimulationOptions o;
  o.seed = o.world.seed = seed;
  o.steps = scans;
  o.clutter_rate = clutter;
  o.controls_per_scan = controls_per_scan;
  return simulate(o);
}

// A rooms world with clutter: corridors, loops and spurious points, where the options that act on association
// (set gating, loop closing, resample-move) have something to do.
inline Scenario cluttered_rooms(std::uint64_t seed, int landmarks, double clutter, int scans = SimulationOptions{}.steps) {
  SimulationOptions o;
  o.seed = o.world.seed = seed;
  o.world.kind = WorldKind::kRooms;
  o.world.landmarks = landmarks;
  o.steps = scans;
  o.clutter_rate = clutter;
  return simulate(o);
}

// A robot standing at the origin, heading +x, scanning every 0.5 s: scans[k] holds scan k's measurements as
// (range, bearing), each labelled true landmark 0. Its sensor sees 20 m over a half circle (sigma 0.1 m and
// 0.01 rad). The start is exact; the odometry has the default noise, a few centimetres and about 2 degrees
// per scan standing still, so a pairing can move FastSLAM 2.0's proposal.
inline Scenario standing_robot(const std::vector<std::vector<Vec2>>& scans) {
  Scenario s;
  s.sensor.max_range_m = 20.0;
  s.sensor.fov_rad = kPi;
  s.sensor.sigma_range_m = 0.1;
  s.sensor.sigma_bearing_rad = 0.01;
  for (std::size_t k = 0; k < scans.size(); ++k) {
    ScenarioStep step;
    step.time_s = 0.5 * static_cast<double>(k);
    step.has_scan = true;
    step.truth_pose = Pose2{};
    for (const Vec2& z : scans[k])
      step.measurements.push_back({z.x(), z.y(), std::numeric_limits<float>::quiet_NaN(), 0});
    s.steps.push_back(step);
  }
  return s;
}

// A FastSLAM run with the default map, known association (the oracle, named: the default is a real strategy)
// and these settings.
inline RunConfig fastslam_config(FilterVersion version, int particles, std::uint64_t seed, int threads) {
  RunConfig c;
  c.assoc = "known";
  c.options.version = version;
  c.options.particles = particles;
  c.options.seed = seed;
  c.options.threads = threads;
  return c;
}

// JCBB with 20 particles, filter seed 3: the identity runs of the options below, small enough to repeat for
// every back end and thread count.
inline void small_jcbb_run(RunConfig& c) {
  c.assoc = "jcbb";
  c.options.particles = 20;
  c.options.seed = 3;
}

// Runs the scenario with every map back end on 1 and 2 threads, each run's config set by `configure`, and
// expects the trajectory, the map and the F1 to be the same to the last bit in all of them; `check` is called
// on every run's output (what a run must show for the comparison to mean something).
inline void expect_bit_identical_across_backends_and_threads(
    const Scenario& scenario, const std::string& name, const std::function<void(RunConfig&)>& configure,
    const std::function<void(const RunOutput&, const std::string& what)>& check = {}) {
  std::string reference;
  for (const std::string& map : map_backend_names()) {
    for (int threads : {1, 2}) {
      RunConfig c;
      configure(c);
      c.map = map;
      c.options.threads = threads;
      c.out_dir = scratch_dir(name + "_" + map + "_" + std::to_string(threads));
      const RunOutput out = run_fastslam(scenario, c);
      const std::string what = map + " with " + std::to_string(threads) + " threads";
      if (check) check(out, what);
      const std::string files =
          read_file(c.out_dir + "/trajectory.tum") + read_file(c.out_dir + "/map.csv") + out.result["assoc_f1"].dump();
      if (reference.empty()) reference = files;
      EXPECT_TRUE(files == reference) << what << " differs";
    }
  }
}

// Consistency over Monte Carlo runs (Bar-Shalom, Li & Kirubarajan 2001, §5.4): the average of 30 NEES values
// of a consistent 3-dof estimator lies in the chi2(90)/30 quantiles [2.19, 3.93] with 95 % probability.
inline constexpr int kNeesSeeds = 30;
inline constexpr double kNeesBandLow = 2.19, kNeesBandHigh = 3.93;
inline bool in_nees_band(double average) { return average >= kNeesBandLow && average <= kNeesBandHigh; }

// Per scan after the exactly known start (scans - 1 values; step 0 has no NEES, 0/0), the average over seeds
// 1..kNeesSeeds of the NEES of run(seed), a run of `scans` scans.
inline std::vector<double> average_nees_over_seeds(int scans, const std::function<RunOutput(int seed)>& run) {
  std::vector<double> sum(scans - 1, 0.0);
  for (int seed = 1; seed <= kNeesSeeds; ++seed) {
    const RunOutput out = run(seed);
    EXPECT_EQ(out.nees.size(), sum.size()) << "one NEES per scan after the exact start, seed " << seed;
    for (std::size_t k = 0; k < sum.size() && k < out.nees.size(); ++k) sum[k] += out.nees[k];
  }
  for (double& v : sum) v /= kNeesSeeds;
  return sum;
}

}  // namespace arbor::testing

#endif  // ARBOR_TESTS_ENGINE_WORLDS_H_
