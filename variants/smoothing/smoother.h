// The Ceres full-SLAM smoother (DESIGN.md §5): the accuracy reference beside every FastSLAM result.
// Plain C++ API; Ceres itself stays inside variants/smoothing/*.cc, so including this costs nothing.
#ifndef ARBOR_VARIANTS_SMOOTHING_SMOOTHER_H_
#define ARBOR_VARIANTS_SMOOTHING_SMOOTHER_H_

#include <cstdint>
#include <map>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "core/enum_names.h"
#include "core/types/scenario.h"
#include "variants/smoothing/factor_graph.h"

namespace arbor {

enum class SmootherLoss { kNone, kHuber, kCauchy };
enum class SmootherLinearSolver { kSparseSchur, kSparseNormalCholesky };

// The CLI's names (core/enum_names.h).
template <> inline constexpr EnumNames<SmootherLoss, 3> kNamesOf<SmootherLoss>{
    {{SmootherLoss::kNone, "none"}, {SmootherLoss::kHuber, "huber"}, {SmootherLoss::kCauchy, "cauchy"}}};
template <> inline constexpr EnumNames<SmootherLinearSolver, 2> kNamesOf<SmootherLinearSolver>{
    {{SmootherLinearSolver::kSparseSchur, "sparse-schur"},
     {SmootherLinearSolver::kSparseNormalCholesky, "sparse-normal-cholesky"}}};

struct SmootherOptions {
  // Poses: one per scan (and the last step), with the controls between composed into one motion factor.
  // With pose_at_truth_steps, also one at every step with a ground-truth pose (UTIAS: 50,000 Vicon-time
  // poses instead of 1,000 scans, and minutes instead of seconds); the evaluation does not need it, since the
  // trajectory is filled in between scans from the controls (densify_trajectory).
  bool pose_at_truth_steps = false;
  // Robust loss on the landmark observations only (a wrong association is an outlier there; odometry has
  // none). scale: the residual, in standard deviations, where the loss leaves the quadratic.
  SmootherLoss loss = SmootherLoss::kNone;
  double loss_scale = 1.0;
  // Both measured in results/smoothing/. SPARSE_SCHUR eliminates an independent set of variables that
  // Ceres chooses, or exactly the landmarks with schur_landmarks_first (the bundle-adjustment choice;
  // ~14x slower on Victoria Park, whose trees are re-seen over long spans and so couple distant poses).
  SmootherLinearSolver linear_solver = SmootherLinearSolver::kSparseNormalCholesky;
  bool schur_landmarks_first = false;
  int max_iterations = 100;
  // Trust-region strategy: Levenberg-Marquardt (false) or Powell's dogleg (true); non-monotonic steps let
  // the cost rise for a few iterations, which helps when dead reckoning starts far from the optimum.
  bool dogleg = false;
  bool nonmonotonic_steps = false;
  // Warm start in the manner of incremental smoothing (iSAM): solve the graph restricted to the first
  // warm_start_poses poses, then grow it by that many poses at a time, initialising each new pose by
  // composing its odometry onto the solved ones and each new landmark from its first observation, with at
  // most warm_start_iterations per intermediate solve; the last solve is the full problem. Dead reckoning
  // over a long run (Victoria Park) starts batch LM in a poor basin; growing the problem avoids it.
  // 0: one batch solve from the graph's initial values (use this with an initial guess, e.g. FastSLAM's).
  // smooth() turns it off when given an initial trajectory.
  int warm_start_poses = 500;
  int warm_start_iterations = 10;
  int threads = 1;
  // Marginal covariance of every pose (ceres::Covariance, sparse QR of the Jacobian at the solution), for
  // the NEES of `arbor smooth`; skipped above this many poses, where it costs more than the solve.
  int pose_marginals_max_poses = 10000;
  double function_tolerance = 1e-10;
  double gradient_tolerance = 1e-12;
  double parameter_tolerance = 1e-10;
  // Added to the covariance of every chained-motion factor: a short or standing interval's process noise is
  // nearly singular (only the floor density moves a standing robot sideways); this keeps the factor's
  // square-root information finite without changing it where the motion noise is larger (m^2, m^2, rad^2).
  Vec3 motion_floor_variance{1e-8, 1e-8, 1e-10};
  // Floor on the first-pose prior's standard deviations (a scenario whose initial pose is exact has zero).
  double prior_floor_sigma = 1e-6;
  bool verbose = false;  // Ceres's per-iteration log on stdout

