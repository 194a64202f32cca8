// A field of N landmarks at constant density whose ids follow a lawn-mower exploration (the order in which a
// robot sweeping the area would create them), and a circular drive through it with range-bearing scans:
// the inputs of the map and step benchmarks and of the back-end identity test. (Not the simulator: a
// minimal, fixed workload whose cost per step does not depend on N.)
#ifndef ARBOR_BENCH_MAP_WORLD_H_
#define ARBOR_BENCH_MAP_WORLD_H_

#include <algorithm>
#include <charconv>
#include <cstdio>
#include <cstring>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <random>
#include <vector>

#include "core/types/landmark.h"
#include "core/engine/rng.h"
#include "core/types/scenario.h"
#include "core/models/range_bearing_model.h"
#include "experiments/sim/survey.h"

namespace arbor::bench {

// Density and sweep width chosen so that a 2 x 15 m sensor footprint sees ~10 landmarks whatever N.
inline constexpr double kLandmarksPerSquareMetre = 0.01;
inline constexpr double kStripWidthM = 30.0;

inline double field_side_m(std::int64_t n) { return std::sqrt(static_cast<double>(n) / kLandmarksPerSquareMetre); }

// The largest N the map and step benchmarks run: 10^6, or ARBOR_BENCH_MAX_N (a power of ten; 10^7 needs
// about 4 GB for the trie or tree and a minute to build each prior map). A value that is not a whole number
// from 100 to 10^7 stops the benchmark with a message, rather than running another range than the one asked.
inline std::int64_t bench_max_n() {
  const char* text = std::getenv("ARBOR_BENCH_MAX_N");
  if (!text) return 1000000;
  std::int64_t n = 0;
  const char* end = text + std::strlen(text);
  const auto [ptr, error] = std::from_chars(text, end, n);
  if (error != std::errc() || ptr != end || n < 100 || n > 10000000) {
    std::fprintf(stderr, "ARBOR_BENCH_MAX_N=%s: expected a whole number from 100 to 10000000\n", text);
    std::exit(2);
  }
  return n;
}

// N landmarks uniform over a square of side field_side_m(n) centred on the origin; ids 0..N-1 in the order
// of a boustrophedon sweep in strips of kStripWidthM (as a creation serial would number them).
inline std::vector<Landmark> make_landmark_field(std::int64_t n, std::uint64_t seed = 42) {
  const double side = field_side_m(n);
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-side / 2, side / 2);
  std::vector<Landmark> field(n);
  for (Landmark& lm : field) {
    lm.mean = draw_vec2([&] { return u(rng); });
    lm.cov = Mat2::Identity() * 0.25;
    lm.log_odds = 1.0f;
    lm.confirmed = true;
  }
  number_in_strips(field, kStripWidthM, -side / 2);
  for (Landmark& lm : field) lm.truth_label = static_cast<std::int32_t>(lm.id);
  return field;
}

struct FieldDrive {
  double radius_m = 60.0;       // circle centred on the origin, driven counter-clockwise
  double step_m = 1.0;          // distance per step
  int steps = 200;
  double max_range_m = 20.0;
  double detection_probability = 0.9;
  std::uint64_t seed = 7;
};

// A scenario driving drive.steps steps around the circle, one scan per step of every landmark of `field`
// in range (truth_id = the landmark's id), each detected with drive.detection_probability.
inline Scenario make_field_scenario(const std::vector<Landmark>& field, const FieldDrive& drive) {
  Scenario sc;
  sc.metadata["source"] = "bench/map_world.h";
  sc.motion.kind = MotionModelKind::kOdometry;
  sc.sensor.max_range_m = drive.max_range_m;
  sc.initial_pose = {drive.radius_m, 0.0, kPi / 2};
  // Only landmarks near the circle can ever be seen: filter once, O(N).
  std::vector<const Landmark*> near;
  for (const Landmark& lm : field) {
    const double d = lm.mean.norm();
    if (d > drive.radius_m - drive.max_range_m - 1.0 && d < drive.radius_m + drive.max_range_m + 1.0) near.push_back(&lm);
  }
  const double dtheta = drive.step_m / drive.radius_m;
  Pose2 truth = sc.initial_pose;
  const double sr = sc.sensor.sigma_range_m, sb = sc.sensor.sigma_bearing_rad;
  for (int t = 0; t < drive.steps; ++t) {
    RandomStream rng(drive.seed, t, 0, RandomPurpose::kSimulation);
    ScenarioStep step;
    const double angle = std::atan2(truth.y, truth.x) + dtheta;
    const Pose2 next{drive.radius_m * std::cos(angle), drive.radius_m * std::sin(angle), wrap_angle(angle + kPi / 2)};
    step.control = odometry_between(truth, next);
    truth = odometry_apply(truth, step.control, nullptr, nullptr);
    step.time_s = t + 1.0;
    step.truth_pose = truth;
    step.has_scan = true;
    for (const Landmark* lm : near) {
      const Vec2 z = range_bearing_predict(truth, lm->mean);
      if (z.x() > drive.max_range_m || z.x() < 0.5) continue;
      if (rng.uniform() > drive.detection_probability) continue;
      Measurement m;
      m.range_m = z.x() + sr * rng.normal();
      m.bearing_rad = wrap_angle(z.y() + sb * rng.normal());
      m.truth_id = lm->id;
      step.measurements.push_back(m);
    }
    sc.steps.push_back(std::move(step));
  }
  return sc;
}

}  // namespace arbor::bench

#endif  // ARBOR_BENCH_MAP_WORLD_H_
