// Factor graph -> ceres::Problem -> solution. The only translation unit that assembles Ceres problems.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <memory>
#include <vector>

#include <Eigen/LU>
#include <ceres/ceres.h>

#include "core/check.h"
#include "core/io/field_limits.h"
#include "core/models/range_bearing_model.h"
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
    problem.AddResidualBlock(internal::cost_of(f), nullptr, data.pose(f.from), data.pose(f.to));
  for (const RangeBearingFactor& f : graph.range_bearings)
    problem.AddResidualBlock(internal::cost_of(f), loss, data.pose(f.pose), data.landmark(f.landmark));
  for (const PointFactor& f : graph.points)
    problem.AddResidualBlock(internal::cost_of(f), loss, data.pose(f.pose), data.landmark(f.landmark));
  for (const PosePriorFactor& f : graph.priors)
    problem.AddResidualBlock(internal::cost_of(f), nullptr, data.pose(f.pose));
}

ceres::Solver::Options make_solver_options(const SmootherOptions& options) {
  ceres::Solver::Options solver_options;
  solver_options.minimizer_type = ceres::TRUST_REGION;
  solver_options.trust_region_strategy_type = options.dogleg ? ceres::DOGLEG : ceres::LEVENBERG_MARQUARDT;
  solver_options.use_nonmonotonic_steps = options.nonmonotonic_steps;
  solver_options.max_num_iterations = options.max_iterations;
  solver_options.num_threads = options.threads;
  solver_options.function_tolerance = options.function_tolerance;
  solver_options.gradient_tolerance = options.gradient_tolerance;
  solver_options.parameter_tolerance = options.parameter_tolerance;
  solver_options.minimizer_progress_to_stdout = options.verbose;
  solver_options.logging_type = options.verbose ? ceres::PER_MINIMIZER_ITERATION : ceres::SILENT;
  solver_options.linear_solver_type = options.linear_solver == SmootherLinearSolver::kSparseSchur
                                          ? ceres::SPARSE_SCHUR
                                          : ceres::SPARSE_NORMAL_CHOLESKY;
  return solver_options;
}

// SPARSE_SCHUR with SmootherOptions::schur_landmarks_first: eliminate exactly the landmarks (no two share a
// factor, so they form an independent set). Otherwise Ceres picks its own independent set to eliminate.
void set_landmarks_first(ProblemData& data, const ceres::Problem& problem, const SmootherOptions& options,
                         ceres::Solver::Options& solver_options) {
  if (solver_options.linear_solver_type != ceres::SPARSE_SCHUR || !options.schur_landmarks_first) return;
  auto ordering = std::make_shared<ceres::ParameterBlockOrdering>();
  for (int j = 0; j < data.landmark_count; ++j)
    if (problem.HasParameterBlock(data.landmark(j))) ordering->AddElementToGroup(data.landmark(j), 0);
  if (ordering->NumElements() == 0) return;  // nothing to eliminate: let Ceres choose
  for (int i = 0; i < data.pose_count; ++i)
    if (problem.HasParameterBlock(data.pose(i))) ordering->AddElementToGroup(data.pose(i), 1);
  solver_options.linear_solver_ordering = ordering;
}

// The warm start of SmootherOptions::warm_start_poses: adds the graph's factors stage by stage (stage =
// highest pose index touched / chunk) into one growing problem, initialising variables as they appear.
class WarmStart {
 public:
  WarmStart(const FactorGraph& graph, ProblemData& data, ceres::LossFunction* loss, ceres::Problem& problem)
      : graph_(graph), data_(data), loss_(loss), problem_(problem), pose_ready_(data.pose_count, false),
        landmark_ready_(data.landmark_count, false) {}

  // Adds the factors of the stages up to `stage` not yet added.
  void add_through(int stage, int chunk) {
    for (; prior_ < graph_.priors.size() && graph_.priors[prior_].pose / chunk <= stage; ++prior_) {
      const PosePriorFactor& f = graph_.priors[prior_];
      ready_pose(f.pose);
      problem_.AddResidualBlock(internal::cost_of(f), nullptr, data_.pose(f.pose));
    }
    for (; between_ < graph_.betweens.size(); ++between_) {
      const BetweenFactor& f = graph_.betweens[between_];
      if (std::max(f.from, f.to) / chunk > stage) break;
      ready_pose_via(f);
      problem_.AddResidualBlock(internal::cost_of(f), nullptr, data_.pose(f.from), data_.pose(f.to));
    }
    add_landmark_factors(
        graph_.range_bearings, range_bearing_, stage, chunk,
        [](const Pose2& x, const RangeBearingFactor& f) { return range_bearing_inverse(x, f.z); });
    add_landmark_factors(
        graph_.points, point_, stage, chunk, [](const Pose2& x, const PointFactor& f) { return x.transform(f.p_robot); });
  }

