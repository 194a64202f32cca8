// The result.json fields shared by `arbor run` and `arbor smooth`.
#include "experiments/run/result_fields.h"

#include "core/io/build_info.h"

namespace arbor {

using Json = nlohmann::json;

Json provenance() {
  return {{"commit", git_commit()}, {"host", host_name()}, {"compiler", compiler()}, {"build", build_type()}};
}

Json optional_number(const std::optional<double>& v) { return v ? Json(*v) : Json(nullptr); }

Json mean_or_null(const std::vector<double>& values) {
  if (values.empty()) return nullptr;
  double mean = 0.0;
  for (double v : values) mean += v / values.size();
  return mean;
}

EvaluationTruth evaluation_truth(const Scenario& scenario) {
  EvaluationTruth truth{truth_positions(scenario), false};
  if (truth.positions.empty() && !scenario.truth_track.empty()) truth = {scenario.truth_track, true};
  return truth;
}

namespace {
Json rmse(const std::optional<AteResult>& ate) { return ate ? Json(ate->rmse_m) : Json(nullptr); }
}  // namespace

TrajectoryErrors trajectory_errors(const EvaluationTruth& truth, const std::vector<TimedPose>& trajectory) {
  const auto ate = absolute_trajectory_error(trajectory, truth.positions, truth.align);
  const auto ate_aligned = truth.align ? ate : absolute_trajectory_error(trajectory, truth.positions, true);
  return {rmse(ate), rmse(ate_aligned), ate ? ate->alignment : Pose2{}};
}

Json accuracy_fields(const Scenario& scenario, const EvaluationTruth& truth, const std::vector<TimedPose>& trajectory,
                     const std::vector<Landmark>& map) {
  const TrajectoryErrors ate = trajectory_errors(truth, trajectory);
  const auto ate_dr = absolute_trajectory_error(dead_reckoning(scenario), truth.positions, truth.align);
  return {{"ate_rmse_m", ate.rmse_m},
          {"ate_aligned", truth.align},
          {"ate_aligned_rmse_m", ate.aligned_rmse_m},
          {"dead_reckoning_ate_m", rmse(ate_dr)},
          {"landmark_rmse_m", optional_number(landmark_rmse(map, scenario.truth_landmarks, ate.alignment))}};
}

}  // namespace arbor
