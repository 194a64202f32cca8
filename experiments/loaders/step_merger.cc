// Time-ordered merge of control readings and scans into steps (zero-order hold of the controls).
#include "experiments/loaders/step_merger.h"

#include <fmt/core.h>

#include "core/io/input_error.h"

namespace arbor {

std::vector<ScenarioStep> merge_controls_and_scans(const std::vector<ControlSample>& controls,
                                                   const std::vector<TimedScan>& scans, const StepMergeOptions& o) {
  std::vector<ScenarioStep> steps;
  steps.reserve(controls.size() + scans.size());
  std::size_t next_control = 0, next_scan = 0;
  // Skip what lies before the start; the last control reading at or before the start is the one in force.
  ControlSample in_force = o.before_first;
  while (next_control < controls.size() && controls[next_control].time_ms <= o.start_ms)
    in_force = controls[next_control++];
  while (next_scan < scans.size() && scans[next_scan].time_ms < o.start_ms) ++next_scan;
  std::int64_t previous_ms = o.start_ms;
  const auto to_seconds = [&](std::int64_t ms) { return (static_cast<double>(ms) - o.origin_ms) / 1000.0; };
  while (next_control < controls.size() || next_scan < scans.size()) {
    const std::int64_t control_ms = next_control < controls.size() ? controls[next_control].time_ms : INT64_MAX;
    const std::int64_t scan_ms = next_scan < scans.size() ? scans[next_scan].time_ms : INT64_MAX;
    const std::int64_t t = std::min(control_ms, scan_ms);
    if (t > o.end_ms) break;
    ScenarioStep step;
    step.time_s = to_seconds(t);
    // dt from the integer clock, so that split intervals add up exactly to the unsplit one.
    step.control = {in_force.u1, in_force.u2, static_cast<double>(t - previous_ms) / 1000.0};
    if (scan_ms == t) {
      if (static_cast<double>(t - in_force.time_ms) > 1000.0 * o.max_control_gap_s)
        throw InputError(o.controls_path, in_force.line, "time",
                         fmt::format("no control reading from t = {:.3f} s to a scan at t = {:.3f} s (over {} s): the "
                                     "file ends or has a hole while the scans go on; converting would hold the last "
                                     "reading throughout",
                                     to_seconds(in_force.time_ms), to_seconds(t), o.max_control_gap_s));
      step.has_scan = true;
      step.measurements = scans[next_scan++].measurements;
    }
    if (control_ms == t) in_force = controls[next_control++];
    previous_ms = t;
    steps.push_back(std::move(step));
  }
  return steps;
}

}  // namespace arbor