  // False (with the reason) for options no solve can use.
  bool validate(std::string* why) const;
};

// Which landmark each measurement observes: landmark_ids[step][measurement], kUnassociated to leave a
// measurement out (clutter, or a decision the source did not make).
inline constexpr std::int64_t kUnassociated = -1;
struct SmootherAssociations {
  std::string source = "known";
  std::vector<std::vector<std::int64_t>> landmark_ids;

  // Ground truth: Measurement::truth_id where >= 0 (clutter and unknown ids are left out).
  static SmootherAssociations from_truth(const Scenario& scenario);
  std::size_t associated_count() const;
};

// Optional initial values (e.g. a FastSLAM result): poses matched to the graph's poses by nearest time;
// landmarks by association id. Anything not given comes from dead reckoning and first sightings.
struct SmootherInitialGuess {
  std::vector<std::pair<double, Pose2>> trajectory;  // (time_s, pose), sorted by time
  std::map<std::int64_t, Vec2> landmarks;
};

// Builds the graph (pose choice and factor construction are documented in factor_graph.cc). Throws
// InputError when the associations do not match the scenario's shape.
FactorGraph build_factor_graph(const Scenario& scenario, const SmootherAssociations& associations,
                               const SmootherOptions& options, const SmootherInitialGuess* guess = nullptr);

struct SmootherSummary {
  double build_time_s = 0.0;   // scenario -> factor graph -> Ceres problem
  double solve_time_s = 0.0;   // ceres::Solve, preprocessing included (wall clock)
  double solve_cpu_s = 0.0;    // CPU time of the whole process (all threads) over the same span: on a busy
                               // machine, with threads = 1, the better estimate of the unloaded wall time
  int iterations = 0;
  double initial_cost = 0.0;   // Ceres's cost: half the sum of squared whitened (robustified) residuals
  double final_cost = 0.0;
  double gradient_max_norm = 0.0;  // at the solution, evaluated after the solve
  std::string termination;         // CONVERGENCE, NO_CONVERGENCE, FAILURE, ...
  bool usable = false;             // Ceres's IsSolutionUsable()
  std::string linear_solver;
  std::string report;              // Ceres's BriefReport()
  int poses = 0, landmarks = 0, factors = 0, residuals = 0, parameters = 0;
  bool pose_marginals = false;     // whether SmoothedPose::covariance holds the marginals
  double marginals_time_s = 0.0;   // their computation (wall clock), not part of solve_time_s
};

struct SmoothedPose {
  double time_s = 0.0;
  int step = -1;
  std::int64_t source_id = 0;
  Pose2 pose;
  Mat3 covariance = Mat3::Zero();  // marginal (x, y, theta), when summary.pose_marginals
};
struct SmoothedLandmark {
  std::int64_t id = 0;
  Vec2 position = Vec2::Zero();
  // Covariance conditional on the smoothed poses: (sum_k H_k^T Sigma_k^-1 H_k)^-1 over its observations,
  // H_k = d z_k / d landmark. Smaller than the full marginal (pose uncertainty is left out); cheap.
  Mat2 covariance = Mat2::Identity();
  int observations = 0;
};
struct SmootherResult {
  std::vector<SmoothedPose> poses;  // in time order
  std::vector<SmoothedLandmark> landmarks;
  SmootherSummary summary;
};

// Solves a graph from its initial values.
SmootherResult solve_factor_graph(const FactorGraph& graph, const SmootherOptions& options);

// build_factor_graph + solve_factor_graph; summary.build_time_s includes both builds. With an initial
// trajectory in `guess` the warm start is off: the guess is the starting point.
SmootherResult smooth(const Scenario& scenario, const SmootherAssociations& associations,
                      const SmootherOptions& options, const SmootherInitialGuess* guess = nullptr);

// The whitened residuals of every factor at `values` (robust loss not applied), in the order betweens,
// range_bearings, points, priors; and, when jacobian is given, d residual / d (poses..., landmarks...) as a
// dense matrix (column 3i+k is pose i's k-th coordinate, then 2 per landmark). For tests on small graphs.
Eigen::VectorXd evaluate_residuals(const FactorGraph& graph, const GraphValues& values,
                                   Eigen::MatrixXd* jacobian = nullptr);

}  // namespace arbor

#endif  // ARBOR_VARIANTS_SMOOTHING_SMOOTHER_H_
