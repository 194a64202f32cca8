// reference.tum: the trajectory a run is scored against, written beside trajectory.tum so that evo (or any
// tool that reads TUM files) can compare the two without Arbor (docs/evo.md).
#ifndef ARBOR_EXPERIMENTS_RUN_REFERENCE_TRAJECTORY_H_
#define ARBOR_EXPERIMENTS_RUN_REFERENCE_TRAJECTORY_H_

#include <string>
#include <vector>

#include "core/types/scenario.h"
#include "core/types/timed_pose.h"

namespace arbor {

// The same reference as result.json's ATE (evaluation_truth): the steps' truth poses where the scenario has
// them (simulation, UTIAS), else its GPS track (Victoria Park, the car park). A GPS fix has no heading, so its
// rows carry the identity orientation: compare translations only (evo's default, `-r trans_part`).
// Empty when the scenario has neither.
std::vector<TimedPose> reference_trajectory(const Scenario& scenario);

// Writes DIR/reference.tum, or removes one a previous run left there when `reference` is empty, so that a
// directory never pairs a trajectory with another scenario's reference.
void write_reference_tum(const std::vector<TimedPose>& reference, const std::string& dir);

}  // namespace arbor

#endif  // ARBOR_EXPERIMENTS_RUN_REFERENCE_TRAJECTORY_H_
