// The controls between two scans composed once (core/models/composed_motion.h) carry any start pose and
// covariance where the chain of per-control EKF predictions carries them, for every motion model, through
// turns and across the heading's wrap. The engine relies on this to predict a whole particle set at once.
#include <gtest/gtest.h>

#include "core/engine/rng.h"
#include "core/models/composed_motion.h"

namespace arbor {
namespace {

MotionModel noisy_model(MotionModelKind kind) {
  MotionModel m;
  m.kind = kind;
  m.odometry = m.velocity = TwistNoise{1e-3, 2e-4, 1e-3, 5e-4, 4e-4};
  m.ackermann = AckermannNoise{0.01, 2.5e-5};
  return m;
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

class ComposedMotionTest : public ::testing::TestWithParam<MotionModelKind> {};

TEST_P(ComposedMotionTest, CarriesAnyStartAsTheChainOfPredictionsDoes) {
  const MotionModel model = noisy_model(GetParam());
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
    const int controls = 1 + trial * 3;
    for (int k = 0; k < controls; ++k) {
      const Vec3 u = random_control(GetParam(), rng);
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

TEST(ComposedMotion, WithoutControlsLeavesThePoseAlone) {
  ComposedMotion none;
  Pose2 x{1.0, 2.0, 3.0};
  Mat3 P = Mat3::Identity();
  none.apply(&x, &P);
  EXPECT_EQ(x.x, 1.0);
  EXPECT_EQ(x.theta, 3.0);
  EXPECT_EQ(P, Mat3::Identity());
}

INSTANTIATE_TEST_SUITE_P(EveryModel, ComposedMotionTest,
                         ::testing::Values(MotionModelKind::kOdometry, MotionModelKind::kVelocity,
                                           MotionModelKind::kAckermann),
                         [](const auto& info) { return std::string(to_string(info.param)); });

}  // namespace
}  // namespace arbor
