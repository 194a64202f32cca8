// Unrestricted interpretation tree (Grimson 1990): every measurement may pair with any candidate that passes
// the unary and binary constraints. Exponential in m; kept as the baseline for the locality tree.
#ifndef ARBOR_VARIANTS_ASSOCIATION_INTERPRETATION_TREE_H_
#define ARBOR_VARIANTS_ASSOCIATION_INTERPRETATION_TREE_H_

#include <string_view>

#include "core/association/association_problem.h"
#include "variants/association/tree_strategy.h"

namespace arbor {

using InterpretationTree = TreeStrategy<false>;

static_assert(AssociationStrategy<InterpretationTree>);

}  // namespace arbor

#endif  // ARBOR_VARIANTS_ASSOCIATION_INTERPRETATION_TREE_H_
