// Whole FastSLAM runs give bit-identical results with every map back end (DESIGN.md §3, "determinism across
// back ends"): same trajectory, same map, same estimate, to the last bit.
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "bench/map_world.h"
#include "variants/registry.h"

namespace arbor {
namespace {

struct RunOutput {
  std::vector<TimedPose> trajectory;
  std::vector<Landmark> map;
  PoseEstimate estimate;
  std::vector<double> n_eff;
  MapMemoryStats memory;
};

RunOutput run(const std::string& map, const Scenario& scenario, FilterVersion version, int threads) {
  FastSlamOptions options;
  options.version = version;
  options.particles = 20;
  options.seed = 5;
  options.threads = threads;
  options.prune_with_known_association = true;  // so that landmarks are erased too, not only set and inserted
  auto filter = make_filter(map, "known", scenario, options);
  RunOutput out;
  for (const ScenarioStep& step : scenario.steps) {
    filter->step(step);
    out.n_eff.push_back(filter->last_step_stats().n_eff);
  }
  out.trajectory = filter->best_trajectory();
  out.map = filter->best_map();
  out.estimate = filter->estimate();
  out.memory = filter->memory_stats();
  return out;
}

void expect_identical(const RunOutput& a, const RunOutput& b, const std::string& what) {
  ASSERT_EQ(a.trajectory.size(), b.trajectory.size()) << what;
  for (std::size_t i = 0; i < a.trajectory.size(); ++i) {
    const Pose2 &p = a.trajectory[i].pose, &q = b.trajectory[i].pose;
    ASSERT_TRUE(p.x == q.x && p.y == q.y && p.theta == q.theta) << what << " pose " << i;
  }
  ASSERT_EQ(a.map.size(), b.map.size()) << what;
  for (std::size_t i = 0; i < a.map.size(); ++i) ASSERT_TRUE(a.map[i] == b.map[i]) << what << " landmark " << i;
  EXPECT_TRUE(a.estimate.mean.x == b.estimate.mean.x && a.estimate.mean.y == b.estimate.mean.y &&
              a.estimate.mean.theta == b.estimate.mean.theta && a.estimate.covariance == b.estimate.covariance)
      << what;
  EXPECT_EQ(a.n_eff, b.n_eff) << what;
}

class BackendIdentity : public ::testing::TestWithParam<FilterVersion> {};

TEST_P(BackendIdentity, WholeRunsAreBitIdenticalAcrossMapBackends) {
  const auto field = bench::make_landmark_field(400, 3);
  bench::FieldDrive drive;
  drive.steps = 450;  // more than one loop of the 60 m circle: landmarks are revisited
  drive.detection_probability = 0.8;
  const Scenario scenario = bench::make_field_scenario(field, drive);
  const RunOutput reference = run("naive", scenario, GetParam(), 2);
  ASSERT_GT(reference.map.size(), 50u);
  for (const std::string& name : map_backend_names()) {
    const RunOutput other = run(name, scenario, GetParam(), name == "tree" ? 1 : 2);
    expect_identical(reference, other, name);
    if (name != "naive") {
      // Persistence pays off: the particles' maps share most of their nodes.
      EXPECT_GT(other.memory.shared_bytes, other.memory.bytes / 2) << name;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Versions, BackendIdentity,
                         ::testing::Values(FilterVersion::kFastSlam1, FilterVersion::kFastSlam2),
                         [](const auto& info) { return std::string(to_string(info.param)) == "fastslam1" ? "FastSlam1" : "FastSlam2"; });

}  // namespace
}  // namespace arbor
