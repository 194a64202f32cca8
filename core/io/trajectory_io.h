// Trajectories in the TUM format (`t x y z qx qy qz qw`, one pose per line), readable by evo and others,
// and maps as CSV. Numbers use shortest round-trip formatting, so equal estimates give equal bytes.
#ifndef ARBOR_CORE_IO_TRAJECTORY_IO_H_
#define ARBOR_CORE_IO_TRAJECTORY_IO_H_

#include <string>
#include <vector>

#include "core/types/landmark.h"
#include "core/types/timed_pose.h"

namespace arbor {

// Timestamps strictly ascending, as evo requires: of the poses that share a time only the last is written.
// The trajectory's times must not decrease (checked).
std::string format_tum(const std::vector<TimedPose>& trajectory);
void write_tum(const std::string& path, const std::vector<TimedPose>& trajectory);
// Throws InputError naming file, line and field.
std::vector<TimedPose> read_tum(const std::string& path);

// Header: id,x,y,cov_xx,cov_xy,cov_yy,log_odds,signature,truth_label
std::string format_map_csv(const std::vector<Landmark>& map);
void write_map_csv(const std::string& path, const std::vector<Landmark>& map);
// Throws InputError naming file, line and field: ids must be unique and in LandmarkId's range, covariances
// positive definite, truth_label -1 or a true id.
std::vector<Landmark> read_map_csv(const std::string& path);

}  // namespace arbor

#endif  // ARBOR_CORE_IO_TRAJECTORY_IO_H_