  // True when the factor lists are ordered by stage, which the staged adding above relies on (graphs from
  // build_factor_graph and isam_factor_graph are: factors follow the poses in time order).
  static bool stage_ordered(const FactorGraph& graph) {
    const auto ordered = [](const auto& factors, auto pose_of) {
      for (std::size_t i = 1; i < factors.size(); ++i)
        if (pose_of(factors[i]) < pose_of(factors[i - 1])) return false;
      return true;
    };
    return ordered(graph.betweens, [](const BetweenFactor& f) { return std::max(f.from, f.to); }) &&
           ordered(graph.priors, [](const PosePriorFactor& f) { return f.pose; }) &&
           ordered(graph.range_bearings, [](const RangeBearingFactor& f) { return f.pose; }) &&
           ordered(graph.points, [](const PointFactor& f) { return f.pose; });
  }

 private:
  // The landmark factors of one kind (range-bearing or point) up to `stage`, from factors[next] on. A
  // landmark met for the first time starts where its first factor puts it: initial(pose, factor).
  template <class Factor, class Initial>
  void add_landmark_factors(const std::vector<Factor>& factors, std::size_t& next, int stage, int chunk,
                            const Initial& initial) {
    for (; next < factors.size(); ++next) {
      const Factor& f = factors[next];
      if (f.pose / chunk > stage) break;
      ready_pose(f.pose);
      if (!landmark_ready_[f.landmark]) {
        const double* x = data_.pose(f.pose);
        set_landmark(f.landmark, initial(Pose2{x[0], x[1], x[2]}, f));
      }
      problem_.AddResidualBlock(internal::cost_of(f), loss_, data_.pose(f.pose), data_.landmark(f.landmark));
    }
  }

  // A pose first seen without odometry to a solved pose keeps the graph's initial value.
  void ready_pose(int i) { pose_ready_[i] = true; }

  // The odometry places a new endpoint relative to a solved one (delta, or its inverse when given backwards).
  void ready_pose_via(const BetweenFactor& f) {
    const auto pose = [&](int i) {
      const double* x = data_.pose(i);
      return Pose2{x[0], x[1], x[2]};
    };
    const auto set_pose = [&](int i, const Pose2& p) {
      data_.pose(i)[0] = p.x;
      data_.pose(i)[1] = p.y;
      data_.pose(i)[2] = p.theta;
      pose_ready_[i] = true;
    };
    if (pose_ready_[f.from] && !pose_ready_[f.to]) set_pose(f.to, pose(f.from).compose(f.delta));
    else if (!pose_ready_[f.from] && pose_ready_[f.to]) set_pose(f.from, pose(f.to).compose(f.delta.between(Pose2{})));
    pose_ready_[f.from] = pose_ready_[f.to] = true;
  }

  void set_landmark(int j, const Vec2& m) {
    data_.landmark(j)[0] = m.x();
    data_.landmark(j)[1] = m.y();
    landmark_ready_[j] = true;
  }

