// A scenario: everything a run consumes, simulated or real, in one in-memory form (the text format is in
// docs/scenario_format.md and core/io/scenario_format.h).
#ifndef ARBOR_CORE_TYPES_SCENARIO_H_
#define ARBOR_CORE_TYPES_SCENARIO_H_

#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "core/math/eigen_types.h"
#include "core/math/pose2.h"
#include "core/models/motion_model.h"
#include "core/models/sensor_model.h"
#include "core/types/timed_pose.h"

namespace arbor {

// Ground-truth id of a measurement.
inline constexpr std::int32_t kTruthUnknown = -2;  // real data without ids
inline constexpr std::int32_t kTruthClutter = -1;  // a spurious measurement (simulation)

struct Measurement {
  double range_m = 0.0;
  double bearing_rad = 0.0;
  float signature = std::numeric_limits<float>::quiet_NaN();  // NaN: none
  std::int32_t truth_id = kTruthUnknown;
  Vec2 z() const { return {range_m, bearing_rad}; }
};

// One time step: a control that moves the robot to time_s, then optionally a scan taken there.
struct ScenarioStep {
  double time_s = 0.0;
  Vec3 control = Vec3::Zero();
  std::optional<Pose2> truth_pose;  // ground truth at time_s, where known
  bool has_scan = false;            // a scan with no measurement still gives negative evidence
  // The scenario file's line of the 'step' record (0: not read from a file), for an error about this step that
  // only the run can see (core/engine/numerical_breakdown.h).
  int source_line = 0;
  std::vector<Measurement> measurements;
};

struct TruthLandmark {
  std::int32_t id = 0;
  Vec2 position = Vec2::Zero();
};

struct Scenario {
  std::map<std::string, std::string> metadata;  // provenance: source, world, seed, ...
  MotionModel motion;
  SensorModel sensor;
  Pose2 initial_pose;
  Vec3 initial_sigma = Vec3::Zero();  // std dev of the initial pose (x [m], y [m], theta [rad])
  double start_time_s = 0.0;
  std::vector<TruthLandmark> truth_landmarks;
  std::vector<TimedPosition> truth_track;
  std::vector<ScenarioStep> steps;

  bool has_truth_poses() const {
    for (const auto& s : steps)
      if (s.truth_pose) return true;
    return false;
  }
};

}  // namespace arbor

#endif  // ARBOR_CORE_TYPES_SCENARIO_H_
