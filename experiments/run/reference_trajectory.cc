// The reference trajectory of a scenario, and reference.tum; see reference_trajectory.h.
#include "experiments/run/reference_trajectory.h"

#include <filesystem>
#include <system_error>

#include <fmt/core.h>

#include "core/io/input_error.h"
#include "core/io/trajectory_io.h"

namespace arbor {

std::vector<TimedPose> reference_trajectory(const Scenario& scenario) {
  std::vector<TimedPose> out;
  for (const ScenarioStep& step : scenario.steps)
    if (step.truth_pose) out.push_back({step.time_s, *step.truth_pose});
  if (out.empty())
    for (const TimedPosition& fix : scenario.truth_track)
      out.push_back({fix.time_s, {fix.position.x(), fix.position.y(), 0.0}});
  return out;
}

void write_reference_tum(const std::vector<TimedPose>& reference, const std::string& dir) {
  const std::filesystem::path path = std::filesystem::path(dir) / "reference.tum";
  if (!reference.empty()) return write_tum(path.string(), reference);
  std::error_code error;
  std::filesystem::remove(path, error);
  if (error)
    throw EnvironmentError(path.string(), fmt::format("cannot remove a previous run's reference: {}", error.message()));
}

}  // namespace arbor
