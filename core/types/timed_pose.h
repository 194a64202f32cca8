// Timed states: an estimated or true pose, and a position-only fix (GPS) at its own time.
#ifndef ARBOR_CORE_TYPES_TIMED_POSE_H_
#define ARBOR_CORE_TYPES_TIMED_POSE_H_

#include "core/math/eigen_types.h"
#include "core/math/pose2.h"

namespace arbor {

struct TimedPose {
  double time_s = 0.0;
  Pose2 pose;
};

// A position-only evaluation track (GPS), at its own times.
struct TimedPosition {
  double time_s = 0.0;
  Vec2 position = Vec2::Zero();
};

}  // namespace arbor

#endif  // ARBOR_CORE_TYPES_TIMED_POSE_H_
