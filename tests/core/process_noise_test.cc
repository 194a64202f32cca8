// Continuous-time motion noise (core/models/twist_motion.h): an interval predicted in 1, 10 or 100 pieces gets
// the same covariance, for every motion model, straight and turning; and the quadrature agrees with a
// Monte Carlo of the noise it models.
#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

#include "core/engine/rng.h"
#include "core/models/motion_model.h"

namespace arbor {
namespace {

struct Interval {
  MotionModelKind kind;
  double v, omega, duration;  // forward speed and turn rate (velocity, odometry) or (v_e, steering) (Ackermann)
  const char* name;
};

MotionModel noisy_model(MotionModelKind kind) {
  MotionModel m;
  m.kind = kind;
  m.odometry = m.velocity = TwistNoise{1e-3, 2e-4, 1e-3, 5e-4, 4e-4};
  m.ackermann = AckermannNoise{0.01, 2.5e-5};
  return m;
}

// The control of one piece of the interval: rate controls are cut in time; an odometry reading is the arc
// the robot drives in that time.
Vec3 piece_control(const Pose2& x, const Interval& c, double dt) {
  if (c.kind != MotionModelKind::kOdometry) return {c.v, c.omega, dt};
  return odometry_between(x, velocity_apply(x, {c.v, c.omega, dt}, nullptr, nullptr));
}

Mat3 predicted_covariance(const Interval& c, int pieces, Pose2* end) {
  const MotionModel m = noisy_model(c.kind);
  Pose2 x{2.0, -1.0, 0.4};
  Mat3 P = Mat3::Zero();
  const double dt = c.duration / pieces;
  for (int i = 0; i < pieces; ++i) m.predict(&x, &P, piece_control(x, c, dt), dt);
  *end = x;
  return P;
}

class IntervalSplitting : public ::testing::TestWithParam<Interval> {};

TEST_P(IntervalSplitting, OneTenOrAHundredPiecesGiveTheSameCovariance) {
  const Interval c = GetParam();
  Pose2 end_1, end_n;
  const Mat3 P1 = predicted_covariance(c, 1, &end_1);
  ASSERT_GT(P1.determinant(), 0.0);
  for (int pieces : {10, 100}) {
    const Mat3 Pn = predicted_covariance(c, pieces, &end_n);
    EXPECT_LT(pose_error(end_n, end_1).norm(), 1e-9) << c.name << ": the mean must not depend on the cut";
    // Relative agreement in every direction: the largest eigenvalue of P1^-1/2 (Pn - P1) P1^-1/2.
    const Eigen::LLT<Mat3> llt(P1);
    const Mat3 L_inv = llt.matrixL().solve(Mat3::Identity());
    const Mat3 D = L_inv * (Pn - P1) * L_inv.transpose();
    const double worst = Eigen::SelfAdjointEigenSolver<Mat3>(D).eigenvalues().cwiseAbs().maxCoeff();
    EXPECT_LT(worst, 0.01) << c.name << " in " << pieces << " pieces\nP1:\n" << P1 << "\nPn:\n" << Pn;
  }
}

INSTANTIATE_TEST_SUITE_P(
    EveryModel, IntervalSplitting,
    ::testing::Values(Interval{MotionModelKind::kVelocity, 1.0, 0.0, 2.0, "velocity straight"},
                      Interval{MotionModelKind::kVelocity, 0.8, 0.6, 2.0, "velocity turning"},
                      Interval{MotionModelKind::kVelocity, 0.0, 0.0, 1.0, "velocity standing"},
                      Interval{MotionModelKind::kOdometry, 1.0, 0.0, 1.0, "odometry straight"},
                      Interval{MotionModelKind::kOdometry, 1.0, -0.5, 1.0, "odometry turning"},
                      Interval{MotionModelKind::kAckermann, 3.0, 0.0, 1.0, "ackermann straight"},
                      Interval{MotionModelKind::kAckermann, 3.0, 0.3, 1.0, "ackermann turning"}),
    [](const auto& info) {
      std::string n = info.param.name;
      for (char& ch : n) ch = std::isalnum(static_cast<unsigned char>(ch)) ? ch : '_';
      return n;
    });

// The quadrature against the noise it stands for: integrate the velocity model with white noise on v and
// omega in 200 sub-steps, many times, and compare the end poses' covariance.
TEST(TwistProcessNoise, MatchesMonteCarloOfTheWhiteNoise) {
  const MotionModel m = noisy_model(MotionModelKind::kVelocity);
  const Pose2 start{0.0, 0.0, 0.3};
  const double v = 1.0, omega = 0.5, T = 2.0;
  const int sub = 200, runs = 20000;
  const double h = T / sub;
  const Mat2 psd = m.velocity.psd(v, omega);
  Mat3 C = Mat3::Zero();
  const Pose2 mean = velocity_apply(start, {v, omega, T}, nullptr, nullptr);
  for (int r = 0; r < runs; ++r) {
    RandomStream rng(7, r, 0, RandomPurpose::kSimulation);
    Pose2 x = start;
    for (int i = 0; i < sub; ++i) {
      const double nv = std::sqrt(psd(0, 0) / h) * rng.normal(), nw = std::sqrt(psd(1, 1) / h) * rng.normal();
      x = velocity_apply(x, {v + nv, omega + nw, h}, nullptr, nullptr);
    }
    const Vec3 e = pose_error(x, mean);
    C += e * e.transpose() / runs;
  }
  const Mat3 Q = m.process_noise(start, {v, omega, T}, T);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(C(i, i), Q(i, i), 0.05 * Q(i, i)) << "diagonal " << i << "\nMC:\n" << C << "\nQ:\n" << Q;
}

}  // namespace
}  // namespace arbor
