// Where a particle's sensor could see: the query box and view that pick a scan's association candidates, and
// the narrower view inside which a landmark that goes unseen counts as missed (existence evidence).
#ifndef ARBOR_CORE_ENGINE_SENSOR_VIEW_H_
#define ARBOR_CORE_ENGINE_SENSOR_VIEW_H_

#include <algorithm>
#include <cmath>

#include "core/engine/fastslam_options.h"
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
      : max_range_m_(sensor.max_range_m), min_range_m_(sensor.min_range_m), fov_rad_(sensor.fov_rad), margins_(margins) {}

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
    return in_candidate_range(z.x(), margin) &&
           std::abs(z.y()) <= 0.5 * fov_rad_ + margins_.candidate_bearing_rad + margin.bearing_rad;
  }
  // Whether a landmark predicted at z lies well inside the view: unseen there, it was missed.
  bool in_evidence_range(double range_m) const {
    return range_m <= max_range_m_ - margins_.evidence_range_m && range_m >= min_range_m_ + margins_.evidence_range_m;
  }
  bool in_evidence_view(const Vec2& z) const {
    return in_evidence_range(z.x()) && std::abs(z.y()) <= 0.5 * fov_rad_ - margins_.evidence_bearing_rad;
  }

 private:
  double max_range_m_, min_range_m_, fov_rad_;
  SensorViewMargins margins_;
};

}  // namespace arbor

#endif  // ARBOR_CORE_ENGINE_SENSOR_VIEW_H_
