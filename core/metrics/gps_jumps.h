// GPS tracks used as truth on real data fail in known ways (Victoria Park: "jumps and regions without gps
// data"). Fixes that imply an impossible speed are dropped before the SE(2) alignment, so one jump does not
// bend the fit of the whole trajectory.
#ifndef ARBOR_CORE_METRICS_GPS_JUMPS_H_
#define ARBOR_CORE_METRICS_GPS_JUMPS_H_

#include <vector>

#include "core/types/scenario.h"

namespace arbor {

// Keeps a fix when it lies within max_speed_mps * dt + slack_m of the last KEPT fix (dt since that fix), so a
// jump and the fixes that stay at the jumped-to place are dropped until the vehicle could have got there.
// The first fix is kept. dropped (optional) receives the number of fixes removed.
std::vector<TimedPosition> drop_gps_jumps(const std::vector<TimedPosition>& track, double max_speed_mps,
                                          double slack_m, int* dropped = nullptr);

}  // namespace arbor

#endif  // ARBOR_CORE_METRICS_GPS_JUMPS_H_
