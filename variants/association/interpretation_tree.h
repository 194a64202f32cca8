// Unrestricted interpretation tree (Grimson 1990): every measurement may pair with any candidate that passes
// the unary and binary constraints. Exponential in m; kept as the baseline for the locality tree.
#ifndef ARBOR_VARIANTS_ASSOCIATION_INTERPRETATION_TREE_H_
#define ARBOR_VARIANTS_ASSOCIATION_INTERPRETATION_TREE_H_

#include <string_view>

#include "core/association/association_problem.h"
#include "variants/association/tree_search.h"
#include "variants/association/tree_settings.h"

namespace arbor {

class InterpretationTree {
 public:
  using Scratch = association::TreeScratch;
  static constexpr std::string_view kName = "itree";
  static constexpr bool kUsesGroundTruth = false;

  explicit InterpretationTree(const AssociationOptions& options)
      : settings_(association::make_tree_settings(options, false)) {}
  void solve(const AssociationProblem& problem, Scratch& scratch, AssociationResult& result) const {
    association::solve_tree(problem, settings_, scratch, result);
  }
  bool solve_with_pose(const AssociationProblem& problem, Scratch& scratch, AssociationResult& result,
                       Pose2* world_T_robot) const {
    bool verified = false;
    association::solve_tree(problem, settings_, scratch, result, world_T_robot, &verified);
    return verified;
  }

 private:
  association::TreeSettings settings_;
};

static_assert(AssociationStrategy<InterpretationTree>);

}  // namespace arbor

#endif  // ARBOR_VARIANTS_ASSOCIATION_INTERPRETATION_TREE_H_
