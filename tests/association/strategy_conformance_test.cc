// The strategy conformance suite: every strategy of the one list (variants/association/strategy_list.h) on
// generated problems, checked against what its traits promise. Like the map back ends' conformance suite, a
// new strategy is tested by adding it to the list.
#include <algorithm>
#include <numeric>
#include <random>
#include <string>

#include <gtest/gtest.h>

#include "tests/association/test_problems.h"
#include "variants/association/joint_compatibility.h"
#include "variants/association/problem_generator.h"
#include "variants/association/strategy_list.h"

namespace arbor {
namespace {

template <class List>
struct AsGtestTypes;
template <class... S>
struct AsGtestTypes<TypeList<S...>> {
  using type = ::testing::Types<S...>;
};

template <class S>
class StrategyConformance : public ::testing::Test {
 protected:
  // A generated problem that every strategy can solve: truth ids on the measurements and labels on the
  // candidates (known association reads them; the others do not), localities from nearest neighbours.
  static GeneratedProblem problem(std::uint64_t seed, int observations = 8, int clutter = 2) {
    const ProblemGeneratorOptions g{
        .landmarks = 40,
        .observations = observations,
        .clutter = clutter,
        .seed = seed,
        .density = 0.05,
    };
    GeneratedProblem gen = generate_association_problem(g);
    for (std::size_t k = 0; k < gen.truth.size(); ++k) gen.problem.measurements[k].truth_id = gen.truth[k];
    for (auto& c : gen.problem.candidates) c.truth_label = c.id;
    return gen;
  }
  static AssociationResult solve(const AssociationProblem& p) { return testing::solve_with<S>(p); }
};

// Cases named after the strategy (gtest names allow letters, digits and underscores).
struct StrategyName {
  template <class S>
  static std::string GetName(int) {
    std::string name(S::kName);
    std::replace(name.begin(), name.end(), '-', '_');
    return name;
  }
};

using AllStrategies = AsGtestTypes<AssociationStrategies>::type;
TYPED_TEST_SUITE(StrategyConformance, AllStrategies, StrategyName);

TYPED_TEST(StrategyConformance, AnswersOneDecisionPerMeasurementNamingACandidateOrNewOrSpurious) {
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    const GeneratedProblem gen = this->problem(seed);
    const AssociationResult r = this->solve(gen.problem);
    ASSERT_EQ(r.pairing.size(), gen.problem.measurements.size());
    for (const LandmarkId id : r.pairing) {
      const bool candidate = std::any_of(gen.problem.candidates.begin(), gen.problem.candidates.end(),
                                         [&](const auto& c) { return c.id == id; });
      EXPECT_TRUE(candidate || id == kNewLandmark || id == kSpurious) << "seed " << seed << ": " << id;
    }
  }
}

TYPED_TEST(StrategyConformance, TheAnswerDoesNotDependOnTheOrderOfTheMeasurements) {
  std::mt19937_64 rng(7);
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    const GeneratedProblem gen = this->problem(seed);
    const AssociationResult reference = this->solve(gen.problem);
    std::vector<int> perm(gen.problem.measurements.size());
    std::iota(perm.begin(), perm.end(), 0);
    std::shuffle(perm.begin(), perm.end(), rng);
    AssociationProblem shuffled = gen.problem;
    for (std::size_t k = 0; k < perm.size(); ++k) shuffled.measurements[k] = gen.problem.measurements[perm[k]];
    const AssociationResult r = this->solve(shuffled);
    for (std::size_t k = 0; k < perm.size(); ++k)
      EXPECT_EQ(r.pairing[k], reference.pairing[perm[k]]) << "seed " << seed << ", measurement " << perm[k];
  }
}

TYPED_TEST(StrategyConformance, NeverPairsTwoMeasurementsWithOneLandmarkWhereItPromises) {
  if constexpr (!TypeParam::kTraits.mutually_exclusive) GTEST_SKIP() << "makes no such promise";
  for (std::uint64_t seed = 1; seed <= 30; ++seed) {
    const GeneratedProblem gen = this->problem(seed, 10, 4);
    std::vector<LandmarkId> paired;
    for (const LandmarkId id : this->solve(gen.problem).pairing)
      if (id >= 0) paired.push_back(id);
    std::sort(paired.begin(), paired.end());
    EXPECT_TRUE(std::adjacent_find(paired.begin(), paired.end()) == paired.end()) << "seed " << seed;
  }
}

TYPED_TEST(StrategyConformance, IsJointlyCompatibleWhereItPromises) {
  if constexpr (!TypeParam::kTraits.jointly_compatible) GTEST_SKIP() << "makes no such promise";
  const double gate = AssociationOptions{}.gate_probability;
  for (std::uint64_t seed = 1; seed <= 40; ++seed) {
    const GeneratedProblem gen = this->problem(seed, 10, 4);
    const auto test = association::joint_compatibility(gen.problem, this->solve(gen.problem).pairing, gate);
    EXPECT_TRUE(test.well_formed && test.compatible) << "seed " << seed << ": d2 " << test.d2 << ", dof " << test.dof;
  }
}

TYPED_TEST(StrategyConformance, StaysWithinTheLocalityBoundWhereItPromises) {
  if constexpr (!TypeParam::kTraits.locality_bound) GTEST_SKIP() << "makes no such promise";
  for (std::uint64_t seed = 1; seed <= 30; ++seed) {
    const GeneratedProblem gen = this->problem(seed, 2 + static_cast<int>(seed % 5), 1);
    int c = 0;
    for (const auto& cand : gen.problem.candidates) c = std::max(c, cand.locality.size());
    const int n = static_cast<int>(gen.problem.candidates.size());
    const int m = static_cast<int>(gen.problem.measurements.size());
    EXPECT_LE(static_cast<double>(this->solve(gen.problem).stats.hypotheses),
              association::locality_hypothesis_bound(n, m, c)) << "seed " << seed;
  }
}

// In the filter the engine keeps the candidates' locality sets only for a strategy that says it reads them
// (StrategyTraits::reads_localities); any other strategy must answer the same without them.
TYPED_TEST(StrategyConformance, IgnoresLocalitiesUnlessItReadsThem) {
  if constexpr (TypeParam::kTraits.reads_localities) GTEST_SKIP() << "reads them";
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    const GeneratedProblem gen = this->problem(seed);
    AssociationProblem without = gen.problem;
    for (auto& c : without.candidates) c.locality = LocalitySet();
    EXPECT_EQ(this->solve(without).pairing, this->solve(gen.problem).pairing) << "seed " << seed;
  }
}

// A strategy that knows the truth finds it; the others find most of it on these well-separated problems.
TYPED_TEST(StrategyConformance, FindsMostOfTheTruePairings) {
  AssociationCounts total;
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    const GeneratedProblem gen = this->problem(seed);
    total += score_against_truth(this->solve(gen.problem).pairing, gen.truth);
  }
  ASSERT_TRUE(total.f1().has_value());
  EXPECT_GT(*total.f1(), TypeParam::kTraits.uses_ground_truth ? 0.99 : 0.8) << TypeParam::kName;
}

}  // namespace
}  // namespace arbor
