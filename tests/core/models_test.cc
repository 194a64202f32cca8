// Every analytic Jacobian of the motion and measurement models against central differences, including the
// edge cases: bearings near +-pi, a standing robot, straight-line velocity motion, a landmark at the sensor.
#include <gtest/gtest.h>

#include <functional>

#include <Eigen/Eigenvalues>

#include "core/math/angles.h"
#include "core/math/covariance_floor.h"
#include "core/models/motion_model.h"
#include "core/models/range_bearing_model.h"

namespace arbor {
namespace {

// Central differences of f: R^n -> R^m, with angle components of the output wrapped.
template <int M, int N>
Eigen::Matrix<double, M, N> numeric_jacobian(const std::function<Eigen::Matrix<double, M, 1>(const Eigen::Matrix<double, N, 1>&)>& f,
                                             const Eigen::Matrix<double, N, 1>& x, int angle_row) {
  Eigen::Matrix<double, M, N> J;
  const double h = 1e-6;
  for (int j = 0; j < N; ++j) {
    Eigen::Matrix<double, N, 1> plus = x, minus = x;
    plus[j] += h;
    minus[j] -= h;
    Eigen::Matrix<double, M, 1> d = f(plus) - f(minus);
    if (angle_row >= 0) d[angle_row] = wrap_angle(d[angle_row]);
    J.col(j) = d / (2 * h);
  }
  return J;
}

void expect_near(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b, double tol, const std::string& what) {
  EXPECT_LT((a - b).cwiseAbs().maxCoeff(), tol) << what << "\nanalytic:\n" << a << "\nnumeric:\n" << b;
}

MotionModel model_of(MotionModelKind kind) {
  MotionModel m;
  m.kind = kind;
  return m;
}

struct MotionCase {
  MotionModelKind kind;
  Pose2 pose;
  Vec3 u;
};

class MotionJacobians : public ::testing::TestWithParam<MotionCase> {};

TEST_P(MotionJacobians, MatchCentralDifferences) {
  const MotionCase c = GetParam();
  const MotionModel model = model_of(c.kind);
  Mat3 J_pose;
  model.apply(c.pose, c.u, &J_pose);
  const auto by_pose = [&](const Vec3& x) { return model.apply(Pose2{x[0], x[1], x[2]}, c.u).vector(); };
  expect_near(J_pose, numeric_jacobian<3, 3>(by_pose, c.pose.vector(), 2), 1e-6, "d pose'/d pose");
  if (c.kind == MotionModelKind::kAckermann) return;  // the engine needs no d pose'/d u: noise is in pose space
  Mat3 J_u;
  if (c.kind == MotionModelKind::kOdometry) odometry_apply(c.pose, c.u, nullptr, &J_u);
  else velocity_apply(c.pose, c.u, nullptr, &J_u);
  const auto by_u = [&](const Vec3& u) { return model.apply(c.pose, u).vector(); };
  expect_near(J_u, numeric_jacobian<3, 3>(by_u, c.u, 2), 1e-6, "d pose'/d u");
}

INSTANTIATE_TEST_SUITE_P(
    AllModels, MotionJacobians,
    ::testing::Values(MotionCase{MotionModelKind::kOdometry, {1, 2, 0.3}, {0.2, 1.5, -0.1}},
                      MotionCase{MotionModelKind::kOdometry, {-4, 2, kPi - 1e-3}, {0.01, 0.5, 0.02}},
                      MotionCase{MotionModelKind::kOdometry, {0, 0, 0}, {0, 0, 0}},  // standing still
                      MotionCase{MotionModelKind::kVelocity, {1, 2, 0.3}, {1.0, 0.4, 0.5}},
                      MotionCase{MotionModelKind::kVelocity, {1, 2, -kPi + 1e-3}, {1.0, 1e-7, 0.5}},  // straight
                      MotionCase{MotionModelKind::kVelocity, {1, 2, 2.0}, {0.5, -2.0, 0.1}},
                      MotionCase{MotionModelKind::kAckermann, {3, -1, 0.7}, {2.0, 0.2, 0.025}},
                      MotionCase{MotionModelKind::kAckermann, {3, -1, kPi - 1e-4}, {4.0, -0.5, 0.025}},
                      MotionCase{MotionModelKind::kAckermann, {0, 0, 0}, {0.0, 0.0, 0.025}}));

TEST(VelocityModel, SeriesBranchAgreesWithArcBranchAtTheSwitch) {
  const Pose2 x{1, 2, 0.3};
  const double dt = 0.5;
  // Just below and just above |omega dt| = 1e-4, where the model switches from the series to the arc.
  const Pose2 series = velocity_apply(x, {1.0, (1e-4 - 1e-12) / dt, dt}, nullptr, nullptr);
  const Pose2 arc = velocity_apply(x, {1.0, (1e-4 + 1e-12) / dt, dt}, nullptr, nullptr);
  EXPECT_NEAR(series.x, arc.x, 1e-11);
  EXPECT_NEAR(series.y, arc.y, 1e-11);
}

TEST(OdometryModel, BetweenInvertsApply) {
  const Pose2 a{1, -2, 3.0}, b{2.5, -1, -2.9};
  const Pose2 c = odometry_apply(a, odometry_between(a, b), nullptr, nullptr);
  EXPECT_NEAR(c.x, b.x, 1e-12);
  EXPECT_NEAR(c.y, b.y, 1e-12);
  EXPECT_NEAR(wrap_angle(c.theta - b.theta), 0.0, 1e-12);
}

struct MeasurementCase {
  Pose2 pose;
  Vec2 landmark;
};

class RangeBearingJacobians : public ::testing::TestWithParam<MeasurementCase> {};

// Named copies, not a structured binding: clang 14 (the sanitizer build) cannot capture bindings in lambdas.
TEST_P(RangeBearingJacobians, MatchCentralDifferences) {
  const Pose2 pose = GetParam().pose;
  const Vec2 m = GetParam().landmark;
  Mat2 J_lm;
  Mat23 J_pose;
  range_bearing_predict(pose, m, &J_lm, &J_pose);
  const auto by_lm = [&](const Vec2& l) { return range_bearing_predict(pose, l); };
  const auto by_pose = [&](const Vec3& x) { return range_bearing_predict(Pose2{x[0], x[1], x[2]}, m); };
  expect_near(J_lm, numeric_jacobian<2, 2>(by_lm, m, 1), 1e-6, "dz/dm");
  expect_near(J_pose, numeric_jacobian<2, 3>(by_pose, pose.vector(), 1), 1e-6, "dz/dx");
}

TEST_P(RangeBearingJacobians, InverseModelRoundTripsAndItsJacobianMatches) {
  const Pose2 pose = GetParam().pose;
  const Vec2 m = GetParam().landmark;
  const Vec2 z = range_bearing_predict(pose, m);
  Mat2 J;
  const Vec2 back = range_bearing_inverse(pose, z, &J);
  EXPECT_NEAR((back - m).norm(), 0.0, 1e-9);
  const auto by_z = [&](const Vec2& zz) { return range_bearing_inverse(pose, zz); };
  expect_near(J, numeric_jacobian<2, 2>(by_z, z, -1), 1e-6, "dm/dz");
}

INSTANTIATE_TEST_SUITE_P(
    Geometry, RangeBearingJacobians,
    ::testing::Values(MeasurementCase{{0, 0, 0}, {3, 4}},
                      MeasurementCase{{1, 1, 0.5}, {-5, 1.0001}},          // bearing near +pi
                      MeasurementCase{{1, 1, 0.0}, {-5, 0.9999}},          // bearing near -pi
                      MeasurementCase{{2, -3, kPi - 1e-6}, {10, -3.001}},  // heading near pi
                      MeasurementCase{{0, 0, -2.0}, {0.01, 0.02}}));       // very close landmark

TEST(RangeBearing, LandmarkAtTheSensorGivesFiniteValues) {
  Mat2 J_lm;
  Mat23 J_pose;
  const Vec2 z = range_bearing_predict({1, 1, 0}, {1, 1}, &J_lm, &J_pose);
  EXPECT_TRUE(z.allFinite());
  EXPECT_TRUE(J_lm.allFinite());
  EXPECT_TRUE(J_pose.allFinite());
}

TEST(RangeBearing, InnovationWrapsTheBearing) {
  const Vec2 nu = range_bearing_innovation({5, kPi - 0.01}, {5, -kPi + 0.01});
  EXPECT_NEAR(nu.y(), -0.02, 1e-12);
}

TEST(Angles, WrapIsIntoHalfOpenInterval) {
  EXPECT_DOUBLE_EQ(wrap_angle(kPi), kPi);
  EXPECT_DOUBLE_EQ(wrap_angle(-kPi), kPi);
  EXPECT_NEAR(wrap_angle(3 * kPi + 0.5), -kPi + 0.5, 1e-12);
  EXPECT_NEAR(wrap_angle(-7.0), -7.0 + 2 * kPi, 1e-12);
  EXPECT_DOUBLE_EQ(wrap_angle(0.25), 0.25);
}

TEST(MotionModel, PredictionCovarianceIsPositiveDefiniteForAStandingRobot) {
  for (auto kind : {MotionModelKind::kOdometry, MotionModelKind::kVelocity, MotionModelKind::kAckermann}) {
    const MotionModel m = model_of(kind);
    const Vec3 u = kind == MotionModelKind::kOdometry ? Vec3::Zero() : Vec3(0, 0, 0.025);
    const Eigen::SelfAdjointEigenSolver<Mat3> eig(m.process_noise({0, 0, 0}, u, 0.025));
    EXPECT_GT(eig.eigenvalues().minCoeff(), 0.0) << to_string(kind);
  }
}

// A zero-range measurement initialises a rank-1 covariance (its bearing moves the point by r dphi = 0);
// the floor makes it definite, and leaves an ordinary covariance exactly as it was.
TEST(CovarianceFloor, MakesAZeroRangeInitialisationDefiniteAndLeavesOrdinaryOnesAlone) {
  const Mat2 R = Vec2(0.1 * 0.1, 0.0087 * 0.0087).asDiagonal();
  Mat2 zero_range = range_bearing_initial_covariance(Pose2{1.0, 2.0, 0.7}, Vec2(0.0, 0.3), R);
  EXPECT_LE(zero_range.determinant(), 1e-30);
  floor_covariance(&zero_range);
  Eigen::SelfAdjointEigenSolver<Mat2> eigen(zero_range);
  EXPECT_GT(eigen.eigenvalues()(0), 0.5 * kMinEigenvalueRatio * eigen.eigenvalues()(1));
  EXPECT_NEAR(eigen.eigenvalues()(1), 0.01, 1e-12);  // the range's variance is kept

  const Mat2 ordinary = range_bearing_initial_covariance(Pose2{1.0, 2.0, 0.7}, Vec2(7.0, 0.3), R);
  Mat2 floored = ordinary;
  floor_covariance(&floored);
  EXPECT_EQ(floored, ordinary);
}

}  // namespace
}  // namespace arbor

