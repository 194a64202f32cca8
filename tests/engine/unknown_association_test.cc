// FastSLAM with unknown association: each particle associates its measurements against its own map with
// the chosen strategy. Accuracy against known association on a cluttered world, and bit-identity across
// thread counts and map back ends.
#include <vector>

#include <gtest/gtest.h>

#include "core/metrics/run_statistics.h"
#include "experiments/run/fastslam_run.h"
#include "experiments/sim/simulator.h"
#include "tests/engine/worlds.h"
#include "variants/registry.h"

namespace arbor {
namespace {

RunOutput run(const Scenario& scenario, const std::string& map, const std::string& assoc, std::uint64_t seed,
              int threads, int particles = 100, const std::string& out_dir = "", bool existence = true) {
  RunConfig c;
  if (!existence) {
    c.options.log_odds_confirm = c.options.log_odds_initial;  // every new landmark confirmed at once
    c.options.provisional_scans = 0;
  }
  c.map = map;
  c.assoc = assoc;
  c.options.version = FilterVersion::kFastSlam2;
  c.options.particles = particles;
  c.options.seed = seed;
  c.options.threads = threads;
  c.out_dir = out_dir;
  return run_fastslam(scenario, c);
}

// Measured on the simulator of d43e3e0, seeds 1-3 (300 steps, 2 clutter per scan, 100 particles): JCBB F1
// 0.984-0.995 (NN 0.990-0.995), ATE 0.10-0.19 m against known association's 0.09-0.40 m (seed 2: 0.134
// against 0.093, the tightest); confirmed landmarks 132-138 for 131-138 true ones observed (NN 132-139),
// 1-3 of them spurious. The ATE ratio is a property of the strategy, not of one draw of the particles, so
// the median of the three is held to 1.5x, and each run only to staying on the map (under 1 m): a draw tried
// in stop 54 gave seed 1 0.31 m against known association's unusually good 0.09 m (3.4x), its F1 and map as
// good as ever.
TEST(UnknownAssociation, Fastslam2WithJcbbMatchesKnownAssociationOnAClutteredWorld) {
  std::vector<double> ratios;
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    const Scenario scenario = testing::simulated_world(seed, 300, 2.0);
    const RunOutput known = run(scenario, "tree", "known", seed, 0);
    const RunOutput jcbb = run(scenario, "tree", "jcbb", seed, 0);
    const RunOutput nn = run(scenario, "tree", "nn", seed, 0);
    const double ate_known = known.result["ate_rmse_m"].get<double>();
    const double ate_jcbb = jcbb.result["ate_rmse_m"].get<double>();
    EXPECT_GE(jcbb.result["assoc_f1"].get<double>(), 0.95) << "seed " << seed;
    ratios.push_back(ate_jcbb / ate_known);
    EXPECT_LT(ate_jcbb, 1.0) << "seed " << seed << ": known " << ate_known << " m";
    // Clutter stays out of the confirmed map: a clutter landmark is seen once and never confirmed.
    const double observed = jcbb.result["observed_true_landmarks"].get<double>();
    EXPECT_LE(jcbb.result["landmarks"].get<double>(), 1.2 * observed) << "seed " << seed;
    EXPECT_LE(nn.result["landmarks"].get<double>(), 1.2 * observed) << "seed " << seed;
    EXPECT_LE(jcbb.result["spurious_landmarks"].get<double>(), 0.05 * observed) << "seed " << seed;
    if (seed > 1) continue;
    // Without the bookkeeping (every new landmark confirmed at birth) the clutter that negative evidence
    // cannot reach stays: the test must tell the two apart.
    const RunOutput ablation = run(scenario, "tree", "jcbb", seed, 0, 100, "", /*existence=*/false);
    EXPECT_GT(ablation.result["landmarks"].get<double>(), 1.2 * observed);
  }
  EXPECT_LE(median(ratios), 1.5) << "median JCBB / known ATE over seeds 1-3";
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
