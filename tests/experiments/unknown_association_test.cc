// FastSLAM with unknown association: each particle associates its measurements against its own map with
// the chosen strategy. Accuracy against known association on a cluttered world, and bit-identity across
// thread counts and map back ends.
#include <gtest/gtest.h>

#include "experiments/run/fastslam_run.h"
#include "experiments/sim/simulator.h"
#include "test_support.h"
#include "variants/registry.h"

namespace arbor {
namespace {

RunOutput run(const Scenario& scenario, const std::string& map, const std::string& assoc, std::uint64_t seed,
              int threads, int particles = 100, const std::string& out_dir = "") {
  RunConfig c;
  c.map = map;
  c.assoc = assoc;
  c.options.version = FilterVersion::kFastSlam2;
  c.options.particles = particles;
  c.options.seed = seed;
  c.options.threads = threads;
  c.out_dir = out_dir;
  return run_fastslam(scenario, c);
}

// Measured at commit time on seeds 1-3 (300 steps, 2 clutter per scan, 100 particles): see kMeasured below.
TEST(UnknownAssociation, Fastslam2WithJcbbMatchesKnownAssociationOnAClutteredWorld) {
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    const Scenario scenario = testing::simulated_world(seed, 300, 2.0);
    const RunOutput known = run(scenario, "tree", "known", seed, 0);
    const RunOutput jcbb = run(scenario, "tree", "jcbb", seed, 0);
    const double f1 = jcbb.result["assoc_f1"].get<double>();
    const double ate_known = known.result["ate_rmse_m"].get<double>();
    const double ate_jcbb = jcbb.result["ate_rmse_m"].get<double>();
    EXPECT_GE(f1, 0.95) << "seed " << seed;
    EXPECT_LE(ate_jcbb, 1.5 * ate_known) << "seed " << seed << ": known " << ate_known << " m";
    // Clutter must not grow the map without bound: most provisional landmarks are pruned. Clutter that
    // appears at the edge of view and leaves it before it can be missed twice survives.
    std::size_t clutter = 0;
    for (const auto& step : scenario.steps)
      for (const auto& m : step.measurements) clutter += m.truth_id == kTruthClutter;
    const double extra = jcbb.result["landmarks"].get<double>() - known.result["landmarks"].get<double>();
    EXPECT_LT(extra, 0.35 * clutter) << "seed " << seed << ": " << clutter << " clutter measurements";
  }
}

TEST(UnknownAssociation, BitIdenticalAcrossThreadCountsAndMapBackends) {
  const Scenario scenario = testing::simulated_world(5, 80, 1.0);
  for (const std::string assoc : {"nn", "jcbb", "locality"}) {
    std::string reference;
    for (const std::string& map : map_backend_names()) {
      for (int threads : {1, 2}) {
        const std::string dir = testing::scratch_dir("unknown_" + assoc + "_" + map + "_" + std::to_string(threads));
        const RunOutput out = run(scenario, map, assoc, 3, threads, 30, dir);
        const std::string files = testing::read_file(dir + "/trajectory.tum") + testing::read_file(dir + "/map.csv") +
                                  out.result["assoc_f1"].dump() + out.result["hypotheses"].dump();
        if (reference.empty()) reference = files;
        EXPECT_TRUE(files == reference) << assoc << " with " << map << " and " << threads << " threads differs";
      }
    }
  }
}

}  // namespace
}  // namespace arbor
