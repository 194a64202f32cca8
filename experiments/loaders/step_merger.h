// Merges a stream of timed control readings with timed scans into scenario steps, the one rule every real
// loader follows: a step ends at every control time and at every scan time (their union, in order).
#ifndef ARBOR_EXPERIMENTS_LOADERS_STEP_MERGER_H_
#define ARBOR_EXPERIMENTS_LOADERS_STEP_MERGER_H_

#include <cstdint>
#include <string>
#include <vector>

#include "core/types/scenario.h"

namespace arbor {

// A control reading (speed and steering, or v and omega) logged at time_ms, in force until the next one.
struct ControlSample {
  std::int64_t time_ms = 0;
  double u1 = 0.0;
  double u2 = 0.0;
  int line = 0;  // in the controls file, for errors
};

// All measurements that share one time stamp.
struct TimedScan {
  std::int64_t time_ms = 0;
  std::vector<Measurement> measurements;
};

struct StepMergeOptions {
  std::int64_t start_ms = 0;       // the scenario's start: steps end strictly after it, or at it for a scan
  std::int64_t end_ms = INT64_MAX;  // nothing after this time
  double origin_ms = 0.0;          // step time_s = (time_ms - origin_ms) / 1000
  ControlSample before_first;      // the control in force before the first reading (u1, u2 only)
  // A scan this long after the control reading in force is an error: the hold would drive the robot on the
  // last reading through the whole stretch (a cut control file converted "fine" and gave 10.96 m ATE instead
  // of 0.67 m). The shipped datasets log controls at 40 Hz (Ackermann) or with gaps of at most 1.03 s (UTIAS).
  double max_control_gap_s = 5.0;
  std::string controls_path;  // named in that error
};

// Steps at the sorted union of control and scan times within [start_ms, end_ms]. Each step's control is
// (u1, u2, dt_s) with the reading in force at the START of its interval (zero-order hold: a reading applies
// from its time stamp until the next one), so a scan inside a control interval splits it in two steps that
// carry the same (u1, u2). A scan at start_ms gives a first step with dt = 0. Both inputs must be sorted by
// strictly increasing time (the loaders check this while reading). Throws InputError (controls_path, the
// line of the reading in force, field "time") at a scan more than max_control_gap_s after that reading.
std::vector<ScenarioStep> merge_controls_and_scans(const std::vector<ControlSample>& controls,
                                                   const std::vector<TimedScan>& scans, const StepMergeOptions& options);

}  // namespace arbor

#endif  // ARBOR_EXPERIMENTS_LOADERS_STEP_MERGER_H_
