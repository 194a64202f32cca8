// Unknown association inside the engine (issue 4): FastSLAM 2.0 + JCBB on a cluttered world against known
// association, and bit-identical output across thread counts and map back ends with a search-based strategy.
#include <gtest/gtest.h>

#include "experiments/run/fastslam_run.h"
#include "experiments/sim/simulator.h"
#include "variants/registry.h"
#include "tests/engine/worlds.h"

namespace arbor {
namespace {

Scenario cluttered_world(std::uint64_t seed) { return testing::simulated_world(seed, 300, 2.0); }

RunOutput run(const Scenario& scenario, const std::string& assoc, int threads = 1, const std::string& out = "",
              const std::string& map = "naive") {
  RunConfig c = testing::fastslam_config(FilterVersion::kFastSlam2, 20, 1, threads);
  c.assoc = assoc;
  c.map = map;
  c.out_dir = out;
  return run_fastslam(scenario, c);
}

// Measured on the simulator of d43e3e0 (seeds 1-4, 300 steps, clutter 2/scan, 20 particles): per-seed F1
// 0.982-0.994; mean ATE 0.232 m with JCBB vs 0.315 m with known association (0.74x; at this test's commit
// 1.12x). Single-seed ATE ratios range from 0.4x to 2.1x with 20 particles, so the ATE margin is asserted on
// the mean over the seeds.
TEST(AssociationEngine, FastSlam2WithJcbbMatchesKnownAssociationOnAClutteredWorld) {
  double ate_known = 0.0, ate_jcbb = 0.0;
  for (std::uint64_t seed = 1; seed <= 4; ++seed) {
    const Scenario scenario = cluttered_world(seed);
    const RunOutput known = run(scenario, "known");
    const RunOutput jcbb = run(scenario, "jcbb");
    ASSERT_TRUE(jcbb.result["assoc_f1"].is_number());
    EXPECT_GE(jcbb.result["assoc_f1"].get<double>(), 0.95) << "seed " << seed;
    ate_known += known.result["ate_rmse_m"].get<double>();
    ate_jcbb += jcbb.result["ate_rmse_m"].get<double>();
  }
  EXPECT_LE(ate_jcbb, 1.5 * ate_known);
}

// A search that reaches its budget answers with its best hypothesis so far, and the run counts it.
TEST(AssociationEngine, SearchesThatReachTheirBudgetAreCounted) {
  const Scenario scenario = testing::simulated_world(2, 60, 2.0);
  for (const std::string assoc : {"jcbb", "locality"}) {
    RunConfig c = testing::fastslam_config(FilterVersion::kFastSlam2, 10, 1, 2);
    c.assoc = assoc;
    EXPECT_EQ(run_fastslam(scenario, c).result["budget_exhausted"].get<int>(), 0) << assoc;
    // Measured: a budget of 30 stops 44 (JCBB) and 60 (locality) of the 600 particle-scans, and the answers
    // keep F1 0.977 and 0.987, as with no budget.
    c.options.association.max_hypotheses = 30;
    const RunOutput tight = run_fastslam(scenario, c);
    EXPECT_GT(tight.result["budget_exhausted"].get<int>(), 0) << assoc;
    EXPECT_GT(tight.result["assoc_f1"].get<double>(), 0.9) << assoc << ": the best hypothesis so far still pairs";
  }
}

TEST(AssociationEngine, JcbbRunsAreBitIdenticalAcrossThreadCounts) {
  const Scenario scenario = cluttered_world(5);
  std::string files[2];
  for (int t = 1; t <= 2; ++t) {
    const std::string dir = testing::scratch_dir("assoc_jcbb_threads" + std::to_string(t));
    const RunOutput out = run(scenario, "jcbb", t, dir);
    files[t - 1] = testing::read_file(dir + "/trajectory.tum") + testing::read_file(dir + "/map.csv") +
                   out.result["assoc_f1"].dump() + out.result["landmarks"].dump();
  }
  ASSERT_GT(files[0].size(), 1000u);
  EXPECT_TRUE(files[0] == files[1]);
}

// Every back end hands landmarks to the strategy in ascending id order, so the searches see identical problems.
TEST(AssociationEngine, JcbbRunsAreBitIdenticalAcrossMapBackEnds) {
  const Scenario scenario = cluttered_world(6);
  std::vector<std::string> files;
  for (const std::string& map : map_backend_names()) {
    const std::string dir = testing::scratch_dir("assoc_jcbb_map_" + map);
    const RunOutput out = run(scenario, "jcbb", 1, dir, map);
    files.push_back(testing::read_file(dir + "/trajectory.tum") + testing::read_file(dir + "/map.csv") +
                    out.result["assoc_f1"].dump());
  }
  ASSERT_GE(files.size(), 2u);
  for (std::size_t k = 1; k < files.size(); ++k) EXPECT_TRUE(files[k] == files[0]) << map_backend_names()[k];
}

}  // namespace
}  // namespace arbor
