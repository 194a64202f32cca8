// Builds the interpretation-tree settings from the shared association options.
#ifndef ARBOR_VARIANTS_ASSOCIATION_TREE_SETTINGS_H_
#define ARBOR_VARIANTS_ASSOCIATION_TREE_SETTINGS_H_

#include "core/association/association_problem.h"
#include "core/math/chi_square.h"
#include "variants/association/tree_search.h"

namespace arbor::association {

// Joint tests beyond this many degrees of freedom (more than 64 pairings) compute the quantile directly.
inline constexpr int kJointGateMaxDof = 128;

inline TreeSettings make_tree_settings(const AssociationOptions& options, bool use_locality) {
  TreeSettings s;
  s.use_locality = use_locality;
  s.anchor_only = true;
  s.joint_gate = ChiSquareTable(options.gate_probability, kJointGateMaxDof);
  s.gate2 = chi_square_quantile(options.gate_probability, 2);
  s.binary_gate = chi_square_quantile(options.gate_probability, 1);
  s.new_landmark_gate = chi_square_quantile(options.new_landmark_probability, 2);
  s.max_hypotheses = options.max_hypotheses;
  s.max_work = options.max_work;
  s.accept_explained = options.accept_explained;
  s.widen_below = options.widen_below;
  s.pair_again_at_pose = options.pair_again_at_pose;
  return s;
}

}  // namespace arbor::association

#endif  // ARBOR_VARIANTS_ASSOCIATION_TREE_SETTINGS_H_
