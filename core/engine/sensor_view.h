// Where a particle's sensor could see: the query box and view that pick a scan's association candidates, and
// the narrower view inside which a landmark that goes unseen counts as missed (existence evidence).
#ifndef ARBOR_CORE_ENGINE_SENSOR_VIEW_H_
#define ARBOR_CORE_ENGINE_SENSOR_VIEW_H_

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/engine/fastslam_options.h"
#include "core/math/angles.h"
#include "core/math/eigen_types.h"
#include "core/math/pose2.h"
#include "core/models/sensor_model.h"
#include "core/types/box2.h"

namespace arbor {

// How far beyond the sensor's view a pose drawn from N(pose, P) could see: three standard deviations of
// the position (range) and of the heading (bearing). Zero for a sampled pose.
struct ViewMargin {
  double range_m = 0.0, bearing_rad = 0.0;
};
inline ViewMargin uncertainty_margin(const Mat3& P) {
  return {3.0 * std::sqrt(std::max({P(0, 0), P(1, 1), 0.0})), 3.0 * std::sqrt(std::max(P(2, 2), 0.0))};
}

class SensorView {
 public:
  SensorView(const SensorModel& sensor, const SensorViewMargins& margins)
      : max_range_m_(sensor.max_range_m), min_range_m_(sensor.min_range_m), fov_rad_(sensor.fov_rad), margins_(margins),
        candidate_base_rad_(0.5 * fov_rad_ + margins_.candidate_bearing_rad),
        cos_candidate_base_(std::cos(candidate_base_rad_)), sin_candidate_base_(std::sin(candidate_base_rad_)),
        evidence_cos_bound_(cosine_bound(evidence_bearing_limit())) {}

  // Where the sensor could see: the landmarks in this box are the association candidates.
  Box2 query_box(const Pose2& pose, double extra_reach_m = 0.0) const {
    const double reach = max_range_m_ + margins_.candidate_range_m + extra_reach_m;
    return {pose.position() - Vec2(reach, reach), pose.position() + Vec2(reach, reach)};
  }
  // Whether a landmark predicted at z could be seen from a pose within margin of the particle's; the range
  // half alone, for a test before the bearing is computed.
  bool in_candidate_range(double range_m, const ViewMargin& margin) const {
    return range_m <= max_range_m_ + margins_.candidate_range_m + margin.range_m;
  }
  bool in_candidate_view(const Vec2& z, const ViewMargin& margin) const {
    return in_candidate_range(z.x(), margin) && std::abs(z.y()) <= candidate_bearing_limit(margin);
  }
  double candidate_bearing_limit(const ViewMargin& margin) const { return candidate_base_rad_ + margin.bearing_rad; }
  // Whether a landmark predicted at z lies well inside the view: unseen there, it was missed.
  bool in_evidence_range(double range_m) const {
    return range_m <= max_range_m_ - margins_.evidence_range_m && range_m >= min_range_m_ + margins_.evidence_range_m;
  }
  bool in_evidence_view(const Vec2& z) const {
    return in_evidence_range(z.x()) && std::abs(z.y()) <= evidence_bearing_limit();
  }
  double evidence_bearing_limit() const { return 0.5 * fov_rad_ - margins_.evidence_bearing_rad; }

  // For BearingBound: numbers below the cosines of the views' bearing limits by a margin (1e-9) that no
  // rounding can cross, -inf where the limit reaches a full turn. The candidate limit grows with the
  // particle's heading margin b; cos(L + b) >= cos L - b sin L - b^2 / 2 (Taylor, with the remainder's
  // cosine at most 1) bounds it without a cosine per particle.
  double candidate_cos_bound(const ViewMargin& margin) const {
    const double b = margin.bearing_rad;
    if (candidate_base_rad_ + b >= kPi) return kNoBound;
    return cos_candidate_base_ - b * sin_candidate_base_ - 0.5 * b * b - kCosineMargin;
  }
  double evidence_cos_bound() const { return evidence_cos_bound_; }

 private:
  static constexpr double kCosineMargin = 1e-9;
  static constexpr double kNoBound = -std::numeric_limits<double>::infinity();
  static double cosine_bound(double limit_rad) {
    return limit_rad >= kPi ? kNoBound : std::cos(limit_rad) - kCosineMargin;
  }

  double max_range_m_, min_range_m_, fov_rad_;
  SensorViewMargins margins_;
  double candidate_base_rad_, cos_candidate_base_, sin_candidate_base_;
  double evidence_cos_bound_;
};

// A test before a bearing's atan2 is paid for: whether the bearing phi of landmark m from pose is certainly
// beyond a view's limit L, |phi| > L, decided on its cosine: cos phi = (R(theta)^T (m - p))_x / r < cos_bound,
// with cos_bound below cos L by a margin (SensorView::*_cos_bound) some million times what the rounding of
// this test and of atan2 can move. A landmark it rules out is one the view's own test would rule out too, so
// what a scan pairs and what its evidence counts stay bit-identical. Default-constructed, it rules out nothing.
class BearingBound {
 public:
  BearingBound() = default;
  BearingBound(const Pose2& pose, double cos_bound)
      : x_(pose.x), y_(pose.y), cos_theta_(std::cos(pose.theta)), sin_theta_(std::sin(pose.theta)),
        cos_bound_(cos_bound) {}

  // range_m: predicted_range(pose, m).
  bool certainly_beyond(const Vec2& m, double range_m) const {
    return cos_theta_ * (m.x() - x_) + sin_theta_ * (m.y() - y_) < cos_bound_ * range_m;
  }

 private:
  double x_ = 0.0, y_ = 0.0, cos_theta_ = 1.0, sin_theta_ = 0.0;
  double cos_bound_ = -std::numeric_limits<double>::infinity();
};

}  // namespace arbor

#endif  // ARBOR_CORE_ENGINE_SENSOR_VIEW_H_
