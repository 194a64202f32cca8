// Names of the motion models, as used in scenario files and on the command line.
#include "core/models/motion_model.h"

namespace arbor {

std::string_view to_string(MotionModelKind kind) {
  switch (kind) {
    case MotionModelKind::kOdometry: return "odometry";
    case MotionModelKind::kVelocity: return "velocity";
    case MotionModelKind::kAckermann: return "ackermann";
  }
  return "?";
}

bool from_string(std::string_view name, MotionModelKind* kind) {
  for (MotionModelKind k : {MotionModelKind::kOdometry, MotionModelKind::kVelocity, MotionModelKind::kAckermann}) {
    if (to_string(k) == name) {
      *kind = k;
      return true;
    }
  }
  return false;
}

}  // namespace arbor
