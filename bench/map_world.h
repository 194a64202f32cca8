// A field of N landmarks at constant density whose ids follow a lawn-mower exploration (the order in which a
// robot sweeping the area would create them), shared by the map and step benchmarks.
#ifndef ARBOR_BENCH_MAP_WORLD_H_
#define ARBOR_BENCH_MAP_WORLD_H_

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "core/engine/landmark.h"

namespace arbor::bench {

// Density and sweep width chosen so that a 2 x 15 m sensor footprint sees ~10 landmarks whatever N.
inline constexpr double kLandmarksPerSquareMetre = 0.01;
inline constexpr double kStripWidthM = 30.0;

inline double field_side_m(std::int64_t n) { return std::sqrt(static_cast<double>(n) / kLandmarksPerSquareMetre); }

// N landmarks uniform over a square of side field_side_m(n) centred on the origin; ids 0..N-1 in the order
// of a boustrophedon sweep in strips of kStripWidthM (as a creation serial would number them).
inline std::vector<Landmark> make_landmark_field(std::int64_t n, std::uint64_t seed = 42) {
  const double side = field_side_m(n);
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-side / 2, side / 2);
  std::vector<Landmark> field(n);
  for (Landmark& lm : field) {
    lm.mean = Vec2(u(rng), u(rng));
    lm.cov = Mat2::Identity() * 0.25;
    lm.log_odds = 1.0f;
  }
  auto strip = [&](const Landmark& lm) { return static_cast<std::int64_t>((lm.mean.y() + side / 2) / kStripWidthM); };
  std::sort(field.begin(), field.end(), [&](const Landmark& a, const Landmark& b) {
    const std::int64_t sa = strip(a), sb = strip(b);
    if (sa != sb) return sa < sb;
    return (sa % 2 == 0) ? a.mean.x() < b.mean.x() : a.mean.x() > b.mean.x();
  });
  for (std::int64_t i = 0; i < n; ++i) field[i].id = static_cast<LandmarkId>(i);
  return field;
}

}  // namespace arbor::bench

#endif  // ARBOR_BENCH_MAP_WORLD_H_
