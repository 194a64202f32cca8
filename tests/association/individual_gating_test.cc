// Individual gating passes over a pair whose range innovation alone puts it outside both gates; what it keeps
// must be what testing every pair's full Mahalanobis distance keeps, to the bit.
#include <algorithm>
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "core/math/chi_square.h"
#include "core/models/range_bearing_model.h"
#include "variants/association/association_common.h"
#include "variants/association/problem_generator.h"

namespace arbor {
namespace {

struct Reference {
  std::vector<association::GatedPair> pairs;
  std::vector<char> near_any;
};

// Every (measurement, candidate) distance, with no shortcut.
Reference gate_every_pair(const AssociationProblem& p, double gate, double new_landmark_gate) {
  Reference r;
  r.near_any.assign(p.measurements.size(), 0);
  for (int i = 0; i < static_cast<int>(p.measurements.size()); ++i)
    for (int j = 0; j < static_cast<int>(p.candidates.size()); ++j) {
      Mat2 c = p.innovation_covariance(j, j);
      c = 0.5 * (c + c.transpose());
      Mat2 inverse;
      if (!association::invert_spd2(c, &inverse)) continue;
      const Vec2 nu = range_bearing_innovation(p.measurements[i].z, p.candidates[j].z_hat);
      const double d2 = nu.dot(inverse * nu);
      if (d2 <= new_landmark_gate) r.near_any[i] = 1;
      if (d2 <= gate) r.pairs.push_back({d2, i, j});
    }
  return r;
}

TEST(IndividualGating, KeepsExactlyThePairsOfTheFullTest) {
  int kept = 0, near = 0;
  for (std::uint64_t seed = 1; seed <= 120; ++seed) {
    // Pose uncertainty from none to large (strongly correlated innovations), wide and narrow gates, and a
    // new-landmark gate on either side of the pairing gate.
    const double pose_scale = (seed % 4) * 0.5;
    const ProblemGeneratorOptions g{
        .landmarks = 80,
        .observations = 5 + static_cast<int>(seed % 12),
        .clutter = static_cast<int>(seed % 4),
        .seed = seed,
        .pose_sigma = Vec3(0.6, 0.6, 0.1) * pose_scale,
    };
    const AssociationProblem p = generate_association_problem(g).problem;
    const double gate = chi_square_quantile(seed % 2 ? 0.99 : 0.999999, 2);
    const double new_landmark_gate = chi_square_quantile(seed % 3 ? 0.95 : 0.9999999, 2);
    association::IndividualGating gating;
    AssociationStats stats;
    association::gate_individually(p, gate, new_landmark_gate, &gating, &stats);
    const Reference want = gate_every_pair(p, gate, new_landmark_gate);
    ASSERT_EQ(gating.pairs.size(), want.pairs.size()) << "seed " << seed;
    for (std::size_t k = 0; k < want.pairs.size(); ++k) {
      EXPECT_EQ(gating.pairs[k].measurement, want.pairs[k].measurement) << "seed " << seed;
      EXPECT_EQ(gating.pairs[k].candidate, want.pairs[k].candidate) << "seed " << seed;
      EXPECT_EQ(gating.pairs[k].d2, want.pairs[k].d2) << "seed " << seed;
    }
    EXPECT_EQ(gating.near_any, want.near_any) << "seed " << seed;
    EXPECT_EQ(stats.tests, static_cast<std::int64_t>(p.measurements.size() * p.candidates.size()));
    kept += static_cast<int>(want.pairs.size());
    near += static_cast<int>(std::count(want.near_any.begin(), want.near_any.end(), 1));
  }
  // The comparison has pairs and new-landmark decisions to compare.
  EXPECT_GT(kept, 500);
  EXPECT_GT(near, 500);
}

}  // namespace
}  // namespace arbor
