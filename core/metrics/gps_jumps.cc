// GPS jump rejection by an implied-speed test against the last accepted fix.
#include "core/metrics/gps_jumps.h"

namespace arbor {

std::vector<TimedPosition> drop_gps_jumps(const std::vector<TimedPosition>& track, double max_speed_mps, double slack_m,
                                          int* dropped) {
  std::vector<TimedPosition> kept;
  kept.reserve(track.size());
  for (const TimedPosition& fix : track) {
    if (!kept.empty()) {
      const double dt = fix.time_s - kept.back().time_s;
      if ((fix.position - kept.back().position).norm() > max_speed_mps * dt + slack_m) continue;
    }
    kept.push_back(fix);
  }
  if (dropped) *dropped = static_cast<int>(track.size() - kept.size());
  return kept;
}

}  // namespace arbor
