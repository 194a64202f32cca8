// BearingBound (core/engine/sensor_view.h) rules a landmark out before its bearing's atan2 is computed. It
// must never rule out one the view's own test keeps (else the candidates and the existence evidence would
// change), and it must rule out most of those the view rejects by bearing (else it buys nothing).
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <utility>
#include <vector>

#include "core/engine/sensor_view.h"
#include "core/math/angles.h"
#include "core/models/range_bearing_model.h"

namespace arbor {
namespace {

// From random poses (some with the heading at the wrap), landmarks at bearings a hair either side of
// +-limit_rad and one at a random bearing. Fails the test where the bound rules out a landmark the view keeps,
// or a random one whose bearing is clearly (0.1 rad) beyond the limit and that the bound nonetheless keeps.
// Returns how many it ruled out.
template <class InView>
int check_bearing_bound(double cos_bound, double limit_rad, const InView& in_view, std::mt19937_64* rng) {
  std::uniform_real_distribution<double> coordinate(-50.0, 50.0), heading(-kPi, kPi), range(0.5, 20.0), unit(0.0, 1.0);
  int ruled_out = 0;
  for (int trial = 0; trial < 4000; ++trial) {
    const Pose2 pose{coordinate(*rng), coordinate(*rng), trial % 7 == 0 ? kPi - 1e-13 * unit(*rng) : heading(*rng)};
    std::vector<Vec2> landmarks;
    for (double hair : {-1e-6, -1e-12, 0.0, 1e-12, 1e-6})
      for (double sign : {-1.0, 1.0}) {
        const double angle = pose.theta + sign * (limit_rad + hair);
        landmarks.push_back(pose.position() + range(*rng) * Vec2(std::cos(angle), std::sin(angle)));
      }
    const double anywhere = heading(*rng);
    landmarks.push_back(pose.position() + range(*rng) * Vec2(std::cos(anywhere), std::sin(anywhere)));
    const BearingBound bound(pose, cos_bound);
    for (std::size_t k = 0; k < landmarks.size(); ++k) {
      const Vec2& m = landmarks[k];
      const Vec2 z = range_bearing_predict(pose, m);
      const bool kept = in_view(Vec2(5.0, z.y()));  // at a range the view keeps: the bearing decides
      const bool out = bound.certainly_beyond(m, predicted_range(pose, m));
      EXPECT_FALSE(out && kept) << "bearing " << z.y() << " limit " << limit_rad << " heading " << pose.theta;
      const bool random_and_clearly_beyond = k + 1 == landmarks.size() && std::abs(z.y()) > limit_rad + 0.1;
      EXPECT_TRUE(out || !random_and_clearly_beyond) << "bearing " << z.y() << " limit " << limit_rad;
      ruled_out += out;
    }
  }
  return ruled_out;
}

TEST(BearingBound, NeverRulesOutALandmarkTheViewKeepsAndRulesOutThoseClearlyBehind) {
  std::mt19937_64 rng(7);
  // Fields of view from a sliver (whose evidence limit is negative: nothing counts as missed) to a full turn,
  // with heading margins up to the Taylor bound's widest use.
  const std::vector<std::pair<double, double>> fov_and_heading_margin = {
      {0.05, 0.0}, {0.2, 0.0}, {1.0, 0.05}, {kPi, 0.0}, {kPi, 0.3}, {1.5 * kPi, 0.1}, {2.0 * kPi - 0.35, 0.02}, {2.0 * kPi, 0.0}};
  for (const auto& [fov, heading_margin] : fov_and_heading_margin) {
    SensorModel sensor;
    sensor.fov_rad = fov;
    const SensorView view(sensor, SensorViewMargins{});
    const ViewMargin margin{0.0, heading_margin};
    const double candidate_limit = view.candidate_bearing_limit(margin);
    const int candidates_out = check_bearing_bound(view.candidate_cos_bound(margin), candidate_limit,
                                                   [&](const Vec2& z) { return view.in_candidate_view(z, margin); }, &rng);
    const double evidence_limit = view.evidence_bearing_limit();
    const int evidence_out = check_bearing_bound(view.evidence_cos_bound(), evidence_limit,
                                                 [&](const Vec2& z) { return view.in_evidence_view(z); }, &rng);
    // Past a full turn nothing may be ruled out; below one, the random landmarks behind the sensor are.
    if (candidate_limit >= kPi) {
      EXPECT_EQ(candidates_out, 0) << "fov " << fov;
    }
    if (candidate_limit + 0.1 < kPi) {
      EXPECT_GT(candidates_out, 0) << "fov " << fov;
    }
    if (evidence_limit >= kPi) {
      EXPECT_EQ(evidence_out, 0) << "fov " << fov;
    }
    if (evidence_limit + 0.1 < kPi) {
      EXPECT_GT(evidence_out, 0) << "fov " << fov;
    }
  }
}

}  // namespace
}  // namespace arbor
