// Names of the motion models, as used in scenario files and on the command line.
#include "core/models/motion_model.h"

#include "core/enum_names.h"

namespace arbor {
namespace {
constexpr EnumNames<MotionModelKind, 3> kMotionModelNames{{{MotionModelKind::kOdometry, "odometry"},
                                                          {MotionModelKind::kVelocity, "velocity"},
                                                          {MotionModelKind::kAckermann, "ackermann"}}};
}  // namespace

std::string_view to_string(MotionModelKind kind) { return name_of(kMotionModelNames, kind); }
bool from_string(std::string_view name, MotionModelKind* kind) { return value_named(kMotionModelNames, name, kind); }

}  // namespace arbor
