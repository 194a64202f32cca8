// Factor graph -> ceres::Problem -> solution. The only translation unit that assembles Ceres problems.
#include <chrono>
#include <memory>
#include <vector>

#include <ceres/ceres.h>

#include "core/check.h"
#include "variants/smoothing/factors.h"
#include "variants/smoothing/smoother.h"

namespace arbor {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// Parameter storage: 3 doubles per pose, then 2 per landmark, in one contiguous block, so the dense
// Jacobian columns of evaluate_residuals follow the same order.
struct ProblemData {
  std::vector<double> values;
  int pose_count = 0;
  int landmark_count = 0;
  double* pose(int i) { return values.data() + 3 * i; }
  double* landmark(int j) { return values.data() + 3 * pose_count + 2 * j; }
};

ProblemData load_values(const FactorGraph& graph, const GraphValues& values) {
  ARBOR_CHECK(values.poses.size() == graph.poses.size() && values.landmarks.size() == graph.landmarks.size(),
              "values do not match the graph");
  ProblemData data;
  data.pose_count = static_cast<int>(graph.poses.size());
  data.landmark_count = static_cast<int>(graph.landmarks.size());
  data.values.resize(3 * data.pose_count + 2 * data.landmark_count);
  for (int i = 0; i < data.pose_count; ++i) {
    data.pose(i)[0] = values.poses[i].x;
    data.pose(i)[1] = values.poses[i].y;
    data.pose(i)[2] = values.poses[i].theta;
  }
  for (int j = 0; j < data.landmark_count; ++j) {
    data.landmark(j)[0] = values.landmarks[j].x();
    data.landmark(j)[1] = values.landmarks[j].y();
  }
  return data;
}

// loss: applied to landmark observations only (nullptr: plain least squares). The problem takes ownership
// of one shared loss object.
ceres::LossFunction* make_loss(const SmootherOptions& options) {
  switch (options.loss) {
    case SmootherLoss::kNone: return nullptr;
    case SmootherLoss::kHuber: return new ceres::HuberLoss(options.loss_scale);
    case SmootherLoss::kCauchy: return new ceres::CauchyLoss(options.loss_scale);
  }
  return nullptr;
}

// Adds every factor of the graph, in the residual order evaluate_residuals documents. Parameter blocks
// are added in storage order first, so Problem::Evaluate's columns match ProblemData's layout. A landmark
// without any factor cannot occur (landmarks are created from observations); a pose without factors keeps
// its initial value (Ceres leaves a block no residual touches alone).
void add_factors(const FactorGraph& graph, ProblemData& data, ceres::LossFunction* loss, ceres::Problem& problem) {
  for (int i = 0; i < data.pose_count; ++i) problem.AddParameterBlock(data.pose(i), 3);
  for (int j = 0; j < data.landmark_count; ++j) problem.AddParameterBlock(data.landmark(j), 2);
  for (const BetweenFactor& f : graph.betweens)
    problem.AddResidualBlock(internal::BetweenError::create(f), nullptr, data.pose(f.from), data.pose(f.to));
  for (const RangeBearingFactor& f : graph.range_bearings)
    problem.AddResidualBlock(internal::RangeBearingError::create(f), loss, data.pose(f.pose),
                             data.landmark(f.landmark));
  for (const PointFactor& f : graph.points)
    problem.AddResidualBlock(internal::PointError::create(f), loss, data.pose(f.pose), data.landmark(f.landmark));
  for (const PosePriorFactor& f : graph.priors)
    problem.AddResidualBlock(internal::PosePriorError::create(f), nullptr, data.pose(f.pose));
}

}  // namespace

