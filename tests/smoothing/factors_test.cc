// The smoother's factors: analytic (autodiff) Jacobians against central differences, wrapped angle
// residuals, and the chained motion factor against direct propagation for every motion model.
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "tests/smoothing/tiny_world.h"
#include "variants/smoothing/smoother.h"

namespace arbor {
namespace {

// A graph with one factor of each kind over two poses and two landmarks. Bearing of the second observation
// sits at -pi + 0.01 while the predicted one is near +pi: the residual must wrap, not jump by 2 pi.
FactorGraph one_of_each() {
  FactorGraph g;
  g.poses = {{0.0, -1, 0, Pose2{1.0, 2.0, 0.3}}, {1.0, 0, 1, Pose2{2.0, 2.5, 3.1}}};
  g.landmarks = {{7, Vec2(4.0, 5.0)}, {9, Vec2(-3.0, 2.4)}};
  Mat3 cov3;
  cov3 << 0.04, 0.01, 0.002, 0.01, 0.09, 0.003, 0.002, 0.003, 0.01;
  Mat2 cov2;
  cov2 << 0.01, 0.001, 0.001, 0.0004;
  g.betweens.push_back({0, 1, Pose2{1.1, 0.2, 2.7}, cov3});
  g.range_bearings.push_back({0, 0, Vec2(4.2, 0.5), cov2});
  g.range_bearings.push_back({1, 1, Vec2(5.0, -kPi + 0.01), cov2});
  g.points.push_back({1, 0, Vec2(-2.0, -2.5), Mat2(cov2 * 10.0)});
  g.priors.push_back({0, Pose2{1.0, 2.0, -3.1}, cov3});
  return g;
}

std::vector<double> flatten(const GraphValues& v) {
  std::vector<double> x;
  for (const Pose2& p : v.poses) x.insert(x.end(), {p.x, p.y, p.theta});
  for (const Vec2& l : v.landmarks) x.insert(x.end(), {l.x(), l.y()});
  return x;
}

GraphValues unflatten(const std::vector<double>& x, const GraphValues& shape) {
  GraphValues v = shape;
  std::size_t k = 0;
  for (Pose2& p : v.poses) p = Pose2{x[k], x[k + 1], x[k + 2]}, k += 3;  // theta left unwrapped on purpose
  for (Vec2& l : v.landmarks) l = Vec2(x[k], x[k + 1]), k += 2;
  return v;
}

TEST(SmootherFactors, JacobiansMatchCentralDifferences) {
  const FactorGraph graph = one_of_each();
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> jitter(-0.05, 0.05);
  for (int trial = 0; trial < 5; ++trial) {
    GraphValues values = initial_values(graph);
    std::vector<double> x = flatten(values);
    for (double& xi : x) xi += jitter(rng);
    values = unflatten(x, values);
    Eigen::MatrixXd J;
    const Eigen::VectorXd r = evaluate_residuals(graph, values, &J);
    ASSERT_EQ(r.size(), 3 + 2 + 2 + 2 + 3);
    ASSERT_EQ(J.cols(), static_cast<Eigen::Index>(x.size()));
    const double h = 1e-6;
    for (std::size_t c = 0; c < x.size(); ++c) {
      std::vector<double> plus = x, minus = x;
      plus[c] += h;
      minus[c] -= h;
      const Eigen::VectorXd numeric =
          (evaluate_residuals(graph, unflatten(plus, values)) - evaluate_residuals(graph, unflatten(minus, values))) /
          (2 * h);
      for (Eigen::Index row = 0; row < r.size(); ++row)
        EXPECT_NEAR(J(row, c), numeric[row], 1e-5 * (1.0 + std::abs(numeric[row])))
            << "trial " << trial << " residual " << row << " parameter " << c;
    }
  }
}

TEST(SmootherFactors, AngleResidualsAreWrapped) {
  // Unit covariances, so the residuals are the raw errors. The landmark lies just left of straight behind
  // (predicted bearing pi - 0.01); the measurement says just right of it (-pi + 0.02): error -0.03, not 2 pi.
  FactorGraph g;
  g.poses = {{0.0, -1, 0, Pose2{0.0, 0.0, 0.0}}, {1.0, 0, 1, Pose2{1.0, 0.0, kPi - 0.005}}};
  g.landmarks = {{1, Vec2(-5.0 * std::cos(0.01), 5.0 * std::sin(0.01))}};
  g.range_bearings.push_back({0, 0, Vec2(5.0, -kPi + 0.02), Mat2::Identity()});
  g.priors.push_back({0, Pose2{0.0, 0.0, 0.0}, Mat3::Identity()});
  g.betweens.push_back({0, 1, Pose2{1.0, 0.0, -kPi + 0.005}, Mat3::Identity()});  // heading error -0.01 + 2 pi
  const Eigen::VectorXd r = evaluate_residuals(g, initial_values(g));
  ASSERT_EQ(r.size(), 3 + 2 + 3);
  EXPECT_NEAR(r[2], -0.01, 1e-9);      // between heading: (pi - 0.005) - (-pi + 0.005) wrapped
  EXPECT_NEAR(r[3], 0.0, 1e-9);        // range
  EXPECT_NEAR(r[4], -0.03, 1e-9);      // bearing
}

// The chained motion factor over several steps equals first-order propagation from any start pose,
// rotated into the factor's frame: the models are invariant to rigid motion of the start pose.
class ChainedMotion : public ::testing::TestWithParam<MotionModelKind> {};

TEST_P(ChainedMotion, MatchesPropagationFromAnArbitraryStart) {
  testing::TinyWorldOptions o;
  o.motion = GetParam();
  o.steps = 12;
  o.scan_every = 4;  // steps 0, 4, 8 have scans; 11 is the last: poses at start, 0, 4, 8, 11
  Scenario s = testing::make_tiny_world(o);
  for (ScenarioStep& step : s.steps)
    if (!step.has_scan) step.truth_pose.reset();
  const SmootherOptions options;
  const FactorGraph g = build_factor_graph(s, SmootherAssociations::from_truth(s), options);
  ASSERT_EQ(g.poses.size(), 5u);
  ASSERT_EQ(g.betweens.size(), 4u);
  const std::vector<int> kept = {-1, 0, 4, 8, 11};
  const Pose2 start{-3.0, 7.0, 2.5};  // anywhere
  for (int f = 0; f < 4; ++f) {
    Pose2 x = start;
    Mat3 P = Mat3::Zero();
    for (int k = kept[f] + 1; k <= kept[f + 1]; ++k) {
      const Mat3 Q = s.motion.process_noise(x, s.steps[k].control, s.steps[k].time_s - (k > 0 ? s.steps[k - 1].time_s : s.start_time_s));
      Mat3 Jx = Mat3::Zero();  // apply() fills it; zeroed so that gcc 12 sees no read before a write
      x = s.motion.apply(x, s.steps[k].control, &Jx);
      P = Jx * P * Jx.transpose() + Q;
    }
    const Pose2 delta = start.between(x);
    const BetweenFactor& b = g.betweens[f];
    EXPECT_NEAR(b.delta.x, delta.x, 1e-9);
    EXPECT_NEAR(b.delta.y, delta.y, 1e-9);
    EXPECT_NEAR(b.delta.theta, delta.theta, 1e-9);
    // World frame -> delta frame: rotate the translation block by -(start.theta + delta.theta).
    const double a = start.theta + delta.theta, c = std::cos(a), sn = std::sin(a);
    Mat3 G;
    G << c, sn, 0, -sn, c, 0, 0, 0, 1;
    Mat3 expected = G * P * G.transpose();
    expected.diagonal() += options.motion_floor_variance;
    EXPECT_LT((b.covariance - expected).cwiseAbs().maxCoeff(), 1e-9 * (1.0 + expected.cwiseAbs().maxCoeff()))
        << "factor " << f << "\n" << b.covariance << "\nvs\n" << expected;
  }
}

INSTANTIATE_TEST_SUITE_P(AllModels, ChainedMotion,
                         ::testing::Values(MotionModelKind::kOdometry, MotionModelKind::kVelocity,
                                           MotionModelKind::kAckermann),
                         [](const auto& info) { return std::string(to_string(info.param)); });

}  // namespace
}  // namespace arbor
