// The smoother end to end on tiny worlds: more accurate than dead reckoning, at a stationary point of the
// cost (normal equations), independent of the linear solver, robust to a wrong association with a robust
// loss, and well behaved with landmarks seen once or never.
#include <algorithm>
#include <cmath>

#include <Eigen/Cholesky>
#include <gtest/gtest.h>

#include "core/io/input_error.h"

#include "tests/smoothing/tiny_world.h"
#include "variants/smoothing/smoother.h"

namespace arbor {
namespace {

// RMS position error against the scenario's truth at the steps the result has poses for (no alignment:
// both start at the known initial pose).
double position_rmse(const Scenario& s, const std::vector<SmoothedPose>& poses) {
  double sum = 0.0;
  int n = 0;
  for (const SmoothedPose& p : poses) {
    if (p.step < 0 || !s.steps[p.step].truth_pose) continue;
    sum += (p.pose.position() - s.steps[p.step].truth_pose->position()).squaredNorm();
    ++n;
  }
  return std::sqrt(sum / n);
}

double dead_reckoning_rmse(const Scenario& s) {
  const std::vector<Pose2> dr = testing::dead_reckoning(s);
  double sum = 0.0;
  for (std::size_t k = 0; k < dr.size(); ++k) sum += (dr[k].position() - s.steps[k].truth_pose->position()).squaredNorm();
  return std::sqrt(sum / dr.size());
}

double landmark_rmse(const Scenario& s, const std::vector<SmoothedLandmark>& landmarks) {
  double sum = 0.0;
  for (const SmoothedLandmark& l : landmarks) sum += (l.position - s.truth_landmarks.at(l.id).position).squaredNorm();
  return std::sqrt(sum / landmarks.size());
}

TEST(Smoother, MoreAccurateThanDeadReckoningWithTrueAssociation) {
  for (unsigned seed : {1u, 2u, 3u}) {
    testing::TinyWorldOptions o;
    o.seed = seed;
    const Scenario s = testing::make_tiny_world(o);
    const SmootherResult r = smooth(s, SmootherAssociations::from_truth(s), SmootherOptions{});
    ASSERT_TRUE(r.summary.usable) << r.summary.report;
    EXPECT_EQ(r.summary.termination, "CONVERGENCE") << r.summary.report;
    EXPECT_EQ(r.poses.size(), s.steps.size() + 1);
    EXPECT_EQ(r.landmarks.size(), s.truth_landmarks.size());
    const double smoothed = position_rmse(s, r.poses), dr = dead_reckoning_rmse(s);
    EXPECT_LT(smoothed, 0.5 * dr) << "seed " << seed;
    EXPECT_LT(landmark_rmse(s, r.landmarks), 0.3) << "seed " << seed;
    EXPECT_LT(r.summary.final_cost, r.summary.initial_cost);
  }
}

TEST(Smoother, SolutionSatisfiesTheNormalEquations) {
  const Scenario s = testing::make_tiny_world({});
  const SmootherOptions options;
  const FactorGraph graph = build_factor_graph(s, SmootherAssociations::from_truth(s), options);
  const SmootherResult r = solve_factor_graph(graph, options);
  GraphValues solution;
  for (const SmoothedPose& p : r.poses) solution.poses.push_back(p.pose);
  for (const SmoothedLandmark& l : r.landmarks) solution.landmarks.push_back(l.position);
  Eigen::MatrixXd J0, J;
  const Eigen::VectorXd r0 = evaluate_residuals(graph, initial_values(graph), &J0);
  const Eigen::VectorXd res = evaluate_residuals(graph, solution, &J);
  // Gradient of 1/2 |r|^2 is J^T r: zero at a minimum, up to the solver's tolerances.
  const double g0 = (J0.transpose() * r0).cwiseAbs().maxCoeff();
  const double g = (J.transpose() * res).cwiseAbs().maxCoeff();
  EXPECT_GT(g0, 1.0);
  EXPECT_LT(g, 1e-6 * g0);
  EXPECT_LT(r.summary.gradient_max_norm, 1e-6 * g0);
  EXPECT_NEAR(0.5 * res.squaredNorm(), r.summary.final_cost, 1e-9 * r.summary.final_cost);
  // And a minimum, not a saddle: J^T J is positive definite (the prior fixes the gauge).
  Eigen::LLT<Eigen::MatrixXd> llt(J.transpose() * J);
  EXPECT_EQ(llt.info(), Eigen::Success);
}

TEST(Smoother, LinearSolversAgree) {
  const Scenario s = testing::make_tiny_world({});
  SmootherOptions schur, cholesky;
  schur.linear_solver = SmootherLinearSolver::kSparseSchur;
  cholesky.linear_solver = SmootherLinearSolver::kSparseNormalCholesky;
  const SmootherAssociations a = SmootherAssociations::from_truth(s);
  const SmootherResult r1 = smooth(s, a, schur), r2 = smooth(s, a, cholesky);
  EXPECT_EQ(r1.summary.linear_solver, "SPARSE_SCHUR");
  EXPECT_EQ(r2.summary.linear_solver, "SPARSE_NORMAL_CHOLESKY");
  ASSERT_EQ(r1.poses.size(), r2.poses.size());
  for (std::size_t i = 0; i < r1.poses.size(); ++i)
    EXPECT_LT(pose_error(r1.poses[i].pose, r2.poses[i].pose).cwiseAbs().maxCoeff(), 1e-6);
  EXPECT_NEAR(r1.summary.final_cost, r2.summary.final_cost, 1e-8 * r1.summary.final_cost);
}

TEST(Smoother, WarmStartReachesTheBatchOptimum) {
  const Scenario s = testing::make_tiny_world({});
  const FactorGraph g = build_factor_graph(s, SmootherAssociations::from_truth(s), SmootherOptions{});
  SmootherOptions batch, warm;
  batch.warm_start_poses = 0;
  warm.warm_start_poses = 20;  // 81 poses: five stages
  warm.warm_start_iterations = 3;
  const SmootherResult a = solve_factor_graph(g, batch), b = solve_factor_graph(g, warm);
  ASSERT_TRUE(b.summary.usable) << b.summary.report;
  EXPECT_NEAR(a.summary.final_cost, b.summary.final_cost, 1e-8 * a.summary.final_cost);
  EXPECT_NEAR(a.summary.initial_cost, b.summary.initial_cost, 1e-9 * a.summary.initial_cost);
  // Same minimum up to the stopping tolerances (a different basin would differ by centimetres or more).
  for (std::size_t i = 0; i < a.poses.size(); ++i)
    EXPECT_LT(pose_error(a.poses[i].pose, b.poses[i].pose).cwiseAbs().maxCoeff(), 1e-4);
  EXPECT_EQ(b.summary.residuals, a.summary.residuals);  // every factor made it into the final problem
}

TEST(Smoother, ChainsControlsBetweenScans) {
  testing::TinyWorldOptions o;
  o.scan_every = 4;
  Scenario s = testing::make_tiny_world(o);
  for (ScenarioStep& step : s.steps)
    if (!step.has_scan) step.truth_pose.reset();  // only scan steps (and the last) become poses
  const SmootherResult r = smooth(s, SmootherAssociations::from_truth(s), SmootherOptions{});
  ASSERT_TRUE(r.summary.usable);
  EXPECT_EQ(r.poses.size(), 1u + 20u + 1u);  // start, 20 scans (steps 0, 4, ..., 76), last step 79
  EXPECT_EQ(r.poses.back().step, 79);
  // Measured 0.39 m (dead reckoning drifts 2.2 m over the loop); a chain that dropped or misweighted the
  // controls between scans lands far above.
  EXPECT_LT(landmark_rmse(s, r.landmarks), 0.5);
}

// One association replaced by a far-away landmark: plain least squares is pulled off; Cauchy is not.
TEST(Smoother, RobustLossResistsAWrongAssociation) {
  const Scenario s = testing::make_tiny_world({});
  SmootherAssociations wrong = SmootherAssociations::from_truth(s);
  int changed = 0;
  for (std::size_t k = 10; k < 14; ++k) {
    for (std::int64_t& id : wrong.landmark_ids[k]) {
      id = (id + 8) % 16;  // the landmark on the opposite side of the ring
      ++changed;
    }
  }
  ASSERT_GT(changed, 3);
  SmootherOptions plain, cauchy;
  cauchy.loss = SmootherLoss::kCauchy;
  cauchy.loss_scale = 3.0;
  const double truth_error = position_rmse(s, smooth(s, SmootherAssociations::from_truth(s), plain).poses);
  const double plain_error = position_rmse(s, smooth(s, wrong, plain).poses);
  const double robust_error = position_rmse(s, smooth(s, wrong, cauchy).poses);
  EXPECT_GT(plain_error, 3.0 * truth_error);
  EXPECT_LT(robust_error, 1.5 * truth_error);
}

TEST(Smoother, LandmarkSeenOnceIsSolvedFromItsOneObservation) {
  testing::TinyWorldOptions o;
  o.steps = 20;
  Scenario s = testing::make_tiny_world(o);
  // A new landmark, id 99, observed exactly once at step 5.
  const Vec2 position(s.steps[5].truth_pose->x + 3.0, s.steps[5].truth_pose->y + 1.0);
  s.truth_landmarks.push_back({99, position});
  Measurement m;
  const Vec2 z = range_bearing_predict(*s.steps[5].truth_pose, position);
  m.range_m = z.x();
  m.bearing_rad = z.y();
  m.truth_id = 99;
  s.steps[5].measurements.push_back(m);
  const SmootherResult r = smooth(s, SmootherAssociations::from_truth(s), SmootherOptions{});
  ASSERT_TRUE(r.summary.usable) << r.summary.report;
  const auto it = std::find_if(r.landmarks.begin(), r.landmarks.end(), [](const auto& l) { return l.id == 99; });
  ASSERT_NE(it, r.landmarks.end());
  EXPECT_EQ(it->observations, 1);
  // With one observation its residual is zero at the optimum: it sits where the smoothed pose 6 sees it.
  const Pose2 seen_from = r.poses[6].pose;  // pose index 6 = step 5 (every step is kept)
  ASSERT_EQ(r.poses[6].step, 5);
  EXPECT_LT((it->position - range_bearing_inverse(seen_from, z)).norm(), 1e-6);
}

TEST(Smoother, LandmarkNeverSeenIsNotAVariable) {
  testing::TinyWorldOptions o;
  o.steps = 20;
  Scenario s = testing::make_tiny_world(o);
  s.truth_landmarks.push_back({42, Vec2(500.0, 500.0)});  // out of range of everything
  const SmootherResult r = smooth(s, SmootherAssociations::from_truth(s), SmootherOptions{});
  ASSERT_TRUE(r.summary.usable) << r.summary.report;
  for (const SmoothedLandmark& l : r.landmarks) {
    EXPECT_NE(l.id, 42);
    EXPECT_GT(l.observations, 0);
  }
}

TEST(Smoother, ScenarioWithoutMeasurementsIsDeadReckoning) {
  testing::TinyWorldOptions o;
  o.steps = 10;
  Scenario s = testing::make_tiny_world(o);
  for (ScenarioStep& step : s.steps) step.measurements.clear();
  const SmootherResult r = smooth(s, SmootherAssociations::from_truth(s), SmootherOptions{});
  ASSERT_TRUE(r.summary.usable) << r.summary.report;
  EXPECT_TRUE(r.landmarks.empty());
  const std::vector<Pose2> dr = testing::dead_reckoning(s);
  for (std::size_t k = 0; k < dr.size(); ++k)
    EXPECT_LT(pose_error(r.poses[k + 1].pose, dr[k]).cwiseAbs().maxCoeff(), 1e-6);
}

TEST(Smoother, MismatchedAssociationsAreAnInputError) {
  const Scenario s = testing::make_tiny_world({});
  SmootherAssociations a = SmootherAssociations::from_truth(s);
  a.landmark_ids.pop_back();
  EXPECT_THROW(build_factor_graph(s, a, SmootherOptions{}), InputError);
  a = SmootherAssociations::from_truth(s);
  a.landmark_ids[3].push_back(1);
  EXPECT_THROW(build_factor_graph(s, a, SmootherOptions{}), InputError);
}

TEST(Smoother, InitialGuessIsUsed) {
  const Scenario s = testing::make_tiny_world({});
  SmootherInitialGuess guess;
  guess.trajectory.push_back({s.start_time_s, s.initial_pose});
  for (const ScenarioStep& step : s.steps) guess.trajectory.push_back({step.time_s, *step.truth_pose});
  for (const TruthLandmark& l : s.truth_landmarks) guess.landmarks[l.id] = l.position;
  const FactorGraph g = build_factor_graph(s, SmootherAssociations::from_truth(s), SmootherOptions{}, &guess);
  EXPECT_NEAR(g.poses[40].initial.x, s.steps[39].truth_pose->x, 1e-12);
  EXPECT_NEAR(g.landmarks[0].initial.x(), s.truth_landmarks.at(g.landmarks[0].id).position.x(), 1e-12);
  const SmootherResult from_truth = solve_factor_graph(g, SmootherOptions{});
  const SmootherResult from_dr = smooth(s, SmootherAssociations::from_truth(s), SmootherOptions{});
  EXPECT_NEAR(from_truth.summary.final_cost, from_dr.summary.final_cost, 1e-6 * from_dr.summary.final_cost);
  EXPECT_LT(from_truth.summary.initial_cost, from_dr.summary.initial_cost);
}

TEST(SmootherOptions, ValidateRejectsNonsense) {
  std::string why;
  SmootherOptions o;
  EXPECT_TRUE(o.validate(&why));
  o.loss_scale = 0.0;
  EXPECT_FALSE(o.validate(&why));
  EXPECT_NE(why.find("loss scale"), std::string::npos);
  o = SmootherOptions{};
  o.threads = 0;
  EXPECT_FALSE(o.validate(&why));
  SmootherLoss loss;
  SmootherLinearSolver solver;
  EXPECT_TRUE(from_string("cauchy", &loss));
  EXPECT_EQ(loss, SmootherLoss::kCauchy);
  EXPECT_FALSE(from_string("tukey", &loss));
  EXPECT_TRUE(from_string("sparse-normal-cholesky", &solver));
  EXPECT_EQ(solver, SmootherLinearSolver::kSparseNormalCholesky);
}

}  // namespace
}  // namespace arbor
