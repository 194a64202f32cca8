// EKF-SLAM against the smoother on a nearly linear-Gaussian problem (noise small enough that linearising at
// the estimate costs nothing): there the filter's posterior over the last pose and the map is the batch
// solution's, so the two must agree far inside the filter's own uncertainty (Probabilistic Robotics §10.2:
// the EKF is exact for linear-Gaussian SLAM). A wrong cross covariance, a missing term of the prediction or an
// initialisation without its pose part breaks the agreement by several standard deviations.
#include <gtest/gtest.h>

#include "tests/smoothing/tiny_world.h"
#include "variants/registry.h"
#include "variants/smoothing/smoother.h"

namespace arbor {
namespace {

TEST(EkfVsSmoother, LastPoseAndMapAgreeOnANearlyLinearProblem) {
  for (unsigned seed : {1u, 2u, 3u}) {
    testing::TinyWorldOptions o;
    o.seed = seed;
    // A tenth of the tiny world's noise: at its full noise the filter's linearisation at the estimate
    // already differs from the batch solution's by up to half a standard deviation (0.53 on seed 1); at a
    // tenth by 0.06 at most, and at a hundredth the smoother's own convergence tolerance dominates.
    o.noise_scale = 0.1;
    Scenario s = testing::make_tiny_world(o);
    FastSlamOptions options;
    options.version = FilterVersion::kEkf;
    std::unique_ptr<Filter> ekf = make_filter("", "known", s, options);
    for (const ScenarioStep& step : s.steps) ekf->step(step);
    const SmootherResult smoothed = smooth(s, SmootherAssociations::from_truth(s), SmootherOptions{});
    ASSERT_TRUE(smoothed.summary.usable) << smoothed.summary.report;

    const PoseEstimate last = ekf->estimate();
    const Pose2& batch = smoothed.poses.back().pose;
    const Vec3 d(last.mean.x - batch.x, last.mean.y - batch.y, wrap_angle(last.mean.theta - batch.theta));
    const Vec3 truth_d = (last.mean.vector() - s.steps.back().truth_pose->vector());
    // In the filter's standard deviations: the pose's Mahalanobis distance to the batch solution.
    const double mahalanobis = std::sqrt(d.dot(last.covariance.ldlt().solve(d)));
    EXPECT_LT(mahalanobis, 0.1) << "seed " << seed << ", last pose off by " << d.transpose() << " (truth "
                                 << truth_d.transpose() << ")";
    int compared = 0;
    for (const Landmark& lm : ekf->best_map()) {
      const auto it = std::find_if(smoothed.landmarks.begin(), smoothed.landmarks.end(),
                                   [&](const SmoothedLandmark& b) { return b.id == lm.truth_label; });
      ASSERT_NE(it, smoothed.landmarks.end()) << "landmark " << lm.truth_label;
      const Vec2 e = lm.mean - it->position;
      EXPECT_LT(std::sqrt(e.dot(lm.cov.ldlt().solve(e))), 0.1) << "seed " << seed << ", landmark " << lm.truth_label;
      ++compared;
    }
    EXPECT_EQ(compared, static_cast<int>(smoothed.landmarks.size()));
  }
}

}  // namespace
}  // namespace arbor
