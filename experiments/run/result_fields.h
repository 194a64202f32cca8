// The result.json fields `arbor run` and `arbor smooth` share (DESIGN.md §9), computed in one place so the
// FastSLAM and smoother rows of a table are measured the same way.
#ifndef ARBOR_EXPERIMENTS_RUN_RESULT_FIELDS_H_
#define ARBOR_EXPERIMENTS_RUN_RESULT_FIELDS_H_

#include <optional>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/types/landmark.h"
#include "core/engine/persistent_history.h"
#include "core/types/scenario.h"
#include "core/metrics/trajectory_metrics.h"

namespace arbor {

// Where it came from: commit, host, compiler, build.
nlohmann::json provenance();

nlohmann::json optional_number(const std::optional<double>& v);
// The mean, or null for no values.
nlohmann::json mean_or_null(const std::vector<double>& values);

// What a trajectory is scored against: truth poses in the estimator's frame (simulation, UTIAS), else a GPS
// track (Victoria Park) after SE(2) alignment.
struct EvaluationTruth {
  std::vector<TimedPosition> positions;
  bool align = false;
};
EvaluationTruth evaluation_truth(const Scenario& scenario);

// One trajectory's ATE RMSE in the truth's frame (aligned where the truth asks for it) and SE(2)-aligned, null
// where there is no truth, and the alignment of the first (identity without one).
struct TrajectoryErrors {
  nlohmann::json rmse_m, aligned_rmse_m;
  Pose2 alignment;
};
TrajectoryErrors trajectory_errors(const EvaluationTruth& truth, const std::vector<TimedPose>& trajectory);

// ate_rmse_m, ate_aligned, ate_aligned_rmse_m (SE(2)-aligned, comparable with tools whose frame differs),
// dead_reckoning_ate_m and landmark_rmse_m (in the frame the ATE aligned to); null where there is no truth.
nlohmann::json accuracy_fields(const Scenario& scenario, const EvaluationTruth& truth,
                               const std::vector<TimedPose>& trajectory, const std::vector<Landmark>& map);

}  // namespace arbor

#endif  // ARBOR_EXPERIMENTS_RUN_RESULT_FIELDS_H_
