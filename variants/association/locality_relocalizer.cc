#include "variants/association/locality_relocalizer.h"

#include <algorithm>

#include "variants/association/tree_strategy.h"

namespace arbor {

Relocalizer make_locality_relocalizer(const AssociationOptions& options) {
  return [tree = LocalityTree(options)](const AssociationProblem& problem, Pose2* world_T_robot) {
    LocalityTree::Scratch scratch;
    AssociationResult result;
    if (!tree.solve_with_pose(problem, scratch, result, world_T_robot)) return 0;
    return static_cast<int>(std::count_if(result.pairing.begin(), result.pairing.end(), [](LandmarkId id) { return id >= 0; }));
  };
}

}  // namespace arbor
