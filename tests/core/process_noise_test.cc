// Continuous-time motion noise (core/models/twist_motion.h): an interval predicted in 1, 10 or 100 pieces gets
// the same covariance, for every motion model, straight and turning; and the quadrature agrees with a
// Monte Carlo of the noise it models. The controls between two scans composed once (core/models/composed_motion.h)
// carry any start pose and covariance where the chain of per-control predictions carries them, for every model,
// through turns and across the heading's wrap: the engine relies on it to predict a whole particle set at once.
#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

#include "core/engine/rng.h"
#include "core/models/composed_motion.h"
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

// A control of the model's kind that drives and turns: (rot1, trans, rot2); (v, omega, dt); (v_e, alpha, dt).
Vec3 random_control(MotionModelKind kind, RandomStream& rng) {
  switch (kind) {
    case MotionModelKind::kOdometry: return {0.3 * rng.normal(), 0.5 + rng.uniform(), 0.3 * rng.normal()};
    case MotionModelKind::kVelocity: return {1.0 + rng.uniform(), 0.8 * rng.normal(), 0.05 + 0.1 * rng.uniform()};
    case MotionModelKind::kAckermann: return {2.0 + rng.uniform(), 0.3 * rng.normal(), 0.025};
  }
  return Vec3::Zero();
}

TEST(ComposedMotion, CarriesAnyStartAsTheChainOfPredictionsDoes) {
  for (MotionModelKind kind : {MotionModelKind::kOdometry, MotionModelKind::kVelocity, MotionModelKind::kAckermann}) {
    SCOPED_TRACE(to_string(kind));
    const MotionModel model = noisy_model(kind);
    RandomStream rng(7, 0, 0, RandomPurpose::kMotion);
    for (int trial = 0; trial < 20; ++trial) {
      // A start near the heading's wrap on odd trials, and a start covariance that is not zero (a prediction
      // since the last draw, or a roughening kernel).
      const Pose2 start{10.0 * rng.normal(), 10.0 * rng.normal(), trial % 2 ? 3.1 : rng.normal()};
      Mat3 L = Mat3::Zero();
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c <= r; ++c) L(r, c) = (r == c ? 0.2 : 0.05) * rng.normal();
      const Mat3 P0 = L * L.transpose() + 1e-6 * Mat3::Identity();

      Pose2 chain = start;
      Mat3 P_chain = P0;
      ComposedMotion composed;
      for (int k = 0; k < 1 + trial * 3; ++k) {
        const Vec3 u = random_control(kind, rng);
        const BodyProcessNoise noise = model.body_noise(u, 0.05);
        model.predict(&chain, &P_chain, u, noise);
        composed.add(model, u, noise);
      }
      Pose2 x = start;
      Mat3 P = P0;
      composed.apply(&x, &P);
      EXPECT_NEAR(x.x, chain.x, 1e-9) << "trial " << trial;
      EXPECT_NEAR(x.y, chain.y, 1e-9) << "trial " << trial;
      EXPECT_NEAR(wrap_angle(x.theta - chain.theta), 0.0, 1e-12) << "trial " << trial;
      EXPECT_LT((P - P_chain).cwiseAbs().maxCoeff(), 1e-9 * P_chain.cwiseAbs().maxCoeff()) << "trial " << trial;
      EXPECT_LT((P - P.transpose()).cwiseAbs().maxCoeff(), 1e-12 * P.cwiseAbs().maxCoeff()) << "trial " << trial;
    }
  }
}

TEST(ComposedMotion, WithoutControlsLeavesThePoseAlone) {
  ComposedMotion none;
  Pose2 x{1.0, 2.0, 3.0};
  Mat3 P = Mat3::Identity();
  none.apply(&x, &P);
  EXPECT_EQ(x.x, 1.0);
  EXPECT_EQ(x.theta, 3.0);
  EXPECT_EQ(P, Mat3::Identity());
}

}  // namespace
}  // namespace arbor