SmootherResult solve_factor_graph(const FactorGraph& graph, const SmootherOptions& options) {
  std::string why;
  ARBOR_CHECK(options.validate(&why), "invalid smoother options: {}", why);
  const auto build_start = Clock::now();
  ProblemData data = load_values(graph, initial_values(graph));
  ceres::Problem::Options problem_options;
  problem_options.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  std::unique_ptr<ceres::LossFunction> loss(make_loss(options));
  ceres::Problem problem(problem_options);
  add_factors(graph, data, loss.get(), problem);

  ceres::Solver::Options solver_options;
  solver_options.minimizer_type = ceres::TRUST_REGION;
  solver_options.trust_region_strategy_type = ceres::LEVENBERG_MARQUARDT;
  solver_options.max_num_iterations = options.max_iterations;
  solver_options.num_threads = options.threads;
  solver_options.function_tolerance = options.function_tolerance;
  solver_options.gradient_tolerance = options.gradient_tolerance;
  solver_options.parameter_tolerance = options.parameter_tolerance;
  solver_options.minimizer_progress_to_stdout = options.verbose;
  solver_options.logging_type = options.verbose ? ceres::PER_MINIMIZER_ITERATION : ceres::SILENT;
  if (options.linear_solver == SmootherLinearSolver::kSparseSchur) {
    solver_options.linear_solver_type = ceres::SPARSE_SCHUR;
    // Eliminate the landmarks first: no two share a factor, so they form an independent set, and the
    // reduced system couples only the poses that saw a common landmark.
    if (data.landmark_count > 0) {
      auto ordering = std::make_shared<ceres::ParameterBlockOrdering>();
      for (int j = 0; j < data.landmark_count; ++j) ordering->AddElementToGroup(data.landmark(j), 0);
      for (int i = 0; i < data.pose_count; ++i) ordering->AddElementToGroup(data.pose(i), 1);
      solver_options.linear_solver_ordering = ordering;
    }
  } else {
    solver_options.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
  }
  const double build_time = seconds_since(build_start);

  ceres::Solver::Summary ceres_summary;
  const auto solve_start = Clock::now();
  ceres::Solve(solver_options, &problem, &ceres_summary);
  const double solve_time = seconds_since(solve_start);

  SmootherResult result;
  SmootherSummary& s = result.summary;
  s.build_time_s = build_time;
  s.solve_time_s = solve_time;
  s.iterations = static_cast<int>(ceres_summary.iterations.size()) - 1;  // iteration 0 is the initial point
  s.initial_cost = ceres_summary.initial_cost;
  s.final_cost = ceres_summary.final_cost;
  s.termination = ceres::TerminationTypeToString(ceres_summary.termination_type);
  s.usable = ceres_summary.IsSolutionUsable();
  s.linear_solver = ceres::LinearSolverTypeToString(ceres_summary.linear_solver_type_used);
  s.report = ceres_summary.BriefReport();
  s.poses = data.pose_count;
  s.landmarks = data.landmark_count;
  s.factors = static_cast<int>(graph.factor_count());
  s.residuals = problem.NumResiduals();
  s.parameters = problem.NumParameters();
  std::vector<double> gradient;
  double cost = 0.0;
  problem.Evaluate(ceres::Problem::EvaluateOptions(), &cost, nullptr, &gradient, nullptr);
  for (double g : gradient) s.gradient_max_norm = std::max(s.gradient_max_norm, std::abs(g));

  result.poses.reserve(data.pose_count);
  for (int i = 0; i < data.pose_count; ++i) {
    const GraphPose& p = graph.poses[i];
    result.poses.push_back({p.time_s, p.step, p.source_id,
                            Pose2::from_vector(Vec3(data.pose(i)[0], data.pose(i)[1], data.pose(i)[2]))});
  }
  std::vector<int> observations(data.landmark_count, 0);
  for (const RangeBearingFactor& f : graph.range_bearings) ++observations[f.landmark];
  for (const PointFactor& f : graph.points) ++observations[f.landmark];
  result.landmarks.reserve(data.landmark_count);
  for (int j = 0; j < data.landmark_count; ++j)
    result.landmarks.push_back({graph.landmarks[j].id, Vec2(data.landmark(j)[0], data.landmark(j)[1]), observations[j]});
  return result;
}

SmootherResult smooth(const Scenario& scenario, const SmootherAssociations& associations,
                      const SmootherOptions& options, const SmootherInitialGuess* guess) {
  const auto start = Clock::now();
  const FactorGraph graph = build_factor_graph(scenario, associations, options, guess);
  const double graph_time = seconds_since(start);
  SmootherResult result = solve_factor_graph(graph, options);
  result.summary.build_time_s += graph_time;
  return result;
}

Eigen::VectorXd evaluate_residuals(const FactorGraph& graph, const GraphValues& values, Eigen::MatrixXd* jacobian) {
  ProblemData data = load_values(graph, values);
  ceres::Problem problem;
  add_factors(graph, data, nullptr, problem);
  std::vector<double> residuals;
  ceres::CRSMatrix crs;
  double cost = 0.0;
  problem.Evaluate(ceres::Problem::EvaluateOptions(), &cost, &residuals, nullptr, jacobian ? &crs : nullptr);
  if (jacobian) {
    jacobian->setZero(crs.num_rows, crs.num_cols);
    for (int r = 0; r < crs.num_rows; ++r)
      for (int k = crs.rows[r]; k < crs.rows[r + 1]; ++k) (*jacobian)(r, crs.cols[k]) = crs.values[k];
  }
  return Eigen::Map<Eigen::VectorXd>(residuals.data(), static_cast<Eigen::Index>(residuals.size()));
}

}  // namespace arbor
