// Tempered weights (FastSlamOptions::weight_exponent): a set weighted by w^beta stays consistent over a run
// where one weighted by the exact weights grows overconfident, and it resamples less; the default tempers only
// FastSLAM 2.0 with the true pairings. (Bit-identity across back ends and threads:
// GateCovariance.Issue41OptionsAreBitIdenticalAcrossBackendsAndThreads.)
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "experiments/run/fastslam_run.h"
#include "tests/engine/worlds.h"

namespace arbor {
namespace {

struct ConsistencyCount {
  int inside = 0, above = 0, resamples = 0;
};

// The 30-seed average NEES per scan over the first `scans` scans of the default world (100 particles, known
// association), counted inside the 95 % band of a consistent 3-dof estimator (testing::in_nees_band;
// FastSlamRun.FastSlam2IsConsistentOnAShortHorizonOver30Seeds) and above it.
ConsistencyCount consistency(double weight_exponent, int scans) {
  ConsistencyCount count;
  const std::vector<double> nees = testing::average_nees_over_seeds(scans, [&](int s) {
    RunConfig c = testing::fastslam_config(FilterVersion::kFastSlam2, 100, s, 0);
    c.options.weight_exponent = weight_exponent;
    const RunOutput out = run_fastslam(testing::simulated_world(s, scans), c);
    count.resamples += out.result["resamples"].get<int>();
    return out;
  });
  for (double average : nees) {
    count.inside += testing::in_nees_band(average);
    count.above += average > testing::kNeesBandHigh;
  }
  return count;
}

// Measured at commit time over 120 scans: exact weights 44 scans inside the band and 76 above it (1,005
// resamplings in all); weight exponent 0.25: 91 inside, none above (137); 0.1: 99 inside, none above (21).
TEST(TemperedWeights, KeepTheSetConsistentWhereExactWeightsGrowOverconfident) {
  constexpr int kScans = 121;
  const ConsistencyCount exact = consistency(1.0, kScans);
  EXPECT_GT(exact.above, 60) << "the exact weights must grow overconfident over this horizon, or this test shows nothing";
  for (double exponent : {0.25, 0.1}) {
    const ConsistencyCount tempered = consistency(exponent, kScans);
    EXPECT_GE(tempered.inside, 80) << "scans of 120 inside the band, weight exponent " << exponent;
    EXPECT_LE(tempered.above, 5) << "weight exponent " << exponent;
    EXPECT_LT(tempered.resamples, exact.resamples / 5) << "flatter weights fall below the resampling threshold less often";
  }
}

// The default (0) tempers FastSLAM 2.0 with the true pairings only: with a real strategy the weights weed out
// wrong pairings, and FastSLAM 1.0's weights are all that corrects its poses. result.json records what ran.
TEST(TemperedWeights, TheDefaultTempersOnlyFastSlam2WithTheTruePairings) {
  FastSlamOptions o;
  EXPECT_EQ(o.effective_weight_exponent(/*true_pairings=*/true), FastSlamOptions::kTruePairingsWeightExponent);
  EXPECT_EQ(o.effective_weight_exponent(false), 1.0);
  o.version = FilterVersion::kFastSlam1;
  EXPECT_EQ(o.effective_weight_exponent(true), 1.0);
  o.weight_exponent = 0.5;
  EXPECT_EQ(o.effective_weight_exponent(true), 0.5);

  const Scenario scenario = testing::cluttered_rooms(3, 150, /*clutter=*/2.0, /*scans=*/120);
  const auto files = [&](const std::string& assoc, double exponent, const std::string& name) {
    RunConfig c = testing::fastslam_config(FilterVersion::kFastSlam2, 20, 3, 2);
    c.assoc = assoc;
    c.options.weight_exponent = exponent;
    c.out_dir = testing::scratch_dir(name);
    const RunOutput out = run_fastslam(scenario, c);
    return std::make_pair(testing::read_file(c.out_dir + "/trajectory.tum") + testing::read_file(c.out_dir + "/map.csv"),
                          out.result["config"]["weight_exponent"].get<double>());
  };
  const auto known_default = files("known", 0.0, "tempered_known_default");
  EXPECT_EQ(known_default.second, 0.1);
  EXPECT_TRUE(known_default.first == files("known", 0.1, "tempered_known_explicit").first);
  EXPECT_FALSE(known_default.first == files("known", 1.0, "tempered_known_paper").first) << "the default must temper";
  const auto jcbb_default = files("jcbb", 0.0, "tempered_jcbb_default");
  EXPECT_EQ(jcbb_default.second, 1.0);
  EXPECT_TRUE(jcbb_default.first == files("jcbb", 1.0, "tempered_jcbb_paper").first);
}

}  // namespace
}  // namespace arbor
