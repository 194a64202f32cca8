// Builds the interpretation-tree settings from the shared association options.
#ifndef ARBOR_VARIANTS_ASSOCIATION_TREE_SETTINGS_H_
#define ARBOR_VARIANTS_ASSOCIATION_TREE_SETTINGS_H_

#include "core/association/association_problem.h"
#include "core/math/chi_square.h"
#include "variants/association/tree_search.h"

namespace arbor::association {

inline TreeSettings make_tree_settings(const AssociationOptions& options, bool use_locality) {
  TreeSettings s;
  s.use_locality = use_locality;
  s.anchor_only = true;
  s.gate_probability = options.gate_probability;
  s.gate2 = chi_square_quantile(options.gate_probability, 2);
  s.binary_gate = chi_square_quantile(options.gate_probability, 1);
  s.new_landmark_gate = chi_square_quantile(options.new_landmark_probability, 2);
  s.max_hypotheses = options.max_hypotheses;
  return s;
}

}  // namespace arbor::association

#endif  // ARBOR_VARIANTS_ASSOCIATION_TREE_SETTINGS_H_
