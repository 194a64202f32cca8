// The engine's building blocks: counter-based streams, resampling, the persistent pose history, chi-square.
#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <vector>

#include "core/engine/persistent_history.h"
#include "core/engine/resampling.h"
#include "core/engine/rng.h"
#include "core/types/landmark.h"
#include "core/math/chi_square.h"

namespace arbor {
namespace {

TEST(RandomStream, SameKeySameNumbersDifferentKeyDifferentNumbers) {
  RandomStream a(7, 3, 11, RandomPurpose::kMotion), b(7, 3, 11, RandomPurpose::kMotion);
  RandomStream c(7, 3, 12, RandomPurpose::kMotion), d(7, 3, 11, RandomPurpose::kProposal);
  for (int i = 0; i < 100; ++i) {
    const double x = a.normal();
    EXPECT_EQ(x, b.normal());
    EXPECT_NE(x, c.normal());
    EXPECT_NE(x, d.normal());
  }
}

TEST(RandomStream, NormalHasUnitVarianceAndUniformStaysInsideTheOpenInterval) {
  RandomStream r(1, 2, 3, RandomPurpose::kSimulation);
  double sum = 0, sum_sq = 0;
  const int n = 200000;
  for (int i = 0; i < n; ++i) {
    const double x = r.normal();
    sum += x;
    sum_sq += x * x;
    const double u = r.uniform();
    ASSERT_GT(u, 0.0);
    ASSERT_LT(u, 1.0);
  }
  EXPECT_NEAR(sum / n, 0.0, 0.01);
  EXPECT_NEAR(sum_sq / n, 1.0, 0.01);
}

TEST(Resampling, NormalisesInLogSpaceAndComputesNeff) {
  std::vector<double> w;
  const double n_eff = normalize_log_weights({-1000.0, -1000.0, -1000.0, -1000.0}, &w);
  EXPECT_NEAR(n_eff, 4.0, 1e-12);
  EXPECT_NEAR(std::accumulate(w.begin(), w.end(), 0.0), 1.0, 1e-12);
  EXPECT_NEAR(normalize_log_weights({0.0, -800.0}, &w), 1.0, 1e-12);
}

TEST(Resampling, SystematicCopiesEachParticleFloorOrCeilOfMTimesItsWeight) {
  const std::vector<double> w{0.5, 0.25, 0.125, 0.125};
  for (double u : {0.01, 0.3, 0.77, 0.999}) {
    const auto parents = systematic_resample(w, u);
    std::vector<int> copies(4, 0);
    for (int p : parents) ++copies[p];
    for (int i = 0; i < 4; ++i) {
      EXPECT_GE(copies[i], static_cast<int>(std::floor(4 * w[i]))) << "u=" << u;
      EXPECT_LE(copies[i], static_cast<int>(std::ceil(4 * w[i]))) << "u=" << u;
    }
    EXPECT_TRUE(std::is_sorted(parents.begin(), parents.end()));
  }
}

TEST(PoseHistory, CopiesShareTheirPastAndTheLastOneFreesIt) {
  const auto before = PoseHistory::live_nodes();
  {
    PoseHistory a;
    for (int i = 0; i < 10; ++i) a.push({double(i), {double(i), 0, 0}});
    PoseHistory b = a;
    b.push({10, {10, 0, 0}});
    a.push({10, {-10, 0, 0}});
    EXPECT_EQ(PoseHistory::live_nodes() - before, 12);
    EXPECT_EQ(a.to_vector().back().pose.x, -10);
    EXPECT_EQ(b.to_vector().back().pose.x, 10);
    EXPECT_EQ(a.to_vector().size(), 11u);
  }
  EXPECT_EQ(PoseHistory::live_nodes(), before);
}

// A relocalised particle rewrites the pose of the step it was found at; a copy taken before keeps the old one.
TEST(PoseHistory, ReplacingTheNewestEntryLeavesCopiesAndTheOlderPastAlone) {
  const auto before = PoseHistory::live_nodes();
  {
    PoseHistory a;
    for (int i = 0; i < 5; ++i) a.push({double(i), {double(i), 0, 0}});
    const PoseHistory copy = a;
    a.replace_newest({4, {40, 0, 0}});
    const std::vector<TimedPose> mine = a.to_vector(), theirs = copy.to_vector();
    ASSERT_EQ(mine.size(), 5u);
    EXPECT_EQ(mine.back().pose.x, 40);
    EXPECT_EQ(theirs.back().pose.x, 4);
    for (int i = 0; i < 4; ++i) EXPECT_EQ(mine[i].pose.x, i);
    EXPECT_EQ(PoseHistory::live_nodes() - before, 6);  // one new node; the four older ones shared
  }
  EXPECT_EQ(PoseHistory::live_nodes(), before);
}

// The newest shared entry is a shared node, not an equal value: two paths through the same poses drawn apart
// share nothing.
TEST(PoseHistory, TheNewestSharedEntryIsWhereThePathsLastBranched) {
  PoseHistory root;
  for (int i = 0; i < 3; ++i) root.push({double(i), {double(i), 0, 0}});
  PoseHistory a = root, b = root, c = root;
  a.push({3, {3, 0, 0}});
  b.push({3, {3, 0, 0}});  // the same value as a's, in its own node
  c.push({3, {-3, 0, 0}});
  const std::vector<const PoseHistory*> abc{&a, &b, &c};
  ASSERT_NE(PoseHistory::newest_shared_entry(abc), nullptr);
  EXPECT_EQ(PoseHistory::newest_shared_entry(abc)->time_s, 2);
  PoseHistory d = a;  // a copy after the branch shares a's newest entry
  const std::vector<const PoseHistory*> ad{&a, &d};
  EXPECT_EQ(PoseHistory::newest_shared_entry(ad)->time_s, 3);
  PoseHistory other;  // its own start: nothing in common
  for (int i = 0; i < 4; ++i) other.push({double(i), {double(i), 0, 0}});
  const std::vector<const PoseHistory*> a_other{&a, &other};
  EXPECT_EQ(PoseHistory::newest_shared_entry(a_other), nullptr);
}

TEST(PoseHistory, AVeryLongHistoryIsFreedWithoutRecursion) {
  const auto before = PoseHistory::live_nodes();
  {
    PoseHistory h;
    for (int i = 0; i < 2'000'000; ++i) h.push({double(i), {}});
  }
  EXPECT_EQ(PoseHistory::live_nodes(), before);
}

TEST(ChiSquare, QuantilesMatchTables) {
  EXPECT_NEAR(chi_square_quantile(0.95, 2), 5.991464547, 1e-8);
  EXPECT_NEAR(chi_square_quantile(0.99, 2), 9.210340372, 1e-8);
  EXPECT_NEAR(chi_square_quantile(0.95, 3), 7.814727903, 1e-8);
  EXPECT_NEAR(chi_square_quantile(0.975, 90), 118.1358, 1e-3);
  EXPECT_NEAR(chi_square_quantile(0.025, 90), 65.6466, 1e-3);
  const ChiSquareTable table(0.99, 40);
  EXPECT_DOUBLE_EQ(table(2), chi_square_quantile(0.99, 2));
  EXPECT_NEAR(table(60), chi_square_quantile(0.99, 60), 1e-12);
}

TEST(LocalitySet, StaysSortedAndUniqueWithinItsCapacity) {
  LocalitySet s;
  for (LandmarkId id : {9, 3, 7, 3, 1, 12, 5, 8, 2}) s.add(id);
  ASSERT_EQ(s.size(), LocalitySet::kCapacity);
  const std::vector<LandmarkId> ids(s.begin(), s.end());
  EXPECT_TRUE(std::is_sorted(ids.begin(), ids.end()));
  EXPECT_EQ(std::adjacent_find(ids.begin(), ids.end()), ids.end());
  EXPECT_TRUE(s.contains(3));  // seen twice: never the weakest
  s.remove(3);
  EXPECT_FALSE(s.contains(3));
  EXPECT_EQ(s.size(), LocalitySet::kCapacity - 1);
}

// The set keeps learning: a landmark seen often with this one enters even after the set filled up with
// landmarks seen once (a set that kept the first or the lowest ids would refuse it), and it stays while a
// stream of landmarks seen once each passes through.
TEST(LocalitySet, KeepsTheMostFrequentlyCoObservedNotTheFirst) {
  LocalitySet s;
  for (LandmarkId id = 1; id <= LocalitySet::kCapacity; ++id) s.add(id);
  for (int k = 0; k < 3; ++k) s.add(50);
  EXPECT_TRUE(s.contains(50));
  for (int k = 0; k < 20; ++k) s.add(50);
  for (LandmarkId id = 100; id < 140; ++id) s.add(id);
  EXPECT_TRUE(s.contains(50));
  EXPECT_EQ(s.size(), LocalitySet::kCapacity);
}

// Counts are 8-bit: when one would overflow, all are halved, which keeps their order.
TEST(LocalitySet, HalvingOnOverflowKeepsTheOrderOfTheCounts) {
  LocalitySet s;
  for (int k = 0; k < 600; ++k) {
    s.add(7);
    if (k % 3 == 0) s.add(8);
  }
  ASSERT_EQ(s.size(), 2);
  EXPECT_GT(s.weight(0), s.weight(1));  // ids sorted: 7 then 8
  EXPECT_GT(s.weight(1), 0);
  EXPECT_LE(s.weight(0), 255);
}

}  // namespace
}  // namespace arbor
