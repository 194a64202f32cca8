// JCBB: joint compatibility of every answer, equality with NN where the problem is unambiguous, the
// ambiguous case NN gets wrong, order invariance and the search budget.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <numeric>
#include <random>

#include <gtest/gtest.h>

#include <Eigen/LU>

#include "core/math/chi_square.h"
#include "tests/association/test_problems.h"
#include "variants/association/association_common.h"
#include "variants/association/jcbb.h"
#include "variants/association/joint_information.h"
#include "variants/association/joint_compatibility.h"
#include "variants/association/nearest_neighbor.h"
#include "variants/association/problem_generator.h"

namespace arbor {
namespace {

int pairings(const AssociationResult& r) {
  return static_cast<int>(std::count_if(r.pairing.begin(), r.pairing.end(), [](LandmarkId id) { return id >= 0; }));
}

// The information form's 3x3 solve must give Eigen's PartialPivLU answer to the bit, or JCBB's distances,
// and with them its tie-breaks and every run's output, would change: random systems of the form the distance
// solves (I + P J), general ones that need row swaps at both steps, and ones with a zero column.
TEST(Jcbb, ThreeByThreeSolveIsEigensPartialPivotLuToTheBit) {
  std::mt19937_64 rng(11);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::uniform_int_distribution<int> kind(0, 3);
  int swapped = 0;
  for (int trial = 0; trial < 200000; ++trial) {
    Mat3 A;
    for (int i = 0; i < 9; ++i) A(i) = normal(rng) * std::pow(10.0, normal(rng));
    switch (kind(rng)) {
      case 0: {  // the distance's own form
        Mat3 G, H;
        for (int i = 0; i < 9; ++i) G(i) = normal(rng), H(i) = normal(rng);
        A = Mat3::Identity() + (G * G.transpose()) * (H * H.transpose());
        break;
      }
      case 1: A.col(trial % 3).setZero(); break;
      case 2: A.row(0) *= 1e-3; break;  // the first pivot comes from below
      default: break;
    }
    const Vec3 y(normal(rng), normal(rng), normal(rng));
    const Eigen::PartialPivLU<Mat3> lu(A);
    swapped += lu.permutationP().indices() != Eigen::Vector3i(0, 1, 2);
    const Vec3 expected = lu.solve(y);
    const Vec3 got = association::solve3_partial_pivot(A, y);
    for (int i = 0; i < 3; ++i) {
      if (std::isnan(expected(i))) {
        ASSERT_TRUE(std::isnan(got(i))) << "trial " << trial;
      } else {
        ASSERT_EQ(std::memcmp(&expected(i), &got(i), sizeof(double)), 0)
            << "trial " << trial << " component " << i << ": " << expected(i) << " vs " << got(i);
      }
    }
  }
  EXPECT_GT(swapped, 50000);  // the pivoting paths ran
}

TEST(Jcbb, NeverReturnsAJointlyIncompatibleHypothesis) {
  int paired_total = 0;
  for (std::uint64_t seed = 1; seed <= 120; ++seed) {
    ProblemGeneratorOptions g{
        .landmarks = 40 + static_cast<int>(seed % 5) * 30,
        .observations = 5 + static_cast<int>(seed % 4) * 4,
        .clutter = static_cast<int>(seed % 6),
        .seed = seed,
        .density = 0.05,  // crowded: many individually compatible pairs
        .pose_sigma = Vec3(0.4, 0.4, 0.08),  // strong pose coupling
    };
    const GeneratedProblem gen = generate_association_problem(g);
    for (double prob : {0.95, 0.99}) {
      AssociationOptions o;
      o.gate_probability = prob;
      const AssociationResult r = testing::solve_with<Jcbb>(gen.problem, o);
      ASSERT_EQ(r.pairing.size(), gen.problem.measurements.size());
      const auto test = association::joint_compatibility(gen.problem, r.pairing, prob);
      EXPECT_TRUE(test.well_formed) << "seed " << seed;
      EXPECT_TRUE(test.compatible) << "seed " << seed << " d2 " << test.d2 << " dof " << test.dof;
      paired_total += pairings(r);
    }
  }
  EXPECT_GT(paired_total, 1000);  // the property is not satisfied vacuously
}

TEST(Jcbb, BudgetReturnsTheBestSoFarAndSaysSo) {
  ProblemGeneratorOptions g{
      .landmarks = 300,
      .observations = 25,
      .clutter = 10,
      .seed = 7,
      .density = 0.08,
      .pose_sigma = Vec3(0.5, 0.5, 0.1),
  };
  const GeneratedProblem gen = generate_association_problem(g);
  AssociationOptions o;
  o.max_hypotheses = 30;
  const AssociationResult r = testing::solve_with<Jcbb>(gen.problem, o);
  EXPECT_TRUE(r.stats.budget_exhausted);
  EXPECT_LE(r.stats.hypotheses, 30);
  EXPECT_TRUE(association::joint_compatibility(gen.problem, r.pairing, o.gate_probability).compatible);
  const AssociationResult full = testing::solve_with<Jcbb>(gen.problem);
  EXPECT_FALSE(full.stats.budget_exhausted);
  EXPECT_GE(pairings(full), pairings(r));
}

// DESIGN.md §4: with P = 0, where each measurement has at most one individually compatible landmark and the sum
// of the individual distances passes chi2(2k), JCBB's answer equals nearest neighbour's.
TEST(Jcbb, EqualsNearestNeighborWithZeroPoseCovarianceWhenUnambiguous) {
  const double gate = chi_square_quantile(0.99, 2);
  int checked = 0;
  for (std::uint64_t seed = 1; seed <= 300; ++seed) {
    const ProblemGeneratorOptions g{
        .landmarks = 60,
        .observations = 4 + static_cast<int>(seed % 10),
        .clutter = static_cast<int>(seed % 3),
        .seed = seed,
        .pose_sigma = Vec3::Zero(),
    };
    const GeneratedProblem gen = generate_association_problem(g);
    const AssociationProblem& p = gen.problem;
    association::IndividualGating gating;
    AssociationStats stats;
    association::gate_individually(p, gate, gate, &gating, &stats);
    bool unambiguous = true;
    for (std::size_t i = 0; i + 1 < gating.first.size(); ++i) unambiguous &= gating.first[i + 1] - gating.first[i] <= 1;
    if (!unambiguous) continue;
    const AssociationResult nn = testing::solve_with<NearestNeighbor>(p);
    // "That sum passes" must hold for every subset, not only for the whole: chi2(2k) grows more slowly than
    // the sum of the k largest individual distances can, so a prefix of NN's answer may fail its joint test
    // although the whole passes, and JCBB (which tests every prefix, Neira & Tardós 2001) then stops short.
    // For P = 0 the worst subset of size k holds the k largest distances.
    std::vector<double> d2;
    for (std::size_t i = 0; i < nn.pairing.size(); ++i)
      for (int e = gating.first[i]; e < gating.first[i + 1]; ++e)
        if (p.candidates[gating.pairs[e].candidate].id == nn.pairing[i]) d2.push_back(gating.pairs[e].d2);
    std::sort(d2.rbegin(), d2.rend());
    double sum = 0.0;
    bool every_subset_passes = true;
    for (std::size_t k = 0; k < d2.size(); ++k) {
      sum += d2[k];
      every_subset_passes &= sum <= chi_square_quantile(0.99, 2 * static_cast<int>(k + 1));
    }
    if (!every_subset_passes) continue;
    ++checked;
    const AssociationResult jcbb = testing::solve_with<Jcbb>(p);
    EXPECT_EQ(jcbb.pairing, nn.pairing) << "seed " << seed;
  }
  EXPECT_GE(checked, 50);
}

// Two landmarks at the same range, bearings +-0.1 rad, heading uncertain (sigma 0.15 rad). The robot's heading
// is off by 0.2 rad, so both are seen 0.2 rad clockwise: z1 (the view of A) lands exactly on B's prediction.
// NN takes z1 -> B (distance 0) and is left with z2 -> A: a crossed pairing whose innovations disagree by
// 0.4 rad although the pose error moves both bearings together. JCBB finds z1 -> A, z2 -> B: both innovations
// are the same common shift, which the pose covariance explains.
TEST(Jcbb, PicksTheJointlyConsistentPairingWhereNearestNeighborDoesNot) {
  const Pose2 prior;
  const Mat2 R = Vec2(0.05 * 0.05, 0.01 * 0.01).asDiagonal();
  const Mat2 sigma = Mat2::Identity() * 0.01 * 0.01;
  AssociationProblem p;
  p.R = R;
  p.P = Vec3(0.01 * 0.01, 0.01 * 0.01, 0.15 * 0.15).asDiagonal();
  const double r = 10.0;
  p.candidates.push_back(testing::make_candidate(4, prior, r * Vec2(std::cos(0.1), std::sin(0.1)), sigma, R));
  p.candidates.push_back(testing::make_candidate(9, prior, r * Vec2(std::cos(-0.1), std::sin(-0.1)), sigma, R));
  p.measurements.push_back(testing::make_measurement(r, -0.1));  // A seen 0.2 rad clockwise
  p.measurements.push_back(testing::make_measurement(r, -0.3));  // B seen 0.2 rad clockwise

  const AssociationResult nn = testing::solve_with<NearestNeighbor>(p);
  EXPECT_EQ(nn.pairing, (std::vector<LandmarkId>{9, 4}));
  EXPECT_FALSE(association::joint_compatibility(p, nn.pairing, 0.99).compatible);

  const AssociationResult jcbb = testing::solve_with<Jcbb>(p);
  EXPECT_EQ(jcbb.pairing, (std::vector<LandmarkId>{4, 9}));
  EXPECT_TRUE(association::joint_compatibility(p, jcbb.pairing, 0.99).compatible);
}

// The correlation a joint covariance carries and a particle's problem cannot (EKF-SLAM's landmark-landmark
// terms): two landmarks whose ranges are 99 % correlated, as two landmarks mapped from one uncertain pose are.
// Each measurement lies two standard deviations out in range, inside its own gate, but one long and the other
// short, which a common error cannot produce. Nearest neighbour, which tests each pair alone, pairs both;
// JCBB pairs one of them only.
TEST(Jcbb, RejectsPairingsThatAreIndividuallyButNotJointlyCompatible) {
  const double sigma_range = 0.1, sigma_bearing = 0.01, rho = 0.99;
  AssociationProblem p;
  p.R = Vec2(sigma_range * sigma_range, sigma_bearing * sigma_bearing).asDiagonal();
  const Pose2 pose;
  p.candidates.push_back(testing::make_candidate(4, pose, 10.0 * Vec2(std::cos(0.5), std::sin(0.5)), Mat2::Zero(), p.R));
  p.candidates.push_back(testing::make_candidate(9, pose, 10.0 * Vec2(std::cos(-0.5), std::sin(-0.5)), Mat2::Zero(), p.R));
  p.joint_covariance = Eigen::MatrixXd::Zero(4, 4);
  for (int i = 0; i < 2; ++i) {
    p.joint_covariance.block<2, 2>(2 * i, 2 * i) = p.R;
    p.candidates[i].H_pose.setZero();
  }
  p.joint_covariance(0, 2) = p.joint_covariance(2, 0) = rho * sigma_range * sigma_range;
  p.measurements.push_back(testing::make_measurement(10.0 + 2.0 * sigma_range, 0.5));
  p.measurements.push_back(testing::make_measurement(10.0 - 2.0 * sigma_range, -0.5));

  EXPECT_TRUE(association::joint_compatibility(p, {4, kNewLandmark}, 0.99).compatible);
  EXPECT_TRUE(association::joint_compatibility(p, {kNewLandmark, 9}, 0.99).compatible);
  EXPECT_FALSE(association::joint_compatibility(p, {4, 9}, 0.99).compatible);
  EXPECT_EQ(testing::solve_with<NearestNeighbor>(p).pairing, (std::vector<LandmarkId>{4, 9}));

  const AssociationResult jcbb = testing::solve_with<Jcbb>(p);
  EXPECT_EQ(pairings(jcbb), 1);
  EXPECT_TRUE(association::joint_compatibility(p, jcbb.pairing, 0.99).compatible);
  // Both long (a common error of the map's frame), the same pair is jointly compatible and JCBB takes it.
  p.measurements[1] = testing::make_measurement(10.0 + 2.0 * sigma_range, -0.5);
  EXPECT_EQ(testing::solve_with<Jcbb>(p).pairing, (std::vector<LandmarkId>{4, 9}));
}

// Permuting the observations and the predictions (each prediction keeps its Jacobians) changes no answer.
TEST(Jcbb, AnswerDoesNotDependOnInputOrder) {
  for (std::uint64_t seed = 1; seed <= 40; ++seed) {
    const ProblemGeneratorOptions g{.landmarks = 80, .observations = 12, .clutter = 4, .seed = seed, .density = 0.05};
    const GeneratedProblem gen = generate_association_problem(g);
    const AssociationResult jcbb = testing::solve_with<Jcbb>(gen.problem);
    const AssociationResult nn = testing::solve_with<NearestNeighbor>(gen.problem);
    std::mt19937 rng(static_cast<unsigned>(seed));
    AssociationProblem shuffled = gen.problem;
    std::vector<int> perm(shuffled.measurements.size());
    std::iota(perm.begin(), perm.end(), 0);
    std::shuffle(perm.begin(), perm.end(), rng);
    for (std::size_t k = 0; k < perm.size(); ++k) shuffled.measurements[k] = gen.problem.measurements[perm[k]];
    std::shuffle(shuffled.candidates.begin(), shuffled.candidates.end(), rng);
    const AssociationResult jcbb2 = testing::solve_with<Jcbb>(shuffled);
    const AssociationResult nn2 = testing::solve_with<NearestNeighbor>(shuffled);
    for (std::size_t k = 0; k < perm.size(); ++k) {
      EXPECT_EQ(jcbb2.pairing[k], jcbb.pairing[perm[k]]) << "seed " << seed;
      EXPECT_EQ(nn2.pairing[k], nn.pairing[perm[k]]) << "seed " << seed;
    }
  }
}

TEST(Jcbb, EmptyProblemsAreFine) {
  AssociationProblem p;
  EXPECT_TRUE(testing::solve_with<Jcbb>(p).pairing.empty());
  p.measurements.push_back(testing::make_measurement(5.0, 0.3));
  EXPECT_EQ(testing::solve_with<Jcbb>(p).pairing, (std::vector<LandmarkId>{kNewLandmark}));
}

}  // namespace
}  // namespace arbor