  const FactorGraph& graph_;
  ProblemData& data_;
  ceres::LossFunction* loss_;
  ceres::Problem& problem_;
  std::vector<bool> pose_ready_, landmark_ready_;
  std::size_t between_ = 0, prior_ = 0, range_bearing_ = 0, point_ = 0;
};

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
  const bool warm_start = options.warm_start_poses > 0 && data.pose_count > options.warm_start_poses &&
                          WarmStart::stage_ordered(graph);
  double initial_cost = 0.0;
  if (warm_start) {
    // The reported initial cost is the full problem's at the graph's initial values, as without a warm start.
    ceres::Problem full(problem_options);
    ProblemData initial = data;
    add_factors(graph, initial, loss.get(), full);
    full.Evaluate(ceres::Problem::EvaluateOptions(), &initial_cost, nullptr, nullptr, nullptr);
  } else {
    add_factors(graph, data, loss.get(), problem);
  }
  const double build_time = seconds_since(build_start);

  SmootherResult result;
  SmootherSummary& s = result.summary;
  ceres::Solver::Summary ceres_summary;
  const auto solve_start = Clock::now();
  const std::clock_t cpu_start = std::clock();
  if (warm_start) {
    WarmStart stages(graph, data, loss.get(), problem);
    const int chunk = options.warm_start_poses;
    const int last_stage = (data.pose_count - 1) / chunk;
    for (int stage = 0; stage <= last_stage; ++stage) {
      stages.add_through(stage, chunk);
      ceres::Solver::Options solver_options = make_solver_options(options);
      if (stage < last_stage) solver_options.max_num_iterations = options.warm_start_iterations;
      set_landmarks_first(data, problem, options, solver_options);
      ceres::Solve(solver_options, &problem, &ceres_summary);
      s.iterations += static_cast<int>(ceres_summary.iterations.size()) - 1;
    }
  } else {
    ceres::Solver::Options solver_options = make_solver_options(options);
    set_landmarks_first(data, problem, options, solver_options);
    ceres::Solve(solver_options, &problem, &ceres_summary);
    s.iterations = static_cast<int>(ceres_summary.iterations.size()) - 1;  // iteration 0 is the initial point
    initial_cost = ceres_summary.initial_cost;
  }
  s.solve_time_s = seconds_since(solve_start);
  s.solve_cpu_s = static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC;
  s.build_time_s = build_time;
  s.initial_cost = initial_cost;
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
  if (s.usable && data.pose_count <= options.pose_marginals_max_poses) {
    const auto marginals_start = Clock::now();
    ceres::Covariance::Options covariance_options;
    covariance_options.algorithm_type = ceres::SPARSE_QR;  // exact; the gauge prior makes J full rank
    covariance_options.num_threads = options.threads;
    ceres::Covariance covariance(covariance_options);
    std::vector<std::pair<const double*, const double*>> blocks;
    for (int i = 0; i < data.pose_count; ++i) blocks.emplace_back(data.pose(i), data.pose(i));
    if (covariance.Compute(blocks, &problem)) {
      s.pose_marginals = true;
      for (int i = 0; i < data.pose_count; ++i) {
        Eigen::Matrix<double, 3, 3, Eigen::RowMajor> block;
        covariance.GetCovarianceBlock(data.pose(i), data.pose(i), block.data());
        result.poses[i].covariance = block;
      }
    }
    s.marginals_time_s = seconds_since(marginals_start);
  }
  std::vector<int> observations(data.landmark_count, 0);
  std::vector<Mat2> information(data.landmark_count, Mat2::Zero());
  const auto pose_at = [&](int i) { return Pose2{data.pose(i)[0], data.pose(i)[1], data.pose(i)[2]}; };
  const auto landmark_at = [&](int j) { return Vec2(data.landmark(j)[0], data.landmark(j)[1]); };
  for (const RangeBearingFactor& f : graph.range_bearings) {
    Mat2 H;
    range_bearing_predict(pose_at(f.pose), landmark_at(f.landmark), &H);
    information[f.landmark] += H.transpose() * f.covariance.inverse() * H;
    ++observations[f.landmark];
  }
  for (const PointFactor& f : graph.points) {
    const double c = std::cos(data.pose(f.pose)[2]), sn = std::sin(data.pose(f.pose)[2]);
    Mat2 H;  // d (R^T (m - p)) / d m = R^T
    H << c, sn, -sn, c;
    information[f.landmark] += H.transpose() * f.covariance.inverse() * H;
    ++observations[f.landmark];
  }
  result.landmarks.reserve(data.landmark_count);
  for (int j = 0; j < data.landmark_count; ++j) {
    // A landmark seen only from the point it sits on (zero-range measurements) has no information at all:
    // a prior as wide as the format's coordinates keeps its covariance finite (about 1e18 m^2) instead of
    // writing NaN to map.csv. Any landmark observed from elsewhere is not touched.
    if (!(information[j].determinant() > 0.0))
      information[j] += Mat2::Identity() / (scenario_limits::kMaxCoordinate * scenario_limits::kMaxCoordinate);
    Mat2 covariance = information[j].inverse();
    covariance = 0.5 * (covariance + covariance.transpose());
    result.landmarks.push_back({graph.landmarks[j].id, landmark_at(j), covariance, observations[j]});
  }
  return result;
}

SmootherResult smooth(const Scenario& scenario, const SmootherAssociations& associations,
                      const SmootherOptions& options, const SmootherInitialGuess* guess) {
  const auto start = Clock::now();
  const FactorGraph graph = build_factor_graph(scenario, associations, options, guess);
  const double graph_time = seconds_since(start);
  SmootherOptions solve_options = options;
  if (guess != nullptr && !guess->trajectory.empty()) solve_options.warm_start_poses = 0;
  SmootherResult result = solve_factor_graph(graph, solve_options);
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
