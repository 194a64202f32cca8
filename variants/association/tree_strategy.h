// The interpretation-tree strategies as one template over the locality restriction: LocalityTree and the
// unrestricted InterpretationTree differ only in that flag (both defined at the end of this file).
#ifndef ARBOR_VARIANTS_ASSOCIATION_TREE_STRATEGY_H_
#define ARBOR_VARIANTS_ASSOCIATION_TREE_STRATEGY_H_

#include <string_view>

#include "core/association/association_problem.h"
#include "variants/association/tree_search.h"
#include "variants/association/tree_settings.h"

namespace arbor {

template <bool kRestrictToLocality>
class TreeStrategy {
 public:
  using Scratch = association::TreeScratch;
  static constexpr std::string_view kName = kRestrictToLocality ? "locality" : "itree";
  // The unrestricted tree is exponential in m: a baseline for the locality tree, not a per-particle strategy.
  static constexpr StrategyTraits kTraits{
      .in_filter = kRestrictToLocality, .locality_bound = kRestrictToLocality, .reads_localities = kRestrictToLocality};

  explicit TreeStrategy(const AssociationOptions& options)
      : settings_(association::make_tree_settings(options, kRestrictToLocality)) {}
  // Per-particle use: the pose-free search, whose answer must also pass the joint test with the problem's own
  // predictions (so a coincidence elsewhere in the map cannot capture a tracking particle).
  void solve(const AssociationProblem& problem, Scratch& scratch, AssociationResult& result) const {
    association::solve_tree(problem, settings_, scratch, result);
  }
  // Relocalisation: the prior is not trusted (no prior check); returns the verified pose world_T_robot.
  bool solve_with_pose(const AssociationProblem& problem, Scratch& scratch, AssociationResult& result,
                       Pose2* world_T_robot) const {
    bool verified = false;
    association::solve_tree(problem, settings_, scratch, result, world_T_robot, &verified);
    return verified;
  }

 private:
  association::TreeSettings settings_;
};

// The unrestricted interpretation tree (Grimson 1990): every measurement may pair with any candidate that
// passes the unary and binary constraints. Exponential in m; kept as the baseline for the locality tree.
using InterpretationTree = TreeStrategy<false>;
static_assert(AssociationStrategy<InterpretationTree>);

// The locality interpretation tree (Grimson's tree with the locality restriction of Ge & Lewis 2006, ch. 9):
// pose-free association for relocalisation, loop closing and as a per-particle strategy.
// Once a measurement is paired with feature f (the anchor, the first pairing), the remaining measurements may
// pair only with features in f's locality (covisibility) set, or stay unpaired. Why the anchor's set rather
// than the union or the intersection over all paired features: the bound n((c+1)^m - 1)/c + 1 is derived
// from exactly c + 1 branches per level after the first pairing; a union grows to m c features and loses the
// bound (and linearity in n); an intersection keeps the bound but, with capped locality sets, drops true
// features that are not in each other's capped set. Measured on generated problems (n = 150, m = 8 + 2
// clutter, kidnapped): anchor 26/30 correct, intersection 25/30; TreeSettings::anchor_only selects it.
// Needs no pose prior: candidates' world positions and the measured points in the robot frame only. The
// best hypotheses (most pairings) are verified by a closed-form pose and a joint chi-square test.
using LocalityTree = TreeStrategy<true>;
static_assert(AssociationStrategy<LocalityTree>);

}  // namespace arbor

#endif  // ARBOR_VARIANTS_ASSOCIATION_TREE_STRATEGY_H_
