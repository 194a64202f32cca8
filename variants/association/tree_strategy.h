// The interpretation-tree strategies as one template over the locality restriction: LocalityTree and the
// unrestricted InterpretationTree differ only in that flag (see locality_tree.h and interpretation_tree.h).
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
  static constexpr StrategyTraits kTraits{.in_filter = kRestrictToLocality, .locality_bound = kRestrictToLocality};

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

}  // namespace arbor

#endif  // ARBOR_VARIANTS_ASSOCIATION_TREE_STRATEGY_H_
