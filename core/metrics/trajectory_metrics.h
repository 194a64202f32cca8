// Trajectory and map accuracy (DESIGN.md §7): ATE RMSE with optional SE(2) alignment, landmark RMSE by
// ground-truth association, and pose NEES.
#ifndef ARBOR_CORE_METRICS_TRAJECTORY_METRICS_H_
#define ARBOR_CORE_METRICS_TRAJECTORY_METRICS_H_

#include <optional>
#include <vector>

#include "core/types/landmark.h"
#include "core/types/timed_pose.h"
#include "core/types/scenario.h"

namespace arbor {

// Linear interpolation of a time-ordered trajectory at time t (heading along the shorter arc);
// nullopt outside its time span.
std::optional<Pose2> interpolate_pose(const std::vector<TimedPose>& trajectory, double t);

// The rigid motion (rotation, translation) minimising sum |R a_i + t - b_i|^2: the closed-form 2-D
// Procrustes solution (Umeyama 1991 without scale). Returned as the pose world_T_aligned.
Pose2 align_se2(const std::vector<Vec2>& a, const std::vector<Vec2>& b);

struct AteResult {
  double rmse_m = 0.0;
  int matched = 0;
  Pose2 alignment;  // identity unless aligned
};

// Position RMSE of the estimate against truth samples at the truth's times (estimate interpolated).
// With align = true, the estimate is first moved by the SE(2) alignment that fits it best to the truth
// (for real data, whose frame is arbitrary). nullopt when no truth time falls inside the estimate.
std::optional<AteResult> absolute_trajectory_error(const std::vector<TimedPose>& estimate,
                                                   const std::vector<TimedPosition>& truth, bool align);

// Truth positions of the scenario's steps that carry a truth pose.
std::vector<TimedPosition> truth_positions(const Scenario& scenario);

// RMSE of every estimated landmark created from a real landmark against that landmark's true position.
std::optional<double> landmark_rmse(const std::vector<Landmark>& map, const std::vector<TruthLandmark>& truth,
                                    const Pose2& alignment = Pose2{});

// Normalised estimation error squared e^T P^-1 e of a pose estimate (3 dof).
double pose_nees(const Pose2& estimate, const Mat3& covariance, const Pose2& truth);

// The two-sided 95 % interval of a chi-square(3) variable: a consistent filter's single-run pose NEES lies in
// it at 95 % of steps (Bar-Shalom, Li & Kirubarajan 2001, §5.4.2).
struct NeesBand {
  double low, high;
};
inline constexpr NeesBand kNeesBand3Dof95{0.2158, 9.3484};

// The share of values inside [band.low, band.high]; 0 for an empty input.
double fraction_in_band(const std::vector<double>& values, NeesBand band);

// The consistency horizon (issue 41): how many of a run's NEES samples (one per scan with ground truth) come
// before the rolling mean over `window` samples leaves its band for good. The band of a mean of `window`
// chi-square(dof) values is the two-sided 95 % interval of chi-square(dof * window) / window (Bar-Shalom, Li &
// Kirubarajan 2001, §5.4.2). values.size() when the last window lies inside it (consistent to the end), 0 when
// no window does; std::nullopt when there are fewer values than one window.
std::optional<std::size_t> consistency_horizon(const std::vector<double>& nees, int dof = 3, int window = 10);

// Dead reckoning: the scenario's controls applied without noise from the initial pose, at every step.
std::vector<TimedPose> dead_reckoning(const Scenario& scenario);

}  // namespace arbor

#endif  // ARBOR_CORE_METRICS_TRAJECTORY_METRICS_H_
